// Wheelset case files (see the header).
#include "case/wheelset_case.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <set>

#include "case/toml_section.hpp"
#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact {

namespace {

constexpr std::uintmax_t kMaxCaseFileBytes = 1u << 20;  // 1 MiB, as a run case

std::optional<bool> optional_bool(Section& s, const std::string& key) {
  const toml::node* node = s.node(key);
  if (node == nullptr) return std::nullopt;
  const auto* b = node->as_boolean();
  if (b == nullptr) throw Error(fmt::format("{}: {} must be true or false", s.location_of(*node), key));
  return b->get();
}

std::filesystem::path resolved(const std::optional<std::string>& file, const std::filesystem::path& base) {
  if (!file) return {};
  std::filesystem::path p(*file);
  if (p.is_relative() && !base.empty()) p = (base / p).lexically_normal();
  return p;
}

void read_setup(Section s, WheelsetCase& c, const std::filesystem::path& base) {
  c.setup_file = resolved(s.optional_string("file"), base);
  const std::filesystem::path wheel = resolved(s.optional_string("wheel_profile"), base);
  const std::filesystem::path rail = resolved(s.optional_string("rail_profile"), base);
  const std::filesystem::path left_wheel = resolved(s.optional_string("left_wheel_profile"), base);
  const std::filesystem::path left_rail = resolved(s.optional_string("left_rail_profile"), base);
  s.finish();
  const bool profiles = !wheel.empty() || !rail.empty() || !left_wheel.empty() || !left_rail.empty();
  if (!c.setup_file.empty() && profiles)
    throw Error(fmt::format("{}: [setup] gives either file or profiles, not both", s.location("file")));
  if (profiles && (wheel.empty() || rail.empty()))
    throw Error(fmt::format("{}: [setup] needs both wheel_profile and rail_profile", s.location("wheel_profile")));
  c.right_wheel_profile = wheel;
  c.right_rail_profile = rail;
  c.left_wheel_profile = left_wheel.empty() ? wheel : left_wheel;
  c.left_rail_profile = left_rail.empty() ? rail : left_rail;
}

void read_position(Section s, WheelsetCase& c, bool by_load) {
  WheelsetPosition& p = c.state.position;
  p.lateral_displacement_m = s.optional_number("y_mm").value_or(0.0) * 1e-3;
  p.yaw_rad = s.optional_number("yaw_mrad").value_or(0.0) * 1e-3;
  p.roll_rad = s.optional_number("roll_mrad").value_or(0.0) * 1e-3;
  const std::optional<double> z = s.optional_number("z_mm");
  if (by_load && z)
    throw Error(fmt::format("{}: [position] z_mm is solved from [load]; give one of them", s.location("z_mm")));
  p.vertical_displacement_m = z.value_or(0.0) * 1e-3;
  s.finish();
}

void read_velocity(Section s, WheelsetCase& c) {
  WheelsetVelocity& v = c.state.velocity;
  v.forward_speed_m_per_s = s.optional_number("speed_m_per_s").value_or(v.forward_speed_m_per_s);
  v.lateral_velocity_m_per_s = s.optional_number("lateral_velocity_m_per_s").value_or(0.0);
  v.vertical_velocity_m_per_s = s.optional_number("vertical_velocity_m_per_s").value_or(0.0);
  v.roll_rate_rad_per_s = s.optional_number("roll_rate_rad_per_s").value_or(0.0);
  v.yaw_rate_rad_per_s = s.optional_number("yaw_rate_rad_per_s").value_or(0.0);
  v.extra_longitudinal_creepage = s.optional_number("extra_longitudinal_creepage").value_or(0.0);
  if (const std::optional<double> w = s.optional_number("wheel_angular_velocity_rad_per_s")) {
    if (s.has("extra_longitudinal_creepage"))
      throw Error(fmt::format("{}: [velocity] gives either wheel_angular_velocity_rad_per_s or "
                              "extra_longitudinal_creepage, not both",
                              s.location("wheel_angular_velocity_rad_per_s")));
    v.wheel_angular_velocity_rad_per_s = *w;
  }
  v.free_rolling = optional_bool(s, "free_rolling").value_or(false);
  // The ranges of the library (wheelset.hpp), named as the file gives them: "FILE:5: [velocity] yaw_rate_rad_per_s".
  const auto name = [&](const char* key) { return fmt::format("{}: [velocity] {}", s.location(key), key); };
  validate(v, WheelsetVelocityNames{name("speed_m_per_s"), name("lateral_velocity_m_per_s"),
                                    name("vertical_velocity_m_per_s"), name("roll_rate_rad_per_s"),
                                    name("yaw_rate_rad_per_s"), name("wheel_angular_velocity_rad_per_s"),
                                    name("extra_longitudinal_creepage"), name("free_rolling")});
  s.finish();
}

void read_load(Section s, WheelsetCase& c) {
  WheelLoads loads;
  loads.right_N = s.optional_positive("right_wheel_N").value_or(loads.right_N);
  loads.left_N = s.optional_positive("left_wheel_N").value_or(loads.left_N);
  loads.balance_roll = optional_bool(s, "balance_roll").value_or(false);
  s.finish();
  c.options.loads = loads;
}

void read_rest(Section friction, Section material, Section mesh, Section solvers, WheelsetCase& c) {
  c.options.friction_coefficient = friction.optional_positive("mu").value_or(c.options.friction_coefficient);
  friction.finish();
  c.options.material.youngs_modulus_Pa = material.optional_positive("E_Pa").value_or(c.options.material.youngs_modulus_Pa);
  c.options.material.poisson_ratio = material.optional_number("nu").value_or(c.options.material.poisson_ratio);
  material.finish();
  c.options.element_size_m = mesh.optional_positive("element_size_mm").value_or(c.options.element_size_m * 1e3) * 1e-3;
  if (const std::optional<std::string> w = mesh.optional_string("reference_weighting")) {
    try {
      c.options.search.weighting = parse_reference_weighting(*w);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: [mesh] reference_weighting: {}", mesh.location("reference_weighting"), e.what()));
    }
  }
  if (const std::optional<std::string> surface = mesh.optional_string("contact_surface")) {
    try {
      c.options.contact_surface = parse_contact_surface(*surface);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: [mesh] contact_surface: {}", mesh.location("contact_surface"), e.what()));
    }
  }
  mesh.finish();
  if (const toml::node* run = solvers.node("run")) {
    const toml::array* list = run->as_array();
    if (list == nullptr || list->empty())
      throw Error(fmt::format("{}: [solvers] run must be a non-empty list of solver names", solvers.location_of(*run)));
    c.options.solvers.clear();
    for (const toml::node& item : *list) {
      const auto* name = item.as_string();
      if (name == nullptr) throw Error(fmt::format("{}: [solvers] run holds a non-string", solvers.location_of(item)));
      TangentialSolver solver{};
      try {
        solver = parse_tangential_solver(name->get());
      } catch (const Error& e) {
        throw Error(fmt::format("{}: [solvers] {}", solvers.location_of(item), e.what()));
      }
      if (std::find(c.options.solvers.begin(), c.options.solvers.end(), solver) != c.options.solvers.end())
        throw Error(fmt::format("{}: [solvers] run names '{}' twice; name each solver once", solvers.location_of(item),
                                name->get()));
      c.options.solvers.push_back(solver);
    }
  }
  if (const std::optional<double> f = solvers.optional_number("flexibility_coarsening")) {
    if (!(*f >= 0 && *f <= kMaximumCoarsening && *f == std::floor(*f)))
      throw Error(fmt::format("{}: [solvers] flexibility_coarsening = {} must be an integer in [0, {}] (0: automatic)",
                              solvers.location("flexibility_coarsening"), *f, kMaximumCoarsening));
    c.options.nh_fastsim.flexibility_coarsening = static_cast<int>(*f);
  }
  if (const std::optional<std::string> d = solvers.optional_string("slip_direction")) {
    try {
      c.options.nh_fastsim.bound.slip_direction = parse_slip_direction(*d);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: [solvers] slip_direction: {}", solvers.location("slip_direction"), e.what()));
    }
  }
  if (const std::optional<std::string> b = solvers.optional_string("balance_solver")) {
    try {
      c.options.balance_solver = parse_tangential_solver(*b);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: [solvers] balance_solver: {}", solvers.location("balance_solver"), e.what()));
    }
  }
  solvers.finish();
}

}  // namespace

