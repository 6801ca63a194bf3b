// `railcontact wheelset`: both wheels of a wheelset on the track, every contact patch, the forces
// on each wheel (docs/WHEELSET.md §5–7).
#include <fmt/core.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "study/patch_files.hpp"
#include "cli/note_on_success.hpp"
#include "cli/option_value.hpp"
#include "railcontact/error.hpp"
#include "railcontact/version.h"
#include "railcontact/wheelset_table.hpp"
#include "case/wheelset_case.hpp"
#include "railcontact/wheelset.hpp"
#include "output/output_directory.hpp"
#include "study/wheelset_sweep.hpp"

namespace railcontact::cli {
namespace {

struct WheelsetArguments {
  std::string case_file;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double roll_rad = 0.0;
  double speed_m_per_s = 20.0;
  double extra_creepage = 0.0;
  double lateral_velocity_m_per_s = 0.0;
  double yaw_rate_rad_per_s = 0.0;
  double load_N = 98100.0;
  double mu = 0.3;
  double element_size_m = 0.2e-3;
  std::vector<std::string> solvers;
  bool json = false;
  int flexibility_coarsening = 0;
  std::string slip_direction;  // --slip-direction (radial, flexibility-weighted, rigid-slip, elastic-slip)
  std::string sweep_y_m;  // FROM:TO:STEP in m
  double wheel_angular_velocity_rad_per_s = 0.0;
  bool free_rolling = false;
  bool rigid_axle = false;
  bool frictionless_balance = false;
  std::string balance_solver;       // --balance-solver (default: the first --solver)
  std::string reference_weighting;  // --reference-weighting (squared-gap, depth)
  std::string contact_surface;      // --contact-surface (planar, conformal)
  std::string table;    // a wheelset table to evaluate from (docs/WHEELSET_TABLE.md)
  std::vector<std::string> table_overrides;  // --table-override: settings the table's values replace
  std::string out = "railcontact-out/wheelset";
};

// Whether the command line gave `option`: a value given overrides the case file's.
bool given(const CLI::App& sub, const char* option) { return sub.count(option) > 0; }

// The case file's case, or the defaults (the shipped set-up, nh-fastsim).
WheelsetCase case_or_defaults(const WheelsetArguments& a) {
  WheelsetCase c;
  if (!a.case_file.empty()) {
    c = read_wheelset_case(a.case_file);
  } else {
    c.options.solvers = {TangentialSolver::nh_fastsim};
  }
  return c;
}

void apply_position(const WheelsetArguments& a, const CLI::App& sub, WheelsetPosition& p) {
  if (given(sub, "--y-m")) p.lateral_displacement_m = a.y_m;
  if (given(sub, "--yaw-rad")) p.yaw_rad = a.yaw_rad;
  if (given(sub, "--roll-rad")) p.roll_rad = a.roll_rad;
}

// The velocities and the wheels' rotation given, checked against their ranges (wheelset.hpp).
void apply_velocity(const WheelsetArguments& a, const CLI::App& sub, WheelsetVelocity& v) {
  if (given(sub, "--speed-m-per-s")) v.forward_speed_m_per_s = a.speed_m_per_s;
  if (given(sub, "--lateral-velocity-m-per-s")) v.lateral_velocity_m_per_s = a.lateral_velocity_m_per_s;
  if (given(sub, "--yaw-rate-rad-per-s")) v.yaw_rate_rad_per_s = a.yaw_rate_rad_per_s;
  // The wheels' rotation: one of pure rolling (with --extra-creepage), a given angular velocity, free rolling.
  const bool extra_creepage = given(sub, "--extra-creepage");
  const bool angular_velocity = given(sub, "--wheel-angular-velocity-rad-per-s");
  const int rotations = (extra_creepage ? 1 : 0) + (angular_velocity ? 1 : 0) + (a.free_rolling ? 1 : 0);
  require(rotations <= 1, "--extra-creepage, --wheel-angular-velocity-rad-per-s and --free-rolling each set the wheels' "
                          "rotation: give one of them");
  // One given on the command line replaces the case file's rotation, whichever of the three it is.
  if (rotations == 1) {
    v.wheel_angular_velocity_rad_per_s = std::numeric_limits<double>::quiet_NaN();
    v.extra_longitudinal_creepage = 0.0;
    v.free_rolling = false;
  }
  if (extra_creepage) v.extra_longitudinal_creepage = a.extra_creepage;
  if (angular_velocity) v.wheel_angular_velocity_rad_per_s = a.wheel_angular_velocity_rad_per_s;
  if (a.free_rolling) v.free_rolling = true;
  // The velocities' ranges, an option given named as given:
  // "--yaw-rate-rad-per-s 1e+06 rad/s must lie in …".
  WheelsetVelocityNames names;
  if (given(sub, "--speed-m-per-s")) names.forward_speed = "--speed-m-per-s";
  if (extra_creepage) names.extra_longitudinal_creepage = "--extra-creepage";
  if (given(sub, "--lateral-velocity-m-per-s")) names.lateral_velocity = "--lateral-velocity-m-per-s";
  if (given(sub, "--yaw-rate-rad-per-s")) names.yaw_rate = "--yaw-rate-rad-per-s";
  if (angular_velocity) names.wheel_angular_velocity = "--wheel-angular-velocity-rad-per-s";
  if (a.free_rolling) names.free_rolling = "--free-rolling";
  validate(v, names);
}

// Friction, mesh and the wheel load (by load: the same on both wheels).
void apply_friction_mesh_and_load(const WheelsetArguments& a, const CLI::App& sub, WheelsetOptions& options) {
  if (given(sub, "--mu")) options.friction_coefficient = a.mu;
  if (given(sub, "--element-size-m")) options.element_size_m = a.element_size_m;
  if (!given(sub, "--load-N")) return;
  require(std::isfinite(a.load_N) && a.load_N > 0.0,
          [&] { return fmt::format("--load-N {:g} N must be positive", a.load_N); });
  require(a.load_N >= kMinimumNormalForce_N && a.load_N <= kMaximumNormalForce_N, [&] {
    return fmt::format("--load-N {:g} N must lie in [{:g}, {:g}] N (a wheel's vertical load: a heavy-haul wheel under "
                       "the largest dynamic factors with a factor 10 to spare)",
                       a.load_N, kMinimumNormalForce_N, kMaximumNormalForce_N);
  });
  options.loads = WheelLoads{a.load_N, a.load_N, false};
}

// nH-FastSim's settings: the coarsening of K2 and the slip direction of its slipping traction.
void apply_nh_fastsim_settings(const WheelsetArguments& a, const CLI::App& sub, WheelsetOptions& options) {
  if (given(sub, "--flexibility-coarsening")) {
    require(a.flexibility_coarsening >= 0 && a.flexibility_coarsening <= kMaximumCoarsening, [&] {
      return fmt::format("--flexibility-coarsening {} must lie in [0, {}] (0: automatic)", a.flexibility_coarsening,
                         kMaximumCoarsening);
    });
    options.nh_fastsim.flexibility_coarsening = a.flexibility_coarsening;
  }
  if (given(sub, "--slip-direction"))
    options.nh_fastsim.bound.slip_direction = parse_option_value("--slip-direction", a.slip_direction, parse_slip_direction);
}

// The solvers run (each once) and the one whose forces the load balance uses (one of them).
void apply_solvers(const WheelsetArguments& a, const CLI::App& sub, WheelsetOptions& options) {
  if (!a.solvers.empty()) {
    options.solvers.clear();
    for (const std::string& name : a.solvers) {
      const TangentialSolver solver = parse_tangential_solver(name);
      require(std::find(options.solvers.begin(), options.solvers.end(), solver) == options.solvers.end(),
              [&] { return fmt::format("--solver {} is given twice; name each solver once", name); });
      options.solvers.push_back(solver);
    }
  }
  if (!given(sub, "--balance-solver")) return;
  options.balance_solver = parse_option_value("--balance-solver", a.balance_solver, parse_tangential_solver);
  const auto& run = options.solvers;
  require(std::find(run.begin(), run.end(), *options.balance_solver) != run.end(), [&] {
    std::string listed;
    for (TangentialSolver s : run) listed += fmt::format("{}{}", listed.empty() ? "" : ", ", solver_name(s));
    return fmt::format("--balance-solver {} is not among the solvers run ({}): add --solver {} or name one of them",
                       a.balance_solver, listed, a.balance_solver);
  });
}

// How each patch is found and shaped: the reference point's weighting and the contact surface.
void apply_patch_geometry(const WheelsetArguments& a, const CLI::App& sub, WheelsetOptions& options) {
  if (given(sub, "--reference-weighting"))
    options.search.weighting =
        parse_option_value("--reference-weighting", a.reference_weighting, parse_reference_weighting);
  if (given(sub, "--contact-surface"))
    options.contact_surface = parse_option_value("--contact-surface", a.contact_surface, parse_contact_surface);
}

// How the loads are met, by load only: without the tangential forces' vertical components, with
// one rigid axle (height and roll).
void apply_load_balance(const WheelsetArguments& a, const CLI::App& sub, WheelsetOptions& options) {
  if (a.frictionless_balance) {
    require(options.loads.has_value(), "--frictionless-balance is a balance of the wheels' loads: it needs the "
                                       "wheelset by load, not the case's vertical position");
    options.tangential_forces_in_vertical_balance = false;
  }
  if (a.rigid_axle) {
    require(options.loads.has_value(), "--rigid-axle balances the wheels' loads: it needs the wheelset by load, not "
                                       "the case's vertical position");
    options.loads->balance_roll = true;
    require(!given(sub, "--roll-rad"), "--rigid-axle solves the roll for the loads: leave out --roll-rad");
  }
}

// The run's case: the file's, or the defaults; command-line options given explicitly override it.
// They are applied and checked in this order: of several wrong options, the first here is reported.
WheelsetCase wheelset_case(const WheelsetArguments& a, const CLI::App& sub) {
  WheelsetCase c = case_or_defaults(a);
  apply_position(a, sub, c.state.position);
  apply_velocity(a, sub, c.state.velocity);
  apply_friction_mesh_and_load(a, sub, c.options);
  apply_nh_fastsim_settings(a, sub, c.options);
  apply_solvers(a, sub, c.options);
  apply_patch_geometry(a, sub, c.options);
  apply_load_balance(a, sub, c.options);
  return c;
}

// A wheelset table and what of it differs from the run's request (docs/WHEELSET_TABLE.md §5).
struct TableUse {
  std::optional<WheelsetTable> table;
  std::vector<WheelsetTableMismatch> overridden;  // named by --table-override: the table's values used
};

// Where the run asks for a setting of the table: a command-line option given, or the case file
// (a case describes the whole run, its defaults included). Without either the table's value is
// used; the recipe is always this railcontact's.
std::optional<std::string> requested_by(WheelsetTableSetting setting, const WheelsetArguments& a, const CLI::App& sub) {
  const auto option_or_case = [&](const char* option, const char* key) -> std::optional<std::string> {
    if (option != nullptr && sub.count(option) > 0) return std::string(option);
    if (!a.case_file.empty()) return fmt::format("the case's {}", key);
    return std::nullopt;
  };
  switch (setting) {
    case WheelsetTableSetting::material: return option_or_case(nullptr, "[material]");
    case WheelsetTableSetting::element_size: return option_or_case("--element-size-m", "[mesh] element_size_mm");
    case WheelsetTableSetting::flexibility_coarsening:
      return option_or_case("--flexibility-coarsening", "[solvers] flexibility_coarsening");
    case WheelsetTableSetting::slip_direction: return option_or_case("--slip-direction", "[solvers] slip_direction");
    case WheelsetTableSetting::collocation_offset:
    case WheelsetTableSetting::traction_bound_skew: return option_or_case(nullptr, "default");
    case WheelsetTableSetting::nh_fastsim_recipe: return std::string("this railcontact's");
    case WheelsetTableSetting::contact_definition: return std::string("this railcontact's");
    case WheelsetTableSetting::contact_surface: return option_or_case("--contact-surface", "[mesh] contact_surface");
    case WheelsetTableSetting::patch_coupling: return std::string("this railcontact's");
  }
  return std::nullopt;
}

// Loads --table and checks it against the run: the track (profiles, parameters), the state (no
// roll), and every setting the run asks for; a setting that differs is an error unless
// --table-override names it.
TableUse table_use(const WheelsetArguments& a, const CLI::App& sub, const WheelsetCase& c, const Wheelset& wheelset,
                   NoteOnSuccess& recipe_note) {
  TableUse use;
  std::vector<WheelsetTableSetting> overrides;
  for (const std::string& name : a.table_overrides)
    overrides.push_back(parse_option_value("--table-override", name, parse_wheelset_table_setting));
  if (a.table.empty()) {
    require(overrides.empty(), "--table-override needs --table (it names settings in which the table may differ)");
    return use;
  }
  const WheelsetOptions& options = c.options;
  // From a wheelset table: both wheels carry their loads (nh-fastsim on the table's patches).
  require(options.loads.has_value(), "--table needs the wheels' loads (by load): the case gives the vertical position");
  require(options.solvers.size() == 1 && options.solvers.front() == TangentialSolver::nh_fastsim,
          "--table gives nh-fastsim only: leave out --solver (or give --solver nh-fastsim)");
  require(!c.state.velocity.free_rolling, [&] {
    return fmt::format("--free-rolling cannot be evaluated from --table {}: free rolling is solved on the fly; give "
                       "--wheel-angular-velocity-rad-per-s or --extra-creepage with --table, or leave out --table",
                       a.table);
  });
  require(!options.loads->balance_roll, [&] {
    return fmt::format("--rigid-axle cannot be evaluated from --table {}: its nodes have zero roll; leave out --table "
                       "to solve the rigid axle",
                       a.table);
  });
  const double roll_rad = c.state.position.roll_rad;
  require(roll_rad == 0.0, [&] {
    const std::string roll = sub.count("--roll-rad") > 0
                                 ? fmt::format("--roll-rad {:g} rad", roll_rad)
                                 : fmt::format("the case's [position] roll_mrad = {:g} mrad", roll_rad * 1e3);
    return fmt::format("{} cannot be evaluated from --table {}: its nodes have zero roll; leave out --table to solve "
                       "the rolled wheelset",
                       roll, a.table);
  });
  use.table = load_wheelset_table(a.table);
  const WheelsetTable& table = *use.table;
  if (const std::string text = older_nh_fastsim_recipe_note(table.metadata().nh_fastsim_recipe); !text.empty())
    recipe_note.set(a.table + ": " + text);
  table.check_track(wheelset.track());
  std::string refused, names;
  for (const WheelsetTableMismatch& m : table.mismatches(options)) {
    const std::optional<std::string> source = requested_by(m.setting, a, sub);
    if (!source) continue;  // not asked for: the table's value
    if (std::find(overrides.begin(), overrides.end(), m.setting) != overrides.end()) {
      use.overridden.push_back(m);
      continue;
    }
    const char* name = wheelset_table_setting_name(m.setting);
    refused += fmt::format("{}{} {} ({}) differs from the table's {}", refused.empty() ? "" : "; ", name, m.requested,
                           *source, m.table);
    names += fmt::format("{}{}", names.empty() ? "" : ",", name);
  }
  require(refused.empty(), [&] {
    return fmt::format("--table {}: {}: rebuild the table for the run, or give --table-override {} to evaluate with "
                       "the table's",
                       a.table, refused, names);
  });
  return use;
}

// --sweep-y-m FROM:TO:STEP in m, with a positive step.
study::WheelsetSweep parse_sweep_y(const std::string& text) {
  std::istringstream in(text);
  char c1 = 0, c2 = 0;
  double from = 0, to = 0, step = 0;
  in >> from >> c1 >> to >> c2 >> step;
  require(in && c1 == ':' && c2 == ':' && in.peek() == std::char_traits<char>::eof() && std::isfinite(from) &&
              std::isfinite(to) && std::isfinite(step) && step > 0.0,
          [&] {
            return fmt::format("--sweep-y-m '{}' must be FROM:TO:STEP in m with a positive step, e.g. "
                               "0:-0.007:0.0001",
                               text);
          });
  study::WheelsetSweep sweep;
  sweep.y_from_m = from;
  sweep.y_to_m = to;
  sweep.y_step_m = step;
  return sweep;
}

// The state evaluated from the wheelset table: both wheels by load, nh-fastsim.
WheelsetResult evaluate_from_table(const WheelsetTable& table, const WheelsetOptions& options,
                                   const WheelsetState& state) {
  return table.evaluate(state, *options.loads, options.friction_coefficient,
                        options.tangential_forces_in_vertical_balance);
}

// --sweep-y-m: the case's state at every y, on the fly or from the table; the CSV and figures in
// --out. A sweep stopped early keeps its rows and ends with the error that stopped it.
int run_y_sweep(const WheelsetArguments& a, const WheelsetCase& c, Wheelset& wheelset, const WheelsetTable* table) {
  const study::WheelsetSweep sweep = parse_sweep_y(a.sweep_y_m);
  output::OutputDirectory out(a.out, &std::cerr);
  fmt::print(std::cerr, "wheelset sweep: y = {:g} ... {:g} mm in steps of {:g} mm{}\n", sweep.y_from_m * 1e3,
             sweep.y_to_m * 1e3, sweep.y_step_m * 1e3, table ? " from the table " + a.table : std::string());
  const study::WheelsetSweepResult done =
      table ? study::run_wheelset_sweep(
                  [&](const WheelsetState& s) { return evaluate_from_table(*table, c.options, s); },
                  {TangentialSolver::nh_fastsim}, c.state, sweep, out, std::cerr)
            : study::run_wheelset_sweep(wheelset, c.state, sweep, out, std::cerr);
  out.commit();
  fmt::print("Wrote {} evaluations to {}/wheelset_sweep.csv (figures: wheelset_sweep.png)\n", done.evaluations, a.out);
  if (done.stopped) {
    // The rows up to the last position that could be evaluated are kept; the error says why the
    // next one could not (for a sweep into the flange, where the flange climbs; from a table, at
    // the end of its y range).
    throw Error(done.stop_kind, fmt::format("the sweep stopped at y = {:g} mm after {} evaluations (written): {}",
                                            done.stopped_at_y_m * 1e3, done.evaluations, done.stop_message));
  }
  return 0;
}

// One state evaluated and the settings it was evaluated with: the table's when evaluating from it.
struct Evaluation {
  WheelsetResult result;
  Material material;
  double element_size_m = 0.0;
  int flexibility_coarsening = 0;
  SlipDirection slip_direction{};
  double nominal_rolling_radius_m = 0.0;  // r0 of pure rolling
};

Evaluation evaluate_state(const WheelsetCase& c, Wheelset& wheelset, const WheelsetTable* table) {
  const WheelsetOptions& options = c.options;
  Evaluation e;
  e.material = table ? table->material() : options.material;
  e.element_size_m = table ? table->metadata().element_size_m : options.element_size_m;
  e.flexibility_coarsening = table ? table->metadata().flexibility_coarsening : options.nh_fastsim.flexibility_coarsening;
  e.slip_direction = table ? table->bound().slip_direction : options.nh_fastsim.bound.slip_direction;
  e.nominal_rolling_radius_m =
      table ? table->nominal_rolling_radius_m() : wheelset.track().parameters().nominal_rolling_radius_m;
  e.result = table ? evaluate_from_table(*table, options, c.state) : wheelset.evaluate(c.state);
  return e;
}

// Every solver's totals, by solver name (the table gives nh-fastsim only).
nlohmann::json solver_totals_json(const std::vector<Vector3>& forces_N, const std::vector<TangentialSolver>& solvers) {
  nlohmann::json totals = nlohmann::json::object();
  for (std::size_t s = 0; s < forces_N.size() && s < solvers.size(); ++s)
    totals[solver_name(solvers[s])] = study::vector_json(forces_N[s]);
  return totals;
}

nlohmann::json wheel_json(const WheelResult& w, const std::vector<TangentialSolver>& solvers) {
  nlohmann::json patches = nlohmann::json::array();
  for (const WheelsetPatch& p : w.patches) patches.push_back(study::wheelset_patch_json(p));
  return {{"side", side_name(w.side)},
          {"vertical_displacement_m", w.vertical_displacement_m},
          {"patches", patches},
          {"force_track_N", study::vector_json(w.force_track_N)},
          {"solver_force_track_N", solver_totals_json(w.solver_force_track_N, solvers)}};
}

// The state evaluated, with the wheels' angular velocity used (pure rolling at r0 resolved).
nlohmann::json state_json(const WheelsetCase& c, const Evaluation& e) {
  const WheelsetResult& r = e.result;
  const double omega = wheelset_motion(r.state, e.nominal_rolling_radius_m).wheel_angular_velocity_rad_per_s;
  return {{"lateral_displacement_m", r.state.position.lateral_displacement_m},
          {"vertical_displacement_m", r.state.position.vertical_displacement_m},
          {"roll_rad", r.state.position.roll_rad},
          {"yaw_rad", r.state.position.yaw_rad},
          {"forward_speed_m_per_s", r.state.velocity.forward_speed_m_per_s},
          {"wheel_angular_velocity_rad_per_s", omega},
          {"free_rolling", c.state.velocity.free_rolling},
          {"free_rolling_iterations", r.free_rolling_iterations}};
}

// How the wheels' heights were found: one rigid axle (height and roll), each wheel on its own
// (the state's vertical displacement is then the mean of the two), or by position.
nlohmann::json load_balance_json(const WheelsetOptions& options) {
  const TangentialSolver balance = options.balance_solver.value_or(options.solvers.front());
  const char* axle = !options.loads ? "by position" : options.loads->balance_roll ? "rigid axle" : "independent wheels";
  return {{"axle", axle},
          {"solver", options.loads ? nlohmann::json(solver_name(balance)) : nlohmann::json(nullptr)},
          {"tangential_forces_in_vertical_balance", options.loads && options.tangential_forces_in_vertical_balance}};
}

// The settings in which the table differs from the run's request, named by --table-override
// (null without a table).
nlohmann::json table_overrides_json(const TableUse& use) {
  nlohmann::json overrides = use.table ? nlohmann::json::array() : nlohmann::json(nullptr);
  for (const WheelsetTableMismatch& m : use.overridden)
    overrides.push_back({{"setting", wheelset_table_setting_name(m.setting)}, {"requested", m.requested}, {"used", m.table}});
  return overrides;
}

// --json: one JSON object.
void print_json(const WheelsetArguments& a, const WheelsetCase& c, const TableUse& use, const Evaluation& e) {
  const WheelsetOptions& options = c.options;
  const WheelsetResult& r = e.result;
  nlohmann::json wheels = nlohmann::json::array();
  for (const WheelResult& w : r.wheels) wheels.push_back(wheel_json(w, options.solvers));
  const nlohmann::json out = {
      {"railcontact_version", RC_VERSION_STRING},
      {"state", state_json(c, e)},
      {"load_balance", load_balance_json(options)},
      {"case", c.source},
      {"friction_coefficient", options.friction_coefficient},
      {"nh_fastsim_slip_direction", slip_direction_name(e.slip_direction)},
      {"element_size_m", e.element_size_m},
      {"material", {{"youngs_modulus_Pa", e.material.youngs_modulus_Pa}, {"poisson_ratio", e.material.poisson_ratio}}},
      {"flexibility_coarsening", e.flexibility_coarsening},
      {"by_load", options.loads.has_value()},
      {"solver", solver_name(options.solvers.front())},
      {"wheelset_table", a.table.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.table)},
      {"wheelset_table_overrides", table_overrides_json(use)},
      {"wheels", wheels},
      {"force_track_N", study::vector_json(r.force_track_N)},
      {"solver_force_track_N", solver_totals_json(r.solver_force_track_N, options.solvers)},
  };
  fmt::print("{}\n", out.dump(2));
}

// The text output's head: the case, the state, the loads or position, the settings overridden and
// the wheels' rotation.
void print_text_heading(const WheelsetArguments& a, const WheelsetCase& c, const TableUse& use, const Evaluation& e) {
  const WheelsetOptions& options = c.options;
  const WheelsetState& state = c.state;
  const WheelsetResult& r = e.result;
  const double load_kN = options.loads ? options.loads->right_N * 1e-3 : 0.0;
  fmt::print("Wheelset {}, y = {:g} mm, yaw = {:g} mrad, roll = {:g} mrad, V = {:g} m/s, {}, mu = {:g}, "
             "elements {:g} mm, forces of {}\n",
             c.source.empty() ? "S1002 / UIC60 1:40" : c.source, r.state.position.lateral_displacement_m * 1e3,
             r.state.position.yaw_rad * 1e3, r.state.position.roll_rad * 1e3, state.velocity.forward_speed_m_per_s,
             options.loads ? fmt::format("{:g} / {:g} kN on the right / left wheel", load_kN,
                                         options.loads->left_N * 1e-3)
                           : fmt::format("by position, z = {:g} mm", state.position.vertical_displacement_m * 1e3),
             options.friction_coefficient, e.element_size_m * 1e3,
             a.table.empty() ? std::string(solver_name(options.solvers.front())) : "nh-fastsim from the table " + a.table);
  for (const WheelsetTableMismatch& m : use.overridden)
    fmt::print("Table override: {} {} (the table's) instead of {}\n", wheelset_table_setting_name(m.setting), m.table,
               m.requested);
  const double nominal = e.nominal_rolling_radius_m;
  const double omega = wheelset_motion(r.state, nominal).wheel_angular_velocity_rad_per_s;
  fmt::print("Wheels' angular velocity {:.6g} rad/s ({}; V / r0 = {:.6g} rad/s){}\n", omega,
             state.velocity.free_rolling ? fmt::format("free rolling, {} evaluations", r.free_rolling_iterations)
             : std::isnan(state.velocity.wheel_angular_velocity_rad_per_s)
                 ? fmt::format("rolling at r0 with extra creepage {:g}", state.velocity.extra_longitudinal_creepage)
                 : std::string("given"),
             state.velocity.forward_speed_m_per_s / nominal,
             options.loads ? fmt::format("; loads met with {}'s forces, {}",
                                         solver_name(options.balance_solver.value_or(options.solvers.front())),
                                         options.loads->balance_roll ? "one rigid axle" : "each wheel's height on its own")
                           : std::string());
}

// One patch: where it lies, its normal solution, creepages and surface, each solver's forces.
void print_patch_text(const WheelsetPatch& p) {
  fmt::print("  at y = {:.2f} mm (rail y_p = {:.2f} mm), angle {:.4f} rad, r = {:.2f} mm: F3 = {:.0f} N, "
             "{} elements, p max {:.0f} MPa\n",
             p.region.reference_point_track_m[1] * 1e3, p.region.rail_profile_y_m * 1e3, p.region.contact_angle_rad,
             p.rolling_radius_m * 1e3, p.normal_force_N, p.elements_in_contact, p.max_pressure_Pa * 1e-6);
  fmt::print("    creepages xi = {:.4e}, eta = {:.4e}, phi = {:.4f} 1/m\n", p.creepage.xi, p.creepage.eta,
             p.creepage.phi);
  if (p.conformal_weight > 0.0 && p.conformal_weight < 1.0)
    fmt::print("    contact surface: planar and conformal blended, conformal weight {:.3f}\n", p.conformal_weight);
  else if (p.surface == ContactSurface::conformal)
    fmt::print("    contact surface: conformal\n");
  if (p.coupling_lift_m > 0.0)
    fmt::print("    coupled with the wheel's other patches: their pressure lifts this one by up to {:.2f} µm "
               "(docs/WHEELSET.md §5)\n",
               p.coupling_lift_m * 1e6);
  // A planar patch whose rail normal turns far from its tangent plane: the note names the remedy
  // (a patch on the curved surface, or blended towards it, is solved as the angle varies).
  const double variation = contact_angle_variation_rad(p.region);
  if (std::isfinite(variation) && variation > kLargeContactAngleVariation_rad && p.conformal_weight == 0.0)
    fmt::print("    note: the rail's normal angle varies over the patch from {:.3f} to {:.3f} rad, up to {:.3f} rad "
               "from its tangent plane: a planar patch is a rough model here; --contact-surface auto (or "
               "conformal) solves it on the curved surface (docs/WHEELSET.md §4)\n",
               p.region.contact_angle_min_rad, p.region.contact_angle_max_rad, variation);
  for (const PatchSolverResult& s : p.solvers)
    fmt::print("    {:<18} F1 = {:.0f} N, F2 = {:.0f} N, M3 = {:.2f} N m\n", solver_name(s.solver), s.forces.F1_N,
               s.forces.F2_N, s.forces.M3_Nm);
}

// The text output: the heading, each wheel with its patches, the wheelset's forces.
void print_text(const WheelsetArguments& a, const WheelsetCase& c, const TableUse& use, const Evaluation& e) {
  const WheelsetResult& r = e.result;
  print_text_heading(a, c, use, e);
  fmt::print("Forces on the wheels in the track frame (x forward, y left, z up), N; patch forces in the contact "
             "frame.\n\n");
  for (const WheelResult& w : r.wheels) {
    fmt::print("{} wheel: {} patch{}, Fx = {:.0f}, Fy = {:.0f}, Fz = {:.0f} N\n", side_name(w.side),
               w.patches.size(), w.patches.size() == 1 ? "" : "es", w.force_track_N[0], w.force_track_N[1],
               w.force_track_N[2]);
    for (const WheelsetPatch& p : w.patches) print_patch_text(p);
  }
  fmt::print("\nwheelset: Fx = {:.0f}, Fy = {:.0f}, Fz = {:.0f} N\n", r.force_track_N[0], r.force_track_N[1],
             r.force_track_N[2]);
}

// `railcontact wheelset`: the case with the options given, checked against the table if one is
// given; then a sweep over y, or one state printed as text or JSON.
int run_wheelset(const WheelsetArguments& a, const CLI::App& sub) {
  const WheelsetCase c = wheelset_case(a, sub);
  Wheelset wheelset(wheelset_track(c), c.options);
  NoteOnSuccess recipe_note;  // a table of an older nH-FastSim recipe: said once the output is written
  const TableUse use = table_use(a, sub, c, wheelset, recipe_note);
  const WheelsetTable* table = use.table ? &*use.table : nullptr;
  if (!a.sweep_y_m.empty()) return run_y_sweep(a, c, wheelset, table);
  const Evaluation e = evaluate_state(c, wheelset, table);
  if (a.json) {
    print_json(a, c, use, e);
  } else {
    print_text(a, c, use, e);
  }
  return 0;
}

}  // namespace

