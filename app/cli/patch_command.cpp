// `railcontact patch`: the wheel–rail normal contact at one wheelset position (docs/WHEEL_RAIL.md).
#include <fmt/core.h>

#include <cerrno>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "railcontact/error.hpp"
#include "railcontact/version.h"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"
#include "output/figures.hpp"
#include "output/output_directory.hpp"
#include "study/patch_files.hpp"

namespace railcontact::cli {
namespace {

struct PatchArguments {
  double y_m = 0.0;
  std::optional<std::string> wheel;
  std::optional<std::string> rail;
  double load_N = WheelRailPatchOptions{}.vertical_load_N;
  int elements = WheelRailPatchOptions{}.target_elements;
  std::string layout = "rolling-resolved";
  std::string reference = "smooth";
  std::string reference_weighting = "squared-gap";
  std::string contact_surface = "planar";
  double element_size_m = WheelsetOptions{}.element_size_m;
  bool json = false;
  std::optional<std::string> out;
};

void print_table(const WheelRailPatch& p, const std::string& wheel, const std::string& rail, double time_s) {
  const WheelRailContactPoint& c = p.contact;
  const Mesh& m = p.potential_area;
  fmt::print("Wheel-rail normal contact (right wheel), y = {:.3f} mm\n", p.lateral_displacement_m * 1e3);
  fmt::print("  wheel {}\n  rail  {}\n\n", wheel, rail);
  if (p.reference == ContactReference::smooth) {
    const InterpenetrationRegion& g = p.region;
    fmt::print("  reference point          y_rail {:.3f} mm, y_wheel {:.3f} mm, {:.3f} mm from the track centre "
               "(smooth: averaged over the overlap)\n",
               g.rail_profile_y_m * 1e3, g.wheel_profile_y_m * 1e3, g.reference_point_track_m[1] * 1e3);
    fmt::print("  first touch              y_rail {:.3f} mm, contact angle {:.5f} rad\n", c.y_rail_m * 1e3,
               c.contact_angle_rad);
    fmt::print("  wheelset height z        {:.3f} um above nominal, carrying Fz ({} load iterations)\n",
               p.vertical_displacement_m * 1e6, p.load_iterations);
  } else {
    fmt::print("  contact point            y_rail {:.3f} mm, y_wheel {:.3f} mm, {:.3f} mm from the track centre "
               "(first touch)\n",
               c.y_rail_m * 1e3, c.y_wheel_m * 1e3, c.y_track_m * 1e3);
  }
  fmt::print("  contact angle            {:.5f} rad\n", p.contact_angle_rad);
  fmt::print("  rolling radius           {:.3f} mm\n", p.rolling_radius_m * 1e3);
  fmt::print("  spin (Eq 24)             {:+.5f} 1/m\n", p.spin_per_m);
  fmt::print("  vertical load Fz         {:.1f} N\n", p.vertical_load_N);
  fmt::print("  normal force F3          {:.1f} N  (Fz / cos gamma)\n", p.normal_force_N);
  fmt::print("  approach                 {:.3f} um\n", p.approach_m * 1e6);
  fmt::print("  max pressure             {:.1f} MPa\n", p.max_pressure_Pa * 1e-6);
  fmt::print("  area                     {:.2f} mm2\n", p.area_m2 * 1e6);
  fmt::print("  extent X1 x X2           {:.3f} x {:.3f} mm\n", p.extent_x1_m * 1e3, p.extent_x2_m * 1e3);
  fmt::print("  centre of pressure       x1 {:+.3f} mm, x2 {:+.3f} mm from the reference point\n",
             p.pressure_centre_x1_m * 1e3, p.pressure_centre_x2_m * 1e3);
  fmt::print("  elements in contact      {}  (mesh {} x {}, {:.4f} x {:.4f} mm, {} solves)\n", p.elements_in_contact,
             m.n1, m.n2, m.dx1_m * 1e3, m.dx2_m * 1e3, p.mesh_passes);
  fmt::print("  normal-solver iterations {}\n", p.iterations);
  if (p.local_hertz.a_m > 0.0) {
    const double hertz_area = M_PI * p.local_hertz.a_m * p.local_hertz.b_m;
    fmt::print("  Hertz (local curvatures) area {:.2f} mm2 ({:+.1f} %), p0 {:.1f} MPa ({:+.1f} %)\n", hertz_area * 1e6,
               100 * (p.area_m2 / hertz_area - 1), p.local_hertz.max_pressure_Pa * 1e-6,
               100 * (p.max_pressure_Pa / p.local_hertz.max_pressure_Pa - 1));
  }
  fmt::print("  time                     {:.1f} ms\n", time_s * 1e3);
}

// --out: patch.json (the JSON object), the pressure map by scripts/plot_patch.py, the staged files
// committed into the directory.
void finish_output(output::OutputDirectory& output, const nlohmann::json& json) {
  const std::filesystem::path path = output.staging() / "patch.json";
  std::ofstream file(path);
  if (!(file << json.dump(2) << '\n')) throw output::write_error(path, errno);
  file.close();
  if (!file) throw output::write_error(path, errno);
  output::draw_figures("plot_patch.py", output.staging(), std::cerr);
  output.commit();
}

// --contact-surface conformal or auto: the right wheel of the wheelset at y (by load, both wheels
// carrying --load-N on their normal forces, no yaw, pure rolling), its patches on that surface
// (docs/WHEELSET.md §4 "Conformal contact"): the single-wheel stage has one tangent plane per patch.
void print_curved(const WheelsetResult& r, const PatchArguments& args, const std::string& wheel,
                  const std::string& rail, double time_s) {
  fmt::print("Wheel-rail normal contact (right wheel of the wheelset), y = {:.3f} mm, contact surface {}\n",
             args.y_m * 1e3, args.contact_surface);
  fmt::print("  wheel {}\n  rail  {}\n\n", wheel, rail);
  const WheelResult& w = r.wheels[0];
  fmt::print("  wheel height z           {:.3f} um above nominal, carrying Fz = {:.1f} N on the normal forces "
             "({} load iterations)\n",
             w.vertical_displacement_m * 1e6, args.load_N, w.load_iterations);
  for (std::size_t k = 0; k < w.patches.size(); ++k) {
    const WheelsetPatch& p = w.patches[k];
    fmt::print("  patch {}: {} (conformal weight {:.2f})\n", k + 1, contact_surface_name(p.surface), p.conformal_weight);
    fmt::print("    contact angle          {:.5f} rad at y_rail {:.3f} mm\n", p.region.contact_angle_rad,
               p.region.rail_profile_y_m * 1e3);
    if (!p.strips.empty()) {
      const auto [lo, hi] = std::minmax_element(p.strips.begin(), p.strips.end(), [](const auto& a, const auto& b) {
        return a.angle_rad < b.angle_rad;
      });
      fmt::print("    strips turned          {:+.4f} ... {:+.4f} rad from it\n", lo->angle_rad, hi->angle_rad);
    }
    fmt::print("    normal force           {:.1f} N (pressure resultant, track frame: {:.1f}, {:.1f}, {:.1f} N)\n",
               p.normal_force_N, p.pressure_force_track_N[0], p.pressure_force_track_N[1], p.pressure_force_track_N[2]);
    fmt::print("    approach               {:.3f} um\n", p.approach_m * 1e6);
    fmt::print("    max pressure           {:.1f} MPa\n", p.max_pressure_Pa * 1e-6);
    fmt::print("    area                   {:.2f} mm2, {} elements in contact\n", p.area_m2 * 1e6, p.elements_in_contact);
  }
  fmt::print("  time                     {:.1f} ms\n", time_s * 1e3);
}

int run_curved_patch(const PatchArguments& args, const std::filesystem::path& wheel, const std::filesystem::path& rail) {
  std::optional<output::OutputDirectory> output;
  if (args.out) output.emplace(*args.out, &std::cerr);
  const auto start = std::chrono::steady_clock::now();
  const WheelsetTrack track(load_wheel_rail_pair(wheel, rail));
  WheelsetOptions options;
  require(std::isfinite(args.element_size_m) && args.element_size_m > 0.0,
          [&] { return fmt::format("--element-size-m {} must be a positive number of metres", args.element_size_m); });
  options.element_size_m = args.element_size_m;
  options.contact_surface = parse_contact_surface(args.contact_surface);
  options.loads = WheelLoads{args.load_N, args.load_N, false};
  options.tangential_forces_in_vertical_balance = false;  // the normal problem alone, as the planar `patch`
  options.keep_tractions = true;                          // the pressures for --out
  try {
    options.search.weighting = parse_reference_weighting(args.reference_weighting);
  } catch (const Error& e) {
    throw Error(fmt::format("--reference-weighting: {}", e.what()));
  }
  try {
    validate(options);
  } catch (const Error& e) {
    throw Error(fmt::format("--element-size-m {:g}: {}", args.element_size_m, e.what()));
  }
  Wheelset wheelset(track, options);
  WheelsetState state;
  state.position.lateral_displacement_m = args.y_m;
  const WheelsetResult r = wheelset.evaluate(state);
  const double time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const WheelResult& w = r.wheels[0];
  nlohmann::json patches = nlohmann::json::array();
  for (const WheelsetPatch& p : w.patches) patches.push_back(study::wheelset_patch_json(p));
  nlohmann::json json = {{"railcontact_version", RC_VERSION_STRING},
                         {"wheel_profile", wheel.string()},
                         {"rail_profile", rail.string()},
                         {"wheel", "right"},
                         {"y", args.y_m},
                         {"contact_surface", args.contact_surface},
                         {"element_size_m", args.element_size_m},
                         {"vertical_load_N", args.load_N},
                         {"vertical_displacement_m", w.vertical_displacement_m},
                         {"patches", patches},
                         {"solve_time_s", time_s}};
  if (output) {
    const std::filesystem::path& dir = output->staging();
    for (std::size_t k = 0; k < w.patches.size(); ++k) {
      const WheelsetPatch& p = w.patches[k];
      const std::string name = fmt::format("pressure_{}.csv", k + 1);
      if (p.patch.elements().count() > 0) study::write_pressure_csv(dir / name, p.patch);
      json["patches"][k]["pressure_csv"] = name;
      json["patches"][k]["mesh"] = {{"dx1_m", p.patch.mesh().dx1_m}, {"dx2_m", p.patch.mesh().dx2_m}};
    }
    finish_output(*output, json);
  }
  if (args.json) {
    fmt::print("{}\n", json.dump(2));
  } else {
    print_curved(r, args, wheel.string(), rail.string(), time_s);
    if (args.out) fmt::print("\nWrote {}/pressure_*.csv, patch.json, pressure.png\n", *args.out);
  }
  return 0;
}

int run_patch(const PatchArguments& args) {
  require(std::isfinite(args.y_m), "--y-m must be a finite number of metres");
  require(std::isfinite(args.load_N) && args.load_N > 0.0,
          [&] { return fmt::format("--load-N must be positive (got {} N)", args.load_N); });
  validate_normal_force(args.load_N, "--load-N");
  require(args.elements >= kMinimumWheelRailElements && args.elements <= kMaximumWheelRailElements, [&] {
    return fmt::format("--elements {} must lie in [{}, {}] (with fewer, the elements are too large for the patch and "
                       "the profiles)",
                       args.elements, kMinimumWheelRailElements, kMaximumWheelRailElements);
  });
  const std::filesystem::path wheel = args.wheel ? std::filesystem::path(*args.wheel) : default_wheel_profile_path();
  const std::filesystem::path rail = args.rail ? std::filesystem::path(*args.rail) : default_rail_profile_path();
  if (args.contact_surface != "planar") return run_curved_patch(args, wheel, rail);

  // --out: locked and staged before the work (docs/RELIABILITY.md "Outputs").
  std::optional<output::OutputDirectory> output;
  if (args.out) output.emplace(*args.out, &std::cerr);
  const auto start = std::chrono::steady_clock::now();
  const WheelRailPair pair = load_wheel_rail_pair(wheel, rail);
  WheelRailPatchOptions options;
  options.vertical_load_N = args.load_N;
  options.target_elements = args.elements;
  options.layout = args.layout == "square" ? PatchMeshLayout::square : PatchMeshLayout::rolling_resolved;
  options.reference = parse_contact_reference(args.reference);
  try {
    options.search.weighting = parse_reference_weighting(args.reference_weighting);
  } catch (const Error& e) {
    throw Error(fmt::format("--reference-weighting: {}", e.what()));
  }
  const WheelRailPatch patch = [&] {
    try {
      return solve_wheel_rail_patch(pair, args.y_m, options);
    } catch (const Error& e) {
      // Refused before the work: named by the options that give it.
      const std::string_view message = e.what();
      if (!message.starts_with(kWheelRailElementsTooSmall)) throw;
      throw Error(fmt::format("--elements {} with --load-N {:g} N:{}", args.elements, args.load_N,
                              message.substr(kWheelRailElementsTooSmall.size())));
    }
  }();
  const double time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json json = study::patch_json(patch);
  json["railcontact_version"] = RC_VERSION_STRING;
  json["wheel_profile"] = wheel.string();
  json["rail_profile"] = rail.string();
  json["solve_time_s"] = time_s;
  if (output) {
    const std::filesystem::path& dir = output->staging();
    study::write_pressure_csv(dir / "pressure.csv", patch.patch);
    finish_output(*output, json);
  }
  if (args.json) {
    fmt::print("{}\n", json.dump(2));
  } else {
    print_table(patch, wheel.string(), rail.string(), time_s);
    if (args.out) fmt::print("\nWrote {}/pressure.csv, patch.json, pressure.png\n", *args.out);
  }
  return 0;
}

}  // namespace

void add_patch_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<PatchArguments>();
  CLI::App* cmd = app.add_subcommand(
      "patch", "wheel-rail normal contact at one wheelset position (default: S1002 on UIC60 1:40, 98.1 kN)");
  cmd->add_option("--y-m", args->y_m,
                  "wheelset lateral displacement (m, track frame, + to the left; y < 0 towards the flange)")
      ->capture_default_str();
  cmd->add_option("--wheel", args->wheel, "wheel profile file (.prw, .whl or text; default: the shipped S1002)");
  cmd->add_option("--rail", args->rail, "rail profile file (.prr, .ban or text; default: the shipped UIC60 1:40)");
  cmd->add_option("--load-N", args->load_N, "vertical wheel load Fz (N, > 0; F3 = Fz / cos(gamma))")->capture_default_str();
  cmd->add_option("--elements", args->elements, "about this many elements in contact")->capture_default_str();
  cmd->add_option("--mesh", args->layout, "element shape: rolling-resolved (dx1 <= dx2) or square")
      ->check(CLI::IsMember({"rolling-resolved", "square"}))
      ->capture_default_str();
  cmd->add_option("--reference", args->reference,
                  "contact reference: smooth (averaged over the overlap, as railcontact wheelset) or first-touch")
      ->check(CLI::IsMember({"smooth", "first-touch"}))
      ->capture_default_str();
  cmd->add_option("--reference-weighting", args->reference_weighting,
                  "the smooth reference's weights: squared-gap (as Kalker's CONTACT) or depth (docs/WHEELSET.md §4)")
      ->capture_default_str();
  cmd->add_option("--contact-surface", args->contact_surface,
                  "planar (default: the single-wheel stage, one tangent plane), or conformal / auto: the right wheel "
                  "of `railcontact wheelset` at this y, its patches on that surface (docs/WHEELSET.md §4)")
      ->check(CLI::IsMember({"planar", "conformal", "auto"}))
      ->capture_default_str();
  cmd->add_option("--element-size-m", args->element_size_m,
                  "with --contact-surface conformal or auto: the square elements' size (m; the wheelset's mesh)")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->add_option("--out", args->out, "write pressure.csv, patch.json and pressure.png into this directory");
  cmd->callback([args, cmd, &action] {
    // Each mode's mesh options: the planar stage's element count and shape, the wheelset's element size.
    std::string conflict;
    if (args->contact_surface != "planar") {
      for (const char* option : {"--elements", "--mesh", "--reference"})
        if (cmd->count(option) > 0 && conflict.empty())
          conflict = fmt::format("{} applies to --contact-surface planar only (with {} the mesh is the wheelset's: "
                                 "--element-size-m; its reference is the smooth one)",
                                 option, args->contact_surface);
    } else if (cmd->count("--element-size-m") > 0) {
      conflict = "--element-size-m applies to --contact-surface conformal or auto only (the planar stage takes "
                 "--elements)";
    }
    action = [args, conflict] {
      if (!conflict.empty()) throw Error(conflict);
      return run_patch(*args);
    };
  });
}

}  // namespace railcontact::cli
