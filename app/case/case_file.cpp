// TOML case files: every key is checked, every error names the file, the line and the key.
#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "case/case.hpp"
#include "case/toml_section.hpp"
#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact {

namespace {

// Case files are small; anything larger is not one (docs/CASE_FILES.md).
constexpr std::uintmax_t kMaxCaseFileBytes = 1u << 20;  // 1 MiB

// The whole file as TOML; only the known sections at the top level.
toml::table parse_toml(std::string_view text, const std::string& source) {
  static const std::set<std::string> kSections{"geometry", "material", "load", "friction", "creepage", "mesh", "solvers"};
  return parse_toml_sections(text, source, kSections);
}

// [geometry] type = "ellipse": the semi-axes a, b (m) or the curvatures A, B (1/m), not both: a
// semi-axis and a curvature together give the ellipse two ways, and one of them would be ignored.
void read_ellipse(Section& geometry, Case& c) {
  c.geometry = GeometryKind::ellipse;
  for (const char* axis : {"a", "b"})
    for (const char* curvature : {"A", "B"})
      if (geometry.has(axis) && geometry.has(curvature))
        throw Error(fmt::format("{}: [geometry] {} and {} both give the ellipse (the semi-axes a, b in m or the "
                                "curvatures A, B in 1/m): give one pair, not both",
                                geometry.location(curvature), axis, curvature));
  c.ellipse.a_m = geometry.optional_positive("a");
  c.ellipse.b_m = geometry.optional_positive("b");
  c.ellipse.A_per_m = geometry.optional_positive("A");
  c.ellipse.B_per_m = geometry.optional_positive("B");
  const bool axes = c.ellipse.a_m && c.ellipse.b_m, curvatures = c.ellipse.A_per_m && c.ellipse.B_per_m;
  if (axes == curvatures)
    throw Error(fmt::format("{}: [geometry] an ellipse needs either a and b (m) or the curvatures A and B (1/m)",
                            geometry.location("type")));
}

// [geometry] type = "wheel-rail": profile files (empty: the shipped pair) and the lateral displacement y.
void read_wheel_rail(Section& geometry, Case& c) {
  c.geometry = GeometryKind::wheel_rail;
  c.wheel_rail.wheel_file = geometry.optional_string("wheel").value_or("");
  c.wheel_rail.rail_file = geometry.optional_string("rail").value_or("");
  c.wheel_rail.y_m = geometry.optional_number("y").value_or(0.0);
  if (std::fabs(c.wheel_rail.y_m) > kMaximumWheelRailLateralDisplacement_m)
    throw Error(fmt::format("{}: [geometry] y = {} m is not a plausible lateral displacement (|y| <= {:g} m)",
                            geometry.location("y"), c.wheel_rail.y_m, kMaximumWheelRailLateralDisplacement_m));
  if (const std::optional<std::string> reference = geometry.optional_string("contact_reference")) {
    if (*reference != "smooth" && *reference != "first-touch")
      throw Error(fmt::format("{}: [geometry] contact_reference must be \"smooth\" or \"first-touch\" (got \"{}\")",
                              geometry.location("contact_reference"), printable_excerpt(*reference)));
    c.wheel_rail.reference = parse_contact_reference(*reference);
  }
}

void read_geometry(Section geometry, Case& c) {
  const std::string type = geometry.optional_string("type").value_or("");
  if (type == "ellipse") {
    read_ellipse(geometry, c);
  } else if (type == "wheel-rail") {
    read_wheel_rail(geometry, c);
  } else {
    throw Error(fmt::format("{}: [geometry] type must be \"ellipse\" or \"wheel-rail\" (got \"{}\")",
                            geometry.location("type"), printable_excerpt(type)));
  }
  geometry.finish();
}

// [material]: nu and either E or G.
void read_material(Section material, Case& c) {
  const std::optional<double> E = material.optional_positive("E");
  const std::optional<double> G = material.optional_positive("G");
  const double nu = material.number("nu");
  if (!(nu >= 0 && nu <= 0.5))
    throw Error(fmt::format("{}: [material] nu must lie in [0, 0.5] (got {})", material.location("nu"), nu));
  if (E.has_value() == G.has_value())
    throw Error(fmt::format("{}: [material] give either E or G (Pa)", material.location("nu")));
  c.material = E ? Material{*E, nu} : Material::from_shear_modulus(*G, nu);
  material.finish();
}

// [load]: the normal force (for a wheel-rail case the vertical wheel load Fz).
void read_load(Section load, Case& c) {
  c.normal_force_N = load.positive("normal_force");
  load.finish();
}

// [friction]: mu.
void read_friction(Section friction, Case& c) {
  c.mu = friction.positive("mu");
  if (c.mu > 2.0)
    throw Error(fmt::format("{}: [friction] mu = {} is not physical (at most 2)", friction.location("mu"), c.mu));
  friction.finish();
}

// [creepage] phi: a number (1/m) or "from-conicity" (Eq 24).
void read_spin(Section& creepage, Case& c) {
  if (const toml::node* phi = creepage.node("phi")) {
    if (const auto* s = phi->as_string()) {
      if (s->get() != "from-conicity")
        throw Error(fmt::format("{}: [creepage] phi must be a number (1/m) or \"from-conicity\"", creepage.location_of(*phi)));
      c.creepage.phi_from_conicity = true;
    } else {
      c.creepage.raw.phi = creepage.optional_number("phi").value_or(0.0);
    }
  }
}

// [creepage]: no absurd magnitudes of the raw or normalised creepages.
void check_creepage_ranges(const Section& creepage, const Case& c) {
  for (const char* key : {"xi", "eta"})
    if (std::fabs(key[0] == 'x' ? c.creepage.raw.xi : c.creepage.raw.eta) > kMaximumCreepage)
      throw Error(fmt::format("{}: [creepage] {} is absurd (|{}| <= {:g})", creepage.location(key), key, key,
                              kMaximumCreepage));
  if (std::fabs(c.creepage.raw.phi) > kMaximumSpinCreepage_per_m)
    throw Error(fmt::format("{}: [creepage] phi = {} 1/m is absurd (|phi| <= {:g} 1/m)", creepage.location("phi"),
                            c.creepage.raw.phi, kMaximumSpinCreepage_per_m));
  for (const char* key : {"xi_normalised", "eta_normalised"}) {
    const auto& v = key[0] == 'x' ? c.creepage.xi_normalised : c.creepage.eta_normalised;
    if (v && std::fabs(*v) > 100.0)
      throw Error(fmt::format("{}: [creepage] {} is absurd (at most 100 in magnitude)", creepage.location(key), key));
  }
}

// [creepage]: raw xi, eta or the normalised xi', eta' (Eq 22-23), and phi. Needs [geometry]: the
// normalisation and the spin from conicity need a wheel-rail patch.
void read_creepage(Section creepage, Case& c) {
  c.creepage.raw.xi = creepage.optional_number("xi").value_or(0.0);
  c.creepage.raw.eta = creepage.optional_number("eta").value_or(0.0);
  c.creepage.xi_normalised = creepage.optional_number("xi_normalised");
  c.creepage.eta_normalised = creepage.optional_number("eta_normalised");
  if (creepage.has("xi") && c.creepage.xi_normalised)
    throw Error(fmt::format("{}: [creepage] give xi or xi_normalised, not both", creepage.location("xi")));
  if (creepage.has("eta") && c.creepage.eta_normalised)
    throw Error(fmt::format("{}: [creepage] give eta or eta_normalised, not both", creepage.location("eta")));
  read_spin(creepage, c);
  check_creepage_ranges(creepage, c);
  if (c.geometry == GeometryKind::ellipse && (c.creepage.xi_normalised || c.creepage.eta_normalised ||
                                              c.creepage.phi_from_conicity))
    throw Error(fmt::format("{}: [creepage] normalised creepages and phi = \"from-conicity\" need a wheel-rail patch",
                            creepage.source()));
  creepage.finish();
}

// [mesh] (optional): the number of elements in contact.
void read_mesh(Section mesh, Case& c) {
  if (const std::optional<double> elements = mesh.optional_positive("elements")) {
    if (*elements < 20 || *elements > 1e6 || std::floor(*elements) != *elements)
      throw Error(fmt::format("{}: [mesh] elements must be a whole number in [20, 1000000] (got {})",
                              mesh.location("elements"), *elements));
    c.target_elements = static_cast<int>(*elements);
  }
  mesh.finish();
}

// [solvers] run: the list of solver names; absent, the default list stays.
void read_solver_list(Section& solvers, Case& c) {
  const toml::node* run = solvers.node("run");
  if (run == nullptr) return;
  const toml::array* list = run->as_array();
  if (list == nullptr || list->empty())
    throw Error(fmt::format("{}: [solvers] run must be a non-empty list of solver names", solvers.location_of(*run)));
  c.solvers.clear();
  for (const toml::node& item : *list) {
    const auto* name = item.as_string();
    const std::string solver = name != nullptr ? name->get() : std::string("?");
    TangentialSolver kind;
    try {
      kind = parse_tangential_solver(solver);
    } catch (const Error&) {
      throw Error(fmt::format("{}: [solvers] unknown solver '{}' (nh-fastsim, fastsim, exact, exact-regularised)",
                              solvers.location_of(item), printable_excerpt(solver)));
    }
    if (std::find(c.solvers.begin(), c.solvers.end(), kind) != c.solvers.end())
      throw Error(fmt::format("{}: [solvers] run names '{}' twice; name each solver once", solvers.location_of(item),
                              solver));
    c.solvers.push_back(kind);
  }
}

// [solvers] (optional): the solvers to run and their options: the collocation offset alpha, the
// regularisation, the tolerance, nH-FastSim's flexibility coarsening, its bound skew (0: the
// paper's parabola, Eq 1) and its slip direction.
void read_solvers(Section solvers, Case& c) {
  read_solver_list(solvers, c);
  if (const std::optional<double> alpha = solvers.optional_number("alpha")) {
    if (!(*alpha >= kMinimumCollocationOffset && *alpha <= 1))
      throw Error(fmt::format("{}: [solvers] alpha = {} must lie in [{}, 1]", solvers.location("alpha"), *alpha,
                              kMinimumCollocationOffset));
    c.rolling.collocation_offset = *alpha;
  }
  if (const std::optional<double> eps = solvers.optional_positive("regularisation")) c.rolling.regularisation = *eps;
  if (const std::optional<double> tol = solvers.optional_positive("tolerance")) c.rolling.tolerance = *tol;
  if (const std::optional<double> f = solvers.optional_positive("flexibility_coarsening")) {
    if (*f != std::floor(*f) || *f > kMaximumCoarsening)
      throw Error(fmt::format("{}: [solvers] flexibility_coarsening must be an integer from 1 to {}",
                              solvers.location("flexibility_coarsening"), kMaximumCoarsening));
    c.flexibility_coarsening = static_cast<int>(*f);
  }
  if (const std::optional<double> skew = solvers.optional_number("bound_skew")) {
    if (!(*skew >= 0 && *skew <= 1))
      throw Error(fmt::format("{}: [solvers] bound_skew must lie in [0, 1] (0: the paper's parabola, Eq 1)",
                              solvers.location("bound_skew")));
    c.bound_skew = *skew;
  }
  if (const std::optional<std::string> d = solvers.optional_string("slip_direction")) {
    try {
      c.slip_direction = parse_slip_direction(*d);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: [solvers] slip_direction: {}", solvers.location("slip_direction"), e.what()));
    }
  }
  solvers.finish();
}

}  // namespace

Case parse_case(std::string_view text, const std::string& source, const std::filesystem::path& base_directory) {
  const toml::table root = parse_toml(text, source);
  const toml::table empty;  // stands in for an absent optional section
  const auto section = [&](const std::string& name, bool required) {
    return Section(section_table(root, name, source, required, empty), name, source);
  };
  Case c;
  c.source = source;
  read_geometry(section("geometry", true), c);
  read_material(section("material", true), c);
  read_load(section("load", true), c);
  read_friction(section("friction", true), c);
  read_creepage(section("creepage", true), c);  // after [geometry]
  read_mesh(section("mesh", false), c);
  read_solvers(section("solvers", false), c);
  // Relative profile paths are relative to the case file's directory (base_directory).
  for (std::string* file : {&c.wheel_rail.wheel_file, &c.wheel_rail.rail_file})
    if (!file->empty() && std::filesystem::path(*file).is_relative() && !base_directory.empty())
      *file = (base_directory / *file).lexically_normal().string();
  return c;
}

Case read_case_file(const std::filesystem::path& path) {
  const std::string text = read_text_file(path, "case file", kMaxCaseFileBytes);
  return parse_case(text, path.string(), path.parent_path());
}

}  // namespace railcontact
