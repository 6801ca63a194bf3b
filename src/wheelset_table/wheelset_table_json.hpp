#pragma once
// The wheelset table's nodes as its file writes them (wheelset_table_file.cpp), for a build's
// runner that moves blocks of nodes between processes.
#include <string>
#include <vector>

#include "railcontact/wheelset_table.hpp"

namespace railcontact::detail {

// Wheelset-table nodes as the table file writes them (a JSON list, an exact round trip), and back:
// how a build's runner moves a block of nodes.
std::string wheelset_table_nodes_json(const std::vector<WheelsetTableNode>& nodes);
std::vector<WheelsetTableNode> parse_wheelset_table_nodes(const std::string& text);

}  // namespace railcontact::detail
