// `railcontact patch`: the wheel–rail normal contact at one wheelset position (docs/WHEEL_RAIL.md).
#include <fmt/core.h>

#include <cerrno>
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
    std::ofstream file(dir / "patch.json");
    if (!(file << json.dump(2) << '\n'))
      throw output::write_error(dir / "patch.json", errno);
    file.close();
    if (!file) throw output::write_error(dir / "patch.json", errno);
    output::draw_figures("plot_patch.py", dir, std::cerr);
    output->commit();
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
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->add_option("--out", args->out, "write pressure.csv, patch.json and pressure.png into this directory");
  cmd->callback([args, &action] { action = [args] { return run_patch(*args); }; });
}

}  // namespace railcontact::cli
