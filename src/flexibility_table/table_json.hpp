#pragma once
// What the table files (flexibility table, wheelset table) share beyond the strict JSON reader
// (support/strict_json.hpp): profile fingerprints and track parameters as JSON, and the flexibility
// table's nodes as its file writes them.
#include <nlohmann/json.hpp>
#include <string>

#include "railcontact/flexibility_table.hpp"
#include "railcontact/geometry.hpp"
#include "support/strict_json.hpp"

namespace railcontact::detail {

FileFingerprint read_fingerprint(StrictJsonReader& parent, const std::string& key);
nlohmann::json fingerprint_json(const FileFingerprint& fingerprint);
TrackWheelsetParameters read_track_parameters(StrictJsonReader& parent, const std::string& key);
nlohmann::json track_parameters_json(const TrackWheelsetParameters& track);

// One flexibility-table node as the table file writes it (JSON, an exact round trip), and back
// (throws Error naming nodes[index] on malformed text): how a build's runner moves nodes.
std::string flexibility_table_node_json(const FlexibilityTableNode& node);
FlexibilityTableNode parse_flexibility_table_node(const std::string& text, std::size_t index);

}  // namespace railcontact::detail
