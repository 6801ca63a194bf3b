// `railcontact geometry`: the rigid contact geometry of a wheelset over a y-sweep (contact points,
// contact angles, rolling radii, Δr, roll) and the equivalent conicity of EN 15302
// (docs/CONTACT_GEOMETRY.md).
#include <fmt/core.h>
#include <fmt/ostream.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "case/wheelset_case.hpp"
#include "cli/commands.hpp"
#include "railcontact/contact_geometry.hpp"
#include "railcontact/error.hpp"
#include "railcontact/version.h"
#include "railcontact/geometry.hpp"
#include "railcontact/wheel_rail.hpp"
#include "study/contact_geometry_study.hpp"
#include "output/output_directory.hpp"

namespace railcontact::cli {
namespace {

struct GeometryArguments {
  std::string case_file;
  std::string wheel_file, rail_file;
  double gauge_m = 0.0, flange_back_m = 0.0, radius_m = 0.0, rail_cant_rad = 0.0;
  double y_from_m = -6e-3, y_to_m = 6e-3, y_step_m = 0.1e-3;
  double amplitude_m = 3e-3;
  bool json = false;
  std::string out = "railcontact-out/geometry";
};

Profile read_option_profile(const std::string& option, const std::string& file, ProfileKind role) {
  try {
    return read_profile(file, ProfileReadOptions{.role = role});
  } catch (const Error& e) {
    throw Error(e.kind(), fmt::format("{} {}: {}", option, file, e.what()));
  }
}

// The track: the case file's, or the shipped S1002/UIC60 set-up with --wheel, --rail and the track
// options applied.
WheelsetTrack geometry_track(const GeometryArguments& a, const CLI::App& sub, std::string& description) {
  const auto given = [&](const char* option) { return sub.count(option) > 0; };
  if (!a.case_file.empty()) {
    for (const char* option : {"--wheel", "--rail", "--gauge-m", "--flange-back-m", "--rolling-radius-m", "--rail-cant-rad"}) {
      require(!given(option), [&] {
        return fmt::format("{} cannot be combined with a case file ({}): the case file sets the profiles and track",
                           option, a.case_file);
      });
    }
    const WheelsetCase c = read_wheelset_case(a.case_file);
    description = a.case_file;
    return wheelset_track(c);
  }
  WheelRailSetup setup = read_wheel_rail_setup(default_wheel_rail_setup_path());
  description = "S1002 / UIC60 1:40";
  const Profile wheel = a.wheel_file.empty() ? read_profile(setup.wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel})
                                           : read_option_profile("--wheel", a.wheel_file, ProfileKind::wheel);
  const Profile rail = a.rail_file.empty() ? read_profile(setup.rail_profile, ProfileReadOptions{.role = ProfileKind::rail})
                                         : read_option_profile("--rail", a.rail_file, ProfileKind::rail);
  if (!a.wheel_file.empty() || !a.rail_file.empty()) {
    description = fmt::format("wheel {}, rail {}", a.wheel_file.empty() ? setup.wheel_profile.filename().string() : a.wheel_file,
                              a.rail_file.empty() ? setup.rail_profile.filename().string() : a.rail_file);
  }
  TrackWheelsetParameters& t = setup.track;
  // The ranges of the library (geometry.hpp).
  const auto length_m = [&](const char* option, double value_m, double low_m, double high_m) {
    require(std::isfinite(value_m) && value_m >= low_m && value_m <= high_m, [&] {
      return fmt::format("{} {:g} m must lie in [{:g}, {:g}] m", option, value_m, low_m, high_m);
    });
    return value_m;
  };
  if (given("--gauge-m")) t.track_gauge_m = length_m("--gauge-m", a.gauge_m, kMinimumTrackGauge_m, kMaximumTrackGauge_m);
  if (given("--flange-back-m"))
    t.flange_back_distance_m =
        length_m("--flange-back-m", a.flange_back_m, kMinimumFlangeBackDistance_m, kMaximumFlangeBackDistance_m);
  if (given("--rolling-radius-m"))
    t.nominal_rolling_radius_m =
        length_m("--rolling-radius-m", a.radius_m, kMinimumNominalRollingRadius_m, kMaximumNominalRollingRadius_m);
  if (given("--rail-cant-rad")) {
    validate_rail_cant(a.rail_cant_rad, "--rail-cant-rad");
    t.rail_cant_rad = a.rail_cant_rad;
  }
  const double play_m = t.track_gauge_m - t.flange_back_distance_m;
  require(play_m >= kMinimumGaugeMinusFlangeBack_m && play_m <= kMaximumGaugeMinusFlangeBack_m, [&] {
    return fmt::format("the gauge {:g} m less the flange backs' distance {:g} m (--gauge-m, --flange-back-m) is {:g} m; "
                       "it must lie in [{:g}, {:g}] m (two flanges and their play: 0.075 m on standard gauge)",
                       t.track_gauge_m, t.flange_back_distance_m, play_m, kMinimumGaugeMinusFlangeBack_m,
                       kMaximumGaugeMinusFlangeBack_m);
  });
  description += fmt::format(", gauge {:g} mm, flange backs {:g} mm", t.track_gauge_m * 1e3,
                             t.flange_back_distance_m * 1e3);
  if (t.rail_cant_rad != 0.0) description += fmt::format(", rail cant {:g} rad", t.rail_cant_rad);
  return WheelsetTrack(wheel, rail, t);
}

int run_geometry(const GeometryArguments& a, const CLI::App& sub) {
  std::string description;
  const WheelsetTrack track = geometry_track(a, sub, description);
  study::ContactGeometryStudy s;
  s.y_from_m = a.y_from_m;
  s.y_to_m = a.y_to_m;
  s.y_step_m = a.y_step_m;
  s.amplitude_m = a.amplitude_m;
  s.stop_at_flange_climb = sub.count("--y-from-m") == 0 && sub.count("--y-to-m") == 0;
  study::validate(s);
  output::OutputDirectory out(a.out, &std::cerr);
  const study::ContactGeometryResult r = study::run_contact_geometry_study(track, s, out, std::cerr);
  out.commit();
  const EquivalentConicity& e = r.at_amplitude;
  if (a.json) {
    const nlohmann::json j = {
        {"railcontact_version", RC_VERSION_STRING},
        {"profiles", description},
        {"y_from_m", s.y_from_m},
        {"y_to_m", s.y_to_m},
        {"y_step_m", s.y_step_m},
        {"positions", r.sweep.size()},
        {"swept_from_m", r.swept_from_m},
        {"swept_to_m", r.swept_to_m},
        {"amplitude_m", e.amplitude_m},
        {"tan_gamma_e_wavelength", e.tan_gamma_e_wavelength},
        {"tan_gamma_e_regression", e.tan_gamma_e_regression},
        {"turning_points_m", {e.turning_point_low_m, e.turning_point_high_m}},
        {"centre_m", e.centre_m},
        {"largest_amplitude_m", r.largest_amplitude_m},
        {"half_contact_distance_m", r.half_contact_distance_m},
        {"nominal_rolling_radius_m", r.nominal_rolling_radius_m},
        {"klingel_wavelength_m",
         klingel_wavelength_m(e.tan_gamma_e_wavelength, r.half_contact_distance_m, r.nominal_rolling_radius_m)},
        {"out", a.out},
    };
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  fmt::print("Contact geometry of {} (rigid wheels and rails, yaw 0), {} positions y = {:g} ... {:g} mm\n",
             description, r.sweep.size(), r.swept_from_m * 1e3, r.swept_to_m * 1e3);
  fmt::print("Equivalent conicity at amplitude {:g} mm (EN 15302): tan γe = {:.4f} (kinematic wavelength, Annex B), "
             "{:.4f} (linear regression, Annex C)\n",
             a.amplitude_m * 1e3, e.tan_gamma_e_wavelength, e.tan_gamma_e_regression);
  fmt::print("Klingel wavelength {:.1f} m (e0 = {:.1f} mm, r0 = {:.0f} mm); amplitudes up to {:.2f} mm in "
             "conicity.csv\n",
             klingel_wavelength_m(e.tan_gamma_e_wavelength, r.half_contact_distance_m, r.nominal_rolling_radius_m),
             r.half_contact_distance_m * 1e3, r.nominal_rolling_radius_m * 1e3, r.largest_amplitude_m * 1e3);
  fmt::print("Wrote {}/geometry.csv, conicity.csv, profiles.csv (figures: contact_points.png, delta_r.png, "
             "contact_angles.png, conicity.png)\n",
             a.out);
  return 0;
}

}  // namespace

void add_geometry_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<GeometryArguments>();
  CLI::App* sub = app.add_subcommand(
      "geometry",
      "Rigid contact geometry of a wheelset over its lateral displacement (contact points, contact angles, rolling "
      "radii, Δr, roll) and the equivalent conicity after EN 15302 (docs/CONTACT_GEOMETRY.md)");
  sub->add_option("case", args->case_file, "wheelset case file (TOML): its profiles and track; default: S1002/UIC60");
  sub->add_option("--wheel", args->wheel_file, "wheel profile file (both wheels; .prw, .whl or y z text in mm)");
  sub->add_option("--rail", args->rail_file, "rail profile file (both rails; .prr, .ban or y z text in mm)");
  sub->add_option("--gauge-m", args->gauge_m, "track gauge (m; default 1.435)");
  sub->add_option("--flange-back-m", args->flange_back_m, "distance between the flange backs (m; default 1.36)");
  sub->add_option("--rolling-radius-m", args->radius_m, "nominal rolling radius r0 (m; default 0.46) at the wheel profile's origin (a set-up's track.nominal_radius_at may put it at the taping line)");
  sub->add_option("--rail-cant-rad", args->rail_cant_rad,
                  "rail inclination towards the track centre applied to the rail profile (rad, |x| <= 0.1; "
                  "default 0: the profile as given, the shipped UIC60 is inclined 1:40; 1:40 is 0.0249948)");
  sub->add_option("--y-from-m", args->y_from_m, "first lateral displacement (m, + to the left; default -0.006, or where the flange climbs)");
  sub->add_option("--y-to-m", args->y_to_m, "last lateral displacement (m, + to the left; default 0.006, or where the flange climbs)");
  sub->add_option("--y-step-m", args->y_step_m, "step of the lateral displacement (m, > 0; default 0.0001)");
  sub->add_option("--amplitude-m", args->amplitude_m, "amplitude of the equivalent conicity (m, > 0; default 0.003)");
  sub->add_flag("--json", args->json, "print the summary as one JSON object");
  sub->add_option("--out", args->out, "output directory (default railcontact-out/geometry)");
  sub->callback([&action, args, sub] { action = [args, sub] { return run_geometry(*args, *sub); }; });
}

}  // namespace railcontact::cli