void add_wheelset_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<WheelsetArguments>();
  CLI::App* sub = app.add_subcommand(
      "wheelset",
      "Both wheels of a wheelset on the track (S1002 / UIC60 1:40, 1435 mm gauge): every contact patch and the "
      "forces on each wheel, the vertical position solved for the wheel load (docs/WHEELSET.md)");
  sub->add_option("case", args->case_file, "wheelset case file (TOML, docs/CASE_FILES.md); default: S1002/UIC60");
  sub->add_option("--y-m", args->y_m, "lateral displacement of the wheelset (m, + to the left; default 0)");
  sub->add_option("--yaw-rad", args->yaw_rad, "yaw angle (rad, + the axle's left end backwards; default 0)");
  sub->add_option("--roll-rad", args->roll_rad, "roll angle (rad, + the left wheel up; default 0)");
  sub->add_option("--speed-m-per-s", args->speed_m_per_s, "forward speed (m/s, > 0; default 20)");
  sub->add_option("--extra-creepage", args->extra_creepage,
                  "extra longitudinal creepage of a driven wheelset (dimensionless; < 0 traction, > 0 braking)");
  sub->add_option("--lateral-velocity-m-per-s", args->lateral_velocity_m_per_s,
                  "lateral velocity of the wheelset centre (m/s, + to the left; default 0)");
  sub->add_option("--yaw-rate-rad-per-s", args->yaw_rate_rad_per_s,
                  "yaw rate (rad/s, + turning as a positive yaw angle; default 0)");
  sub->add_option("--load-N", args->load_N, "vertical load per wheel (N, > 0 pressing the wheel on its rail; default 98100)");
  sub->add_option("--mu", args->mu, "friction coefficient (dimensionless)");
  sub->add_option("--element-size-m", args->element_size_m, "element size of the contact meshes (m; default 0.0002)");
  sub->add_option("--solver", args->solvers, "tangential solver(s): nh-fastsim, fastsim, exact, exact-regularised");
  sub->add_option("--balance-solver", args->balance_solver,
                  "the solver whose tangential forces the load balance (and free rolling) use; one of --solver "
                  "(default: the first); the JSON's load_balance.solver");
  sub->add_option("--wheel-angular-velocity-rad-per-s", args->wheel_angular_velocity_rad_per_s,
                  "the wheels' angular velocity about the axle (rad/s, + rolling forward; default: pure rolling at r0, V/r0)");
  sub->add_flag("--free-rolling", args->free_rolling,
                "solve the wheels' angular velocity so that their tangential forces have no moment about the axle "
                "(an unbraked wheelset; docs/WHEELSET.md §6)");
  sub->add_flag("--rigid-axle", args->rigid_axle,
                "by load: meet both wheels' loads with one rigid axle's height and roll (the roll found is in the JSON's "
                "state); default: each wheel's height on its own");
  sub->add_option("--contact-surface", args->contact_surface,
                  "each patch's contact surface: planar (default: the tangent plane at its reference point), "
                  "conformal (curved with the profiles across the rolling direction) or auto (planar where the "
                  "contact angle hardly varies over the patch, conformal where it does, blended between; "
                  "docs/WHEELSET.md §4)");
  sub->add_flag("--frictionless-balance", args->frictionless_balance,
                "by load: the normal forces alone carry the wheel loads (the tangential forces' vertical components left "
                "out, as a wheelset table's nodes are built); default: the whole contact force carries them");
  sub->add_option("--reference-weighting", args->reference_weighting,
                  "how a patch's reference point and contact angle average its overlap: squared-gap (default, as "
                  "Kalker's CONTACT) or depth (docs/WHEELSET.md §4)");
  sub->add_flag("--json", args->json, "print one JSON object");
  sub->add_option("--flexibility-coarsening", args->flexibility_coarsening,
                  "nH-FastSim: K2 on the patch coarsened in square blocks of this factor (0: automatic, 1: the patch itself)");
  sub->add_option("--slip-direction", args->slip_direction,
                  "nH-FastSim's slipping traction: elastic-slip (default: rigid-slip, and where a patch slips "
                  "everywhere Coulomb's law along the elastic slip), rigid-slip (within 3 % on the flange, in full "
                  "slip under spin too), flexibility-weighted (without the turn to the rigid slip) or radial (Eq 8, "
                  "the paper's); docs/FASTSIM.md \"The slip direction\"");
  sub->add_option("--sweep-y-m", args->sweep_y_m,
                  "sweep the lateral displacement, FROM:TO:STEP in m (+ to the left; e.g. 0:-0.007:0.0001): CSV and "
                  "figures in --out");
  sub->add_option("--out", args->out, "output directory of a sweep");
  sub->add_option("--table", args->table,
                  "evaluate from this wheelset table (`railcontact wheelset-table build`; nh-fastsim, by load, zero "
                  "roll; also a --sweep-y-m); the settings the run asks for must be the table's");
  sub->add_option("--table-override", args->table_overrides,
                  "with --table: evaluate with the table's value of these settings where the run asks for others "
                  "(material, element-size, flexibility-coarsening, collocation-offset, slip-direction, "
                  "traction-bound-skew, recipe; a list); the JSON records them")
      ->delimiter(',');
  sub->callback([&action, args, sub] { action = [args, sub] { return run_wheelset(*args, *sub); }; });
}

}  // namespace railcontact::cli