namespace {
const std::set<std::string> kWheelsetCaseSections{"setup",    "position", "velocity", "load",
                                                  "friction", "material", "mesh",     "solvers"};
}  // namespace

WheelsetCase parse_wheelset_case(std::string_view text, const std::string& source,
                                 const std::filesystem::path& base_directory) {
  const toml::table root = parse_toml_sections(text, source, kWheelsetCaseSections);
  return wheelset_case_from_toml(root, source, base_directory);
}

WheelsetCase parse_wheelset_case_with(std::string_view text, const std::string& source,
                                      const std::filesystem::path& base_directory,
                                      const std::set<std::string>& caller_sections, toml::table& root) {
  std::set<std::string> sections = kWheelsetCaseSections;
  sections.insert(caller_sections.begin(), caller_sections.end());
  root = parse_toml_sections(text, source, sections);
  return wheelset_case_from_toml(root, source, base_directory);
}

WheelsetCase wheelset_case_from_toml(const toml::table& root, const std::string& source,
                                     const std::filesystem::path& base_directory) {
  const toml::table empty;
  const auto section = [&](const std::string& name) {
    return Section(section_table(root, name, source, false, empty), name, source);
  };
  WheelsetCase c;
  c.source = source;
  read_setup(section("setup"), c, base_directory);
  // By load unless the position gives the height (z_mm) and there is no [load]: the default is
  // 98.1 kN per wheel, as on the command line.
  const toml::table* position = root["position"].as_table();
  const bool height_given = position != nullptr && position->contains("z_mm");
  const bool by_load = root.contains("load") || !height_given;
  if (by_load) read_load(section("load"), c);
  else c.options.loads.reset();
  read_position(section("position"), c, by_load);
  read_velocity(section("velocity"), c);
  read_rest(section("friction"), section("material"), section("mesh"), section("solvers"), c);
  try {
    validate(c.options);
  } catch (const Error& e) {
    throw Error(e.kind(), fmt::format("{}: {}", source, e.what()));
  }
  return c;
}

WheelsetCase read_wheelset_case(const std::filesystem::path& path) {
  const std::string text = read_text_file(path, "case file", kMaxCaseFileBytes);
  return parse_wheelset_case(text, path.string(), path.parent_path());
}

WheelsetTrack wheelset_track(const WheelsetCase& c) {
  if (!c.right_wheel_profile.empty()) {
    WheelsetProfiles p{read_profile(c.right_wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}), read_profile(c.left_wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}),
                       read_profile(c.right_rail_profile, ProfileReadOptions{.role = ProfileKind::rail}), read_profile(c.left_rail_profile, ProfileReadOptions{.role = ProfileKind::rail})};
    return WheelsetTrack(p);
  }
  const WheelRailSetup setup = read_wheel_rail_setup(c.setup_file.empty() ? default_wheel_rail_setup_path() : c.setup_file);
  return WheelsetTrack(read_profile(setup.wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}), read_profile(setup.rail_profile, ProfileReadOptions{.role = ProfileKind::rail}), setup.track);
}

}  // namespace railcontact
