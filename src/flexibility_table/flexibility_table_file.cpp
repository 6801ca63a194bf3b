// The flexibility-table file (docs/FLEXTABLE.md §3): one JSON object, every field documented;
// read strictly (unknown keys, missing keys and wrong types are errors naming the key).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"
#include "railcontact/flexibility_table.hpp"
#include "support/file_fingerprint.hpp"
#include "flexibility_table/table_size.hpp"
#include "flexibility_table/table_json.hpp"

namespace railcontact {
namespace {

using nlohmann::json;
using detail::StrictJsonReader;
constexpr const char* kKind = "flexibility table";  // messages read "flexibility table FILE: …"

// A reader of this file's objects.
StrictJsonReader reader(const json& object, const std::string& path, const std::string& source) {
  return StrictJsonReader(object, path, source, kKind);
}

json parse_json(const std::string& text, const std::string& source) {
  return detail::parse_strict_json(text, source, kKind);
}

constexpr const char* kFormat = "railcontact flexibility table";
// Version 2 records the recipe's flexibility coarsening; version-1 tables (built on the full patch,
// coarsening 1) are still read. Version 3 records the contact reference, version 4 the nH-FastSim
// recipe (kNhFastSimRecipe).
constexpr int kFormatVersion = 5;  // 5: each solved node's creepage_coupling (older: none)
// The largest table file read (a 100 × 20 grid is about 1 MB).
constexpr std::uintmax_t kMaxTableFileBytes = 256u << 20;  // 256 MiB

// Doubles are written with 17 significant digits (nlohmann's default): a round trip is exact.
json number_or_null(double value, bool solved) { return solved ? json(value) : json(nullptr); }

json node_json(const FlexibilityTableNode& n) {
  const bool s = n.status == FlexibilityNodeStatus::solved;
  return json{{"y_m", n.y_m},
              {"vertical_load_N", n.vertical_load_N},
              {"status", std::string(flexibility_node_status_name(n.status))},
              {"message", n.message},
              {"L1_m_per_Pa", number_or_null(n.flexibility.L1, s)},
              {"L2_m_per_Pa", number_or_null(n.flexibility.L2, s)},
              {"L3_m_per_Pa", number_or_null(n.flexibility.L3, s)},
              {"f11_N", number_or_null(n.f11_N, s)},
              {"f22_N", number_or_null(n.f22_N, s)},
              {"f23_Nm", number_or_null(n.f23_Nm, s)},
              {"creepage_coupling",
               s ? json{{"xi_per_eta", n.coupling.xi_per_eta},
                        {"xi_per_phi_m", n.coupling.xi_per_phi_m},
                        {"eta_per_xi", n.coupling.eta_per_xi},
                        {"eta_per_phi_m", n.coupling.eta_per_phi_m}}
                 : json(nullptr)},
              {"normal_force_N", number_or_null(n.normal_force_N, s)},
              {"contact_angle_rad", number_or_null(n.contact_angle_rad, s)},
              {"spin_per_m", number_or_null(n.spin_per_m, s)},
              {"area_m2", number_or_null(n.area_m2, s)},
              {"elements_in_contact", s ? json(n.elements_in_contact) : json(nullptr)}};
}

FlexibilityTableNode read_node(const json& item, std::size_t index, const std::string& source) {
  StrictJsonReader r = reader(item, fmt::format("nodes[{}]", index), source);
  FlexibilityTableNode n;
  n.y_m = r.number("y_m");
  n.vertical_load_N = r.number("vertical_load_N");
  const std::string status = r.string("status");
  n.message = r.string("message");
  if (status == "solved") n.status = FlexibilityNodeStatus::solved;
  else if (status == "several-patches") n.status = FlexibilityNodeStatus::several_patches;
  else if (status == "failed") n.status = FlexibilityNodeStatus::failed;
  else r.fail(fmt::format("{} must be \"solved\", \"several-patches\" or \"failed\" (got \"{}\")", r.qualified("status"), printable_excerpt(status)));
  static const char* const kValues[] = {"L1_m_per_Pa", "L2_m_per_Pa", "L3_m_per_Pa", "f11_N", "f22_N", "f23_Nm",
                                        "normal_force_N", "contact_angle_rad", "spin_per_m", "area_m2",
                                        "elements_in_contact"};
  // Format 5 and later: each node's creepage coupling (absent in older tables: none).
  const bool has_coupling = r.has("creepage_coupling");
  if (n.status != FlexibilityNodeStatus::solved) {
    for (const char* key : kValues)
      if (!r.get(key).is_null()) r.fail(fmt::format("{} must be null: the node is not solved", r.qualified(key)));
    if (has_coupling && !r.get("creepage_coupling").is_null())
      r.fail(fmt::format("{} must be null: the node is not solved", r.qualified("creepage_coupling")));
    r.finish();
    return n;
  }
  if (has_coupling) {
    StrictJsonReader c = r.child("creepage_coupling");
    n.coupling = {c.number("xi_per_eta"), c.number("xi_per_phi_m"), c.number("eta_per_xi"), c.number("eta_per_phi_m")};
    c.finish();
  }
  n.flexibility = {r.number("L1_m_per_Pa"), r.number("L2_m_per_Pa"), r.number("L3_m_per_Pa")};
  n.f11_N = r.number("f11_N");
  n.f22_N = r.number("f22_N");
  n.f23_Nm = r.number("f23_Nm");
  n.normal_force_N = r.number("normal_force_N");
  n.contact_angle_rad = r.number("contact_angle_rad");
  n.spin_per_m = r.number("spin_per_m");
  n.area_m2 = r.number("area_m2");
  n.elements_in_contact = r.count("elements_in_contact");
  r.finish();
  return n;
}

// "format" must name a flexibility table; returns "format_version" (1 to kFormatVersion).
int read_format_version(StrictJsonReader& r, const json& root) {
  if (!root.contains("format") || !root["format"].is_string() || root["format"].get<std::string>() != kFormat)
    r.fail(fmt::format("not a flexibility table (the key 'format' must be \"{}\")", kFormat));
  r.get("format");
  const json& version = r.get("format_version");
  if (!version.is_number_integer() || version.get<int>() < 1 || version.get<int>() > kFormatVersion)
    r.fail(fmt::format("format_version {} is not supported (this railcontact reads version {})", detail::quoted_json_value(version), kFormatVersion));
  return version.get<int>();
}

// The recipe of the table: version, profiles (file and hash), track, material, mesh size,
// collocation offset, flexibility coarsening (format version 2), the nH-FastSim recipe (format
// version 4), the match of the flexibilities (term by term) and the contact reference (format
// version 3).
FlexibilityTableMetadata read_metadata(StrictJsonReader& r, int version) {
  FlexibilityTableMetadata m;
  m.railcontact_version = r.string("railcontact_version");
  m.created_utc = r.string("created_utc");
  {
    StrictJsonReader profiles = r.child("profiles");
    m.wheel_profile = detail::read_fingerprint(profiles, "wheel");
    m.rail_profile = detail::read_fingerprint(profiles, "rail");
    profiles.finish();
  }
  m.track = detail::read_track_parameters(r, "track");
  {
    StrictJsonReader material = r.child("material");
    m.material.youngs_modulus_Pa = material.number("youngs_modulus_Pa");
    m.material.poisson_ratio = material.number("poisson_ratio");
    material.finish();
  }
  const std::size_t elements = r.count("target_elements");
  if (elements > static_cast<std::size_t>(std::numeric_limits<int>::max())) r.fail("target_elements is too large");
  m.target_elements = static_cast<int>(elements);
  m.collocation_offset = r.number("collocation_offset");
  m.flexibility_coarsening = 1;  // format version 1: K2 of the patch itself
  if (version >= 2) {
    const std::size_t coarsening = r.count("flexibility_coarsening");
    if (coarsening > static_cast<std::size_t>(kMaximumCoarsening))
      r.fail(fmt::format("flexibility_coarsening {} must lie in [0, {}]", coarsening, kMaximumCoarsening));
    m.flexibility_coarsening = static_cast<int>(coarsening);
  }
  m.nh_fastsim_recipe = 0;  // format versions 1 to 3: recipe 1 or 2, not recorded
  if (version >= 4) {
    const std::size_t recipe = r.count("nh_fastsim_recipe");
    if (recipe > static_cast<std::size_t>(kNhFastSimRecipe))
      r.fail(fmt::format("nh_fastsim_recipe {} must lie in [0, {}] (0: not recorded; a newer railcontact's table?)", recipe,
                         kNhFastSimRecipe));
    m.nh_fastsim_recipe = static_cast<int>(recipe);
  }
  if (r.string("flexibility_match") != "term-by-term") r.fail("flexibility_match must be \"term-by-term\"");
  m.contact_reference = ContactReference::first_touch;  // format versions 1 and 2
  if (version >= 3) {
    const std::string reference = r.string("contact_reference");
    if (reference != "smooth" && reference != "first-touch")
      r.fail(fmt::format("contact_reference \"{}\" must be \"smooth\" or \"first-touch\"", reference));
    m.contact_reference = parse_contact_reference(reference);
  }
  return m;
}

// The contact jumps, each naming an interval of the y grid by its index and its two y values.
std::vector<ContactJump> read_jumps(StrictJsonReader& r, const std::vector<double>& y) {
  std::vector<ContactJump> jumps;
  const json& jump_list = r.array("contact_jumps");
  for (std::size_t k = 0; k < jump_list.size(); ++k) {
    StrictJsonReader j = r.item(jump_list[k], fmt::format("contact_jumps[{}]", k));
    ContactJump jump;
    jump.interval = j.count("interval");
    const double left = j.number("y_left_m"), right = j.number("y_right_m");
    jump.y_rail_left_m = j.number("y_rail_left_m");
    jump.y_rail_right_m = j.number("y_rail_right_m");
    j.finish();
    // interval < y.size() - 1, not interval + 1 < y.size(): 18446744073709551615 + 1 wraps to 0.
    if (y.size() < 2 || jump.interval >= y.size() - 1 || y[jump.interval] != left || y[jump.interval + 1] != right)
      j.fail(fmt::format("contact_jumps[{}] does not name an interval of y_m", k));
    jumps.push_back(jump);
  }
  return jumps;
}

std::vector<FlexibilityTableNode> read_nodes(StrictJsonReader& r, const std::string& source) {
  std::vector<FlexibilityTableNode> nodes;
  const json& node_list = r.array("nodes");
  for (std::size_t k = 0; k < node_list.size(); ++k) nodes.push_back(read_node(node_list[k], k, source));
  return nodes;
}

}  // namespace

namespace detail {
std::string flexibility_table_node_json(const FlexibilityTableNode& node) { return node_json(node).dump(); }
FlexibilityTableNode parse_flexibility_table_node(const std::string& text, std::size_t index) {
  return read_node(parse_json(text, "flexibility table node"), index, "flexibility table node");
}
}  // namespace detail

std::string flexibility_table_json(const FlexibilityTable& table) {
  const FlexibilityTableMetadata& m = table.metadata();
  const TrackWheelsetParameters& t = m.track;
  json nodes = json::array();
  for (const FlexibilityTableNode& n : table.nodes()) nodes.push_back(node_json(n));
  json jumps = json::array();
  for (const ContactJump& j : table.contact_jumps())
    jumps.push_back({{"interval", j.interval},
                     {"y_left_m", table.y_m()[j.interval]},
                     {"y_right_m", table.y_m()[j.interval + 1]},
                     {"y_rail_left_m", j.y_rail_left_m},
                     {"y_rail_right_m", j.y_rail_right_m}});
  const json out = {
      {"format", kFormat},
      {"format_version", kFormatVersion},
      {"railcontact_version", m.railcontact_version},
      {"created_utc", m.created_utc},
      {"profiles",
       {{"wheel", detail::fingerprint_json(m.wheel_profile)}, {"rail", detail::fingerprint_json(m.rail_profile)}}},
      {"track", detail::track_parameters_json(t)},
      {"material", {{"youngs_modulus_Pa", m.material.youngs_modulus_Pa}, {"poisson_ratio", m.material.poisson_ratio}}},
      {"target_elements", m.target_elements},
      {"collocation_offset", m.collocation_offset},
      {"flexibility_coarsening", m.flexibility_coarsening},
      {"nh_fastsim_recipe", m.nh_fastsim_recipe},
      {"flexibility_match", "term-by-term"},
      {"contact_reference", contact_reference_name(m.contact_reference)},
      {"y_m", table.y_m()},
      {"vertical_load_N", table.vertical_loads_N()},
      {"contact_jumps", jumps},
      {"nodes", nodes}};
  return out.dump(1);
}

FlexibilityTable parse_flexibility_table(const std::string& text, const std::string& source) {
  const json root = parse_json(text, source);
  StrictJsonReader r = reader(root, "", source);
  const int version = read_format_version(r, root);
  FlexibilityTableMetadata m = read_metadata(r, version);
  std::vector<double> y = r.numbers("y_m");
  std::vector<double> loads = r.numbers("vertical_load_N");
  try {
    check_table_size(y.size(), loads.size());  // before the nodes are read
  } catch (const Error& e) {
    r.fail(std::string(e.what()).substr(std::string_view("flexibility table: ").size()));
  }
  std::vector<ContactJump> jumps = read_jumps(r, y);
  std::vector<FlexibilityTableNode> nodes = read_nodes(r, source);
  r.finish();
  try {
    FlexibilityTable table(std::move(m), std::move(y), std::move(loads), std::move(nodes), std::move(jumps));
    table.set_source(source);
    return table;
  } catch (const Error& e) {
    // "flexibility table: …" from the constructor, with the file named.
    const std::string what = e.what();
    const std::string prefix = "flexibility table: ";
    throw Error(fmt::format("flexibility table {}: {}", source, what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
  }
}

void save_flexibility_table(const FlexibilityTable& table, const std::filesystem::path& path) {
  std::ofstream file(path);
  if (!(file << flexibility_table_json(table) << '\n')) throw Error(ErrorKind::io, fmt::format("cannot write the flexibility table {}", path.string()));
  file.close();
  if (!file) throw Error(ErrorKind::io, fmt::format("cannot write the flexibility table {}", path.string()));
}

FlexibilityTable load_flexibility_table(const std::filesystem::path& path) {
  return parse_flexibility_table(read_text_file(path, "flexibility table", kMaxTableFileBytes), path.string());
}

}  // namespace railcontact
