// The wheelset-table file (docs/WHEELSET_TABLE.md §4): one JSON object, every field documented;
// read strictly (unknown keys, missing keys and wrong types are errors naming the key).
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "flexibility_table/table_json.hpp"
#include "wheelset_table/wheelset_table_json.hpp"
#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"
#include "railcontact/wheelset_table.hpp"

namespace railcontact {
namespace {

using detail::StrictJsonReader;
using nlohmann::json;

constexpr const char* kKind = "wheelset table";
constexpr const char* kFormat = "railcontact wheelset table";
// Version 2 (2026-11-25): each patch's "lobes" (a patch of several lobes); version 1 files read as
// patches without lobes.
// 3: slip_direction (1-2: the radial one); 4: nh_fastsim_recipe; 5: reference_weighting and
// creepage_point (older: depth, the rail surface); 6: contact_surface, contact_surface_switch and
// each patch's "conformal" part (older: planar); 7: each runtime copy's "creepage_coupling" (older:
// none); 8: patch_coupling (older: separate patches not coupled).
constexpr int kFormatVersion = 8;
// The largest file read (a table of 91 y values × 3 loads at 400 runtime elements is about 12 MB).
constexpr std::uintmax_t kMaxTableFileBytes = 512u << 20;  // 512 MiB
// At most this many nodes (as a build makes) and elements per runtime mesh.
constexpr std::size_t kMaxNodes = 20000;
constexpr std::size_t kMaxRuntimeMeshElements = 1u << 20;

json vector3(const Vector3& v) { return json::array({v[0], v[1], v[2]}); }

json mesh_json(const Mesh& m) {
  return json{{"n1", m.n1}, {"n2", m.n2}, {"dx1_m", m.dx1_m}, {"dx2_m", m.dx2_m}, {"x1_first_m", m.x1_first_m},
              {"x2_first_m", m.x2_first_m}};
}

json flexibility_json(const Flexibility& L) { return json::array({L.L1, L.L2, L.L3}); }
// CreepageCoupling (tangential.hpp): [xi_per_eta, xi_per_phi_m, eta_per_xi, eta_per_phi_m].
json coupling_json(const CreepageCoupling& c) {
  return json::array({c.xi_per_eta, c.xi_per_phi_m, c.eta_per_xi, c.eta_per_phi_m});
}

json strips_json(const std::vector<WheelsetTableStrip>& strips) {
  json out = json::array();
  for (const WheelsetTableStrip& s : strips)
    out.push_back(json{{"angle_rad", s.angle_rad}, {"point_from_wheelset_centre_m", vector3(s.point_from_wheelset_centre_m)}});
  return out;
}

// A patch's lobes; a conformal patch's with their strips.
json lobes_json(const std::vector<WheelsetTableLobe>& lobes, bool with_strips) {
  json out = json::array();
  for (const WheelsetTableLobe& l : lobes) {
    json lobe{{"pressure_centre_x1_m", l.pressure_centre_x1_m},
              {"pressure_centre_x2_m", l.pressure_centre_x2_m},
              {"flexibility_m_per_Pa", flexibility_json(l.flexibility)},
              {"creepage_coupling", coupling_json(l.coupling)},
              {"runtime_mesh", mesh_json(l.runtime_mesh)},
              {"runtime_pressure_Pa", l.runtime_pressure_Pa}};
    if (with_strips) lobe["strips"] = strips_json(l.strips);
    out.push_back(std::move(lobe));
  }
  return out;
}

json conformal_json(const std::optional<WheelsetTableConformalPatch>& conformal) {
  if (!conformal) return nullptr;
  const WheelsetTableConformalPatch& c = *conformal;
  const json strips = strips_json(c.strips);
  return json{{"lobes", lobes_json(c.lobes, true)},
              {"whole_patch_weight", c.whole_patch_weight},{"weight", c.weight},
              {"normal_force_N", c.normal_force_N},
              {"pressure_force_track_N", vector3(c.pressure_force_track_N)},
              {"area_m2", c.area_m2},
              {"elements_in_contact", c.elements_in_contact},
              {"max_pressure_Pa", c.max_pressure_Pa},
              {"pressure_centre_x1_m", c.pressure_centre_x1_m},
              {"pressure_centre_x2_m", c.pressure_centre_x2_m},
              {"flexibility_m_per_Pa", flexibility_json(c.flexibility)},
              {"creepage_coupling", coupling_json(c.coupling)},
              {"runtime_mesh", mesh_json(c.runtime_mesh)},
              {"runtime_pressure_Pa", c.runtime_pressure_Pa},
              {"strips", strips}};
}

json patch_json(const WheelsetTablePatch& p) {
  const json lobes = lobes_json(p.lobes, false);
  return json{{"reference_point_track_m", vector3(p.reference_point_track_m)},
              {"point_from_wheelset_centre_m", vector3(p.point_from_wheelset_centre_m)},
              {"x1_axis", vector3(p.x1_axis)},
              {"x2_axis", vector3(p.x2_axis)},
              {"x3_axis", vector3(p.x3_axis)},
              {"contact_angle_rad", p.contact_angle_rad},
              {"rolling_radius_m", p.rolling_radius_m},
              {"rail_profile_y_m", p.rail_profile_y_m},
              {"wheel_profile_y_m", p.wheel_profile_y_m},
              {"normal_force_N", p.normal_force_N},
              {"area_m2", p.area_m2},
              {"elements_in_contact", p.elements_in_contact},
              {"max_pressure_Pa", p.max_pressure_Pa},
              {"pressure_centre_x1_m", p.pressure_centre_x1_m},
              {"pressure_centre_x2_m", p.pressure_centre_x2_m},
              {"flexibility_m_per_Pa", flexibility_json(p.flexibility)},
              {"creepage_coupling", coupling_json(p.coupling)},
              {"runtime_mesh", mesh_json(p.runtime_mesh)},
              {"runtime_pressure_Pa", p.runtime_pressure_Pa},
              {"lobes", lobes},
              {"whole_patch_weight", p.whole_patch_weight},
              {"conformal", conformal_json(p.conformal)}};
}

json node_json(const WheelsetTableNode& n) {
  json wheels = json::array();
  for (const auto& wheel : n.wheels) {
    json patches = json::array();
    for (const WheelsetTablePatch& p : wheel) patches.push_back(patch_json(p));
    wheels.push_back(patches);
  }
  return json{{"y_m", n.y_m},
              {"yaw_rad", n.yaw_rad},
              {"wheel_load_N", n.wheel_load_N},
              {"status", n.status == WheelsetTableNodeStatus::solved ? "solved" : "failed"},
              {"message", n.message},
              {"vertical_displacement_m", json::array({n.vertical_displacement_m[0], n.vertical_displacement_m[1]})},
              {"wheels", wheels}};
}

Vector3 read_vector3(StrictJsonReader& r, const std::string& key) {
  const std::vector<double> v = r.numbers(key);
  if (v.size() != 3) r.fail(fmt::format("{} must be a list of 3 numbers", r.qualified(key)));
  for (double x : v)
    if (!std::isfinite(x)) r.fail(fmt::format("{} must be finite", r.qualified(key)));
  return {v[0], v[1], v[2]};
}

int read_int(StrictJsonReader& r, const std::string& key, int lo, int hi) {
  const std::size_t n = r.count(key);
  if (n < static_cast<std::size_t>(lo) || n > static_cast<std::size_t>(hi))
    r.fail(fmt::format("{} = {} must lie in [{}, {}]", r.qualified(key), n, lo, hi));
  return static_cast<int>(n);
}

// flexibility_m_per_Pa, runtime_mesh and runtime_pressure_Pa of a patch or a lobe.
void read_runtime(StrictJsonReader& r, Flexibility& flexibility, CreepageCoupling& coupling, Mesh& mesh,
                  std::vector<double>& pressure_Pa) {
  const std::vector<double> L = r.numbers("flexibility_m_per_Pa");
  if (L.size() != 3) r.fail(fmt::format("{} must be a list of 3 numbers", r.qualified("flexibility_m_per_Pa")));
  flexibility = {L[0], L[1], L[2]};
  // Format 7 and later; none in older tables (built before the coupling, recipe 3 or older).
  if (r.has("creepage_coupling")) {
    const std::vector<double> c = r.numbers("creepage_coupling");
    if (c.size() != 4) r.fail(fmt::format("{} must be a list of 4 numbers", r.qualified("creepage_coupling")));
    coupling = {c[0], c[1], c[2], c[3]};
  }
  {
    StrictJsonReader m = r.child("runtime_mesh");
    mesh.n1 = read_int(m, "n1", 0, 1 << 20);
    mesh.n2 = read_int(m, "n2", 0, 1 << 20);
    mesh.dx1_m = m.number("dx1_m");
    mesh.dx2_m = m.number("dx2_m");
    mesh.x1_first_m = m.number("x1_first_m");
    mesh.x2_first_m = m.number("x2_first_m");
    m.finish();
    if (mesh.size() > kMaxRuntimeMeshElements)
      m.fail(fmt::format("{} has {} × {} elements; at most {} are allowed", r.qualified("runtime_mesh"), mesh.n1,
                         mesh.n2, kMaxRuntimeMeshElements));
  }
  pressure_Pa = r.numbers("runtime_pressure_Pa");
  for (double x : pressure_Pa)
    if (!std::isfinite(x) || x < 0.0)
      r.fail(fmt::format("{} must hold finite, non-negative pressures", r.qualified("runtime_pressure_Pa")));
  if (!pressure_Pa.empty() && pressure_Pa.size() != mesh.size())
    r.fail(fmt::format("{} has {} values for a runtime mesh of {} elements", r.qualified("runtime_pressure_Pa"),
                       pressure_Pa.size(), mesh.size()));
}

// At most this many lobes per patch (a build finds two).
constexpr std::size_t kMaxLobes = 16;

// At most this many strips per conformal patch (one per runtime mesh column).
constexpr std::size_t kMaxStrips = 1u << 16;

std::vector<WheelsetTableStrip> read_strips(StrictJsonReader& r) {
  const json& strips = r.array("strips");
  if (strips.size() > kMaxStrips)
    r.fail(fmt::format("{} has {} strips; at most {} are allowed", r.qualified("strips"), strips.size(), kMaxStrips));
  std::vector<WheelsetTableStrip> out;
  for (std::size_t j = 0; j < strips.size(); ++j) {
    StrictJsonReader sr = r.item(strips[j], fmt::format("{}[{}]", r.qualified("strips"), j));
    WheelsetTableStrip strip;
    strip.angle_rad = sr.number("angle_rad");
    strip.point_from_wheelset_centre_m = read_vector3(sr, "point_from_wheelset_centre_m");
    sr.finish();
    out.push_back(strip);
  }
  return out;
}


std::vector<WheelsetTableLobe> read_lobes(StrictJsonReader& r, bool with_strips) {
  const json& lobes = r.array("lobes");
  if (lobes.size() > kMaxLobes)
    r.fail(fmt::format("{} has {} lobes; at most {} are allowed", r.qualified("lobes"), lobes.size(), kMaxLobes));
  std::vector<WheelsetTableLobe> out;
  for (std::size_t j = 0; j < lobes.size(); ++j) {
    StrictJsonReader l = r.item(lobes[j], fmt::format("{}[{}]", r.qualified("lobes"), j));
    WheelsetTableLobe lobe;
    lobe.pressure_centre_x1_m = l.number("pressure_centre_x1_m");
    lobe.pressure_centre_x2_m = l.number("pressure_centre_x2_m");
    read_runtime(l, lobe.flexibility, lobe.coupling, lobe.runtime_mesh, lobe.runtime_pressure_Pa);
    if (with_strips) lobe.strips = read_strips(l);
    l.finish();
    out.push_back(std::move(lobe));
  }
  return out;
}

WheelsetTableConformalPatch read_conformal(StrictJsonReader r) {
  WheelsetTableConformalPatch c;
  c.weight = r.number("weight");
  c.normal_force_N = r.number("normal_force_N");
  c.pressure_force_track_N = read_vector3(r, "pressure_force_track_N");
  c.area_m2 = r.number("area_m2");
  c.elements_in_contact = r.count("elements_in_contact");
  c.max_pressure_Pa = r.number("max_pressure_Pa");
  c.pressure_centre_x1_m = r.number("pressure_centre_x1_m");
  c.pressure_centre_x2_m = r.number("pressure_centre_x2_m");
  read_runtime(r, c.flexibility, c.coupling, c.runtime_mesh, c.runtime_pressure_Pa);
  c.strips = read_strips(r);
  c.lobes = read_lobes(r, true);
  c.whole_patch_weight = r.number("whole_patch_weight");
  r.finish();
  return c;
}

WheelsetTablePatch read_patch(StrictJsonReader r, int version) {
  WheelsetTablePatch p;
  p.reference_point_track_m = read_vector3(r, "reference_point_track_m");
  p.point_from_wheelset_centre_m = read_vector3(r, "point_from_wheelset_centre_m");
  p.x1_axis = read_vector3(r, "x1_axis");
  p.x2_axis = read_vector3(r, "x2_axis");
  p.x3_axis = read_vector3(r, "x3_axis");
  p.contact_angle_rad = r.number("contact_angle_rad");
  p.rolling_radius_m = r.number("rolling_radius_m");
  p.rail_profile_y_m = r.number("rail_profile_y_m");
  p.wheel_profile_y_m = r.number("wheel_profile_y_m");
  p.normal_force_N = r.number("normal_force_N");
  p.area_m2 = r.number("area_m2");
  p.elements_in_contact = r.count("elements_in_contact");
  p.max_pressure_Pa = r.number("max_pressure_Pa");
  p.pressure_centre_x1_m = r.number("pressure_centre_x1_m");
  p.pressure_centre_x2_m = r.number("pressure_centre_x2_m");
  read_runtime(r, p.flexibility, p.coupling, p.runtime_mesh, p.runtime_pressure_Pa);
  if (version >= 2) {
    p.lobes = read_lobes(r, false);
    p.whole_patch_weight = r.number("whole_patch_weight");
  }
  if (version >= 6) {
    const json& conformal = r.get("conformal");
    if (!conformal.is_null()) p.conformal = read_conformal(r.item(conformal, r.qualified("conformal")));
  }
  r.finish();
  return p;
}

WheelsetTableNode read_node(StrictJsonReader r, int version) {
  WheelsetTableNode n;
  n.y_m = r.number("y_m");
  n.yaw_rad = r.number("yaw_rad");
  n.wheel_load_N = r.number("wheel_load_N");
  const std::string status = r.string("status");
  if (status == "solved") n.status = WheelsetTableNodeStatus::solved;
  else if (status == "failed") n.status = WheelsetTableNodeStatus::failed;
  else r.fail(fmt::format("{} must be \"solved\" or \"failed\" (got \"{}\")", r.qualified("status"), printable_excerpt(status)));
  n.message = r.string("message");
  const std::vector<double> z = r.numbers("vertical_displacement_m");
  if (z.size() != 2) r.fail(fmt::format("{} must be a list of 2 numbers (right, left)", r.qualified("vertical_displacement_m")));
  n.vertical_displacement_m = {z[0], z[1]};
  const json& wheels = r.array("wheels");
  if (wheels.size() != 2) r.fail(fmt::format("{} must be a list of 2 wheels (right, left)", r.qualified("wheels")));
  for (std::size_t w = 0; w < 2; ++w) {
    if (!wheels[w].is_array()) r.fail(fmt::format("{}[{}] must be a list of patches", r.qualified("wheels"), w));
    for (std::size_t k = 0; k < wheels[w].size(); ++k)
      n.wheels[w].push_back(
          read_patch(r.item(wheels[w][k], fmt::format("{}[{}][{}]", r.qualified("wheels"), w, k)), version));
  }
  if (n.status != WheelsetTableNodeStatus::solved && (!n.wheels[0].empty() || !n.wheels[1].empty()))
    r.fail(fmt::format("{} must be empty lists: the node is not solved", r.qualified("wheels")));
  r.finish();
  return n;
}

WheelsetTableMetadata read_metadata(StrictJsonReader& r, int format_version) {
  WheelsetTableMetadata m;
  m.railcontact_version = r.string("railcontact_version");
  m.created_utc = r.string("created_utc");
  {
    StrictJsonReader profiles = r.child("profiles");
    m.right_wheel_profile = detail::read_fingerprint(profiles, "right_wheel");
    m.right_rail_profile = detail::read_fingerprint(profiles, "right_rail");
    m.left_wheel_profile = detail::read_fingerprint(profiles, "left_wheel");
    m.left_rail_profile = detail::read_fingerprint(profiles, "left_rail");
    profiles.finish();
  }
  m.track = detail::read_track_parameters(r, "track");
  m.element_size_m = r.number("element_size_m");
  m.flexibility_coarsening = read_int(r, "flexibility_coarsening", 0, kMaximumCoarsening);
  m.collocation_offset = r.number("collocation_offset");
  m.runtime_elements = read_int(r, "runtime_elements", 1, 1 << 20);
  // Format versions 1 to 3: recipe 1 or 2, not recorded.
  m.nh_fastsim_recipe = format_version >= 4 ? read_int(r, "nh_fastsim_recipe", 0, kNhFastSimRecipe) : 0;
  // Format versions 1 to 4: depth-weighted reference points, creepages on the rail surface.
  m.reference_weighting = ReferenceWeighting::depth;
  m.creepage_on_wheel_surface = false;
  if (format_version >= 5) {
    try {
      m.reference_weighting = parse_reference_weighting(r.string("reference_weighting"));
    } catch (const Error& e) {
      r.fail(fmt::format("reference_weighting: {}", e.what()));
    }
    const std::string point = r.string("creepage_point");
    if (point != "undeformed wheel surface")
      r.fail(fmt::format("creepage_point must be \"undeformed wheel surface\" (got \"{}\")", printable_excerpt(point)));
    m.creepage_on_wheel_surface = true;
  }
  // Format versions 1 to 5: planar patches.
  if (format_version >= 6) {
    try {
      m.contact_surface = parse_contact_surface(r.string("contact_surface"));
    } catch (const Error& e) {
      r.fail(fmt::format("contact_surface: {}", e.what()));
    }
    const std::vector<double> band = r.numbers("contact_surface_switch");
    if (band.size() != 2) r.fail("contact_surface_switch must be a list of 2 numbers (planar_up_to, conformal_from)");
    m.contact_surface_switch = {band[0], band[1]};
    try {
      validate(m.contact_surface_switch);
    } catch (const Error& e) {
      r.fail(fmt::format("contact_surface_switch: {}", e.what()));
    }
  }
  // Format versions 1 to 7: separate patches solved on their own.
  if (format_version >= 8) {
    const std::vector<double> distances = r.numbers("patch_coupling");
    if (distances.size() != 2) r.fail("patch_coupling must be a list of 2 numbers (full_distance_m, end_distance_m)");
    m.patch_coupling = {distances[0], distances[1]};
    try {
      validate(m.patch_coupling);
    } catch (const Error& e) {
      r.fail(fmt::format("patch_coupling: {}", e.what()));
    }
  }
  return m;
}

}  // namespace

namespace detail {
std::string wheelset_table_nodes_json(const std::vector<WheelsetTableNode>& nodes) {
  json list = json::array();
  for (const WheelsetTableNode& n : nodes) list.push_back(node_json(n));
  return list.dump();
}
std::vector<WheelsetTableNode> parse_wheelset_table_nodes(const std::string& text) {
  const std::string source = "wheelset table nodes";
  const json root = detail::parse_strict_json(text, source, kKind);
  std::vector<WheelsetTableNode> nodes;
  if (!root.is_array()) throw Error("wheelset table nodes: not a list");
  for (std::size_t k = 0; k < root.size(); ++k)
    nodes.push_back(read_node(StrictJsonReader(root[k], fmt::format("nodes[{}]", k), source, kKind), kFormatVersion));
  return nodes;
}
}  // namespace detail

std::string wheelset_table_json(const WheelsetTable& table) {
  const WheelsetTableMetadata& m = table.metadata();
  json nodes = json::array();
  for (const WheelsetTableNode& n : table.nodes()) nodes.push_back(node_json(n));
  const json out = {{"format", kFormat},
                    {"format_version", kFormatVersion},
                    {"railcontact_version", m.railcontact_version},
                    {"created_utc", m.created_utc},
                    {"profiles",
                     {{"right_wheel", detail::fingerprint_json(m.right_wheel_profile)},
                      {"right_rail", detail::fingerprint_json(m.right_rail_profile)},
                      {"left_wheel", detail::fingerprint_json(m.left_wheel_profile)},
                      {"left_rail", detail::fingerprint_json(m.left_rail_profile)}}},
                    {"track", detail::track_parameters_json(m.track)},
                    {"material",
                     {{"youngs_modulus_Pa", table.material().youngs_modulus_Pa},
                      {"poisson_ratio", table.material().poisson_ratio}}},
                    {"element_size_m", m.element_size_m},
                    {"flexibility_coarsening", m.flexibility_coarsening},
                    {"collocation_offset", m.collocation_offset},
                    {"traction_bound_skew", table.bound().skew},
                    {"slip_direction", slip_direction_name(table.bound().slip_direction)},
                    {"runtime_elements", m.runtime_elements},
                    {"nh_fastsim_recipe", m.nh_fastsim_recipe},
                    {"reference_weighting", reference_weighting_name(m.reference_weighting)},
                    {"creepage_point", "undeformed wheel surface"},
                    {"contact_surface", contact_surface_name(m.contact_surface)},
                    {"contact_surface_switch",
                     json::array({m.contact_surface_switch.planar_up_to, m.contact_surface_switch.conformal_from})},
                    {"patch_coupling", json::array({m.patch_coupling.full_distance_m, m.patch_coupling.end_distance_m})},
                    {"nominal_rolling_radius_m", table.nominal_rolling_radius_m()},
                    {"y_m", table.grid().y_m},
                    {"yaw_rad", table.grid().yaw_rad},
                    {"wheel_load_N", table.grid().wheel_load_N},
                    {"nodes", nodes}};
  return out.dump();
}

WheelsetTable parse_wheelset_table(const std::string& text, const std::string& source) {
  const json root = detail::parse_strict_json(text, source, kKind);
  StrictJsonReader r(root, "", source, kKind);
  if (!root.contains("format") || !root["format"].is_string() || root["format"].get<std::string>() != kFormat)
    r.fail(fmt::format("not a wheelset table (the key 'format' must be \"{}\")", kFormat));
  r.get("format");
  const json& version = r.get("format_version");
  if (!version.is_number_integer() || version.get<int>() < 1 || version.get<int>() > kFormatVersion)
    r.fail(fmt::format("format_version {} is not supported (this railcontact reads versions 1 to {})",
                       detail::quoted_json_value(version), kFormatVersion));
  const int format_version = version.get<int>();
  WheelsetTableMetadata metadata = read_metadata(r, format_version);
  Material material;
  {
    StrictJsonReader m = r.child("material");
    material.youngs_modulus_Pa = m.number("youngs_modulus_Pa");
    material.poisson_ratio = m.number("poisson_ratio");
    m.finish();
  }
  TractionBound bound{r.number("traction_bound_skew"), SlipDirection::radial};
  if (format_version >= 3) {
    const std::string direction = r.string("slip_direction");
    try {
      bound.slip_direction = parse_slip_direction(direction);
    } catch (const Error& e) {
      r.fail(fmt::format("slip_direction: {}", e.what()));
    }
  }
  const double nominal_rolling_radius_m = r.number("nominal_rolling_radius_m");
  WheelsetTableGrid grid;
  grid.y_m = r.numbers("y_m");
  grid.yaw_rad = r.numbers("yaw_rad");
  grid.wheel_load_N = r.numbers("wheel_load_N");
  const std::size_t ny = grid.y_m.size(), nyaw = grid.yaw_rad.size(), nl = grid.wheel_load_N.size();
  if (ny > kMaxNodes || nyaw > kMaxNodes || nl > kMaxNodes || grid.size() > kMaxNodes)
    r.fail(fmt::format("{} y values × {} yaws × {} loads: at most {} nodes are allowed", ny, nyaw, nl, kMaxNodes));
  std::vector<WheelsetTableNode> nodes;
  const json& node_list = r.array("nodes");
  if (node_list.size() != grid.size())
    r.fail(fmt::format("nodes has {} entries for {} y values × {} yaws × {} loads", node_list.size(), ny, nyaw, nl));
  for (std::size_t k = 0; k < node_list.size(); ++k)
    nodes.push_back(read_node(r.item(node_list[k], fmt::format("nodes[{}]", k)), format_version));
  r.finish();
  try {
    validate(material);
    if (!(bound.skew >= 0.0 && bound.skew <= 1.0)) throw Error(fmt::format("traction_bound_skew {} must lie in [0, 1]", bound.skew));
    WheelsetTable table(std::move(grid), std::move(nodes), nominal_rolling_radius_m, material, bound,
                        std::move(metadata));
    table.set_source(source);
    return table;
  } catch (const Error& e) {
    const std::string what = e.what();
    const std::string prefix = "wheelset table: ";
    throw Error(fmt::format("wheelset table {}: {}", source, what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
  }
}

void save_wheelset_table(const WheelsetTable& table, const std::filesystem::path& path) {
  std::ofstream file(path);
  if (!(file << wheelset_table_json(table) << '\n'))
    throw Error(ErrorKind::io, fmt::format("cannot write the wheelset table {}", path.string()));
  file.close();
  if (!file) throw Error(ErrorKind::io, fmt::format("cannot write the wheelset table {}", path.string()));
}

WheelsetTable load_wheelset_table(const std::filesystem::path& path) {
  return parse_wheelset_table(read_text_file(path, "wheelset table", kMaxTableFileBytes), path.string());
}

}  // namespace railcontact
