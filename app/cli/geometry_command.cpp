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
#include "study/output_directory.hpp"

namespace railcontact::cli {
namespace {

struct GeometryArguments {
  std::string case_file;
  std::string wheel_file, rail_file;
  double gauge_mm = 0.0, flange_back_mm = 0.0, radius_mm = 0.0;
  double y_from_mm = -6.0, y_to_mm = 6.0, y_step_mm = 0.1;
  double amplitude_mm = 3.0;
  bool json = false;
  std::string out = "railcontact-out/geometry";
};

Profile read_option_profile(const std::string& option, const std::string& file) {
  try {
    return read_profile(file);
  } catch (const Error& e) {
    throw Error(e.kind(), fmt::format("{} {}: {}", option, file, e.what()));
  }
}

// The track: the case file's, or the shipped S1002/UIC60 set-up with --wheel, --rail and the track
// options applied.
WheelsetTrack geometry_track(const GeometryArguments& a, const CLI::App& sub, std::string& description) {
  const auto given = [&](const char* option) { return sub.count(option) > 0; };
  if (!a.case_file.empty()) {
    for (const char* option : {"--wheel", "--rail", "--gauge", "--flange-back", "--rolling-radius"}) {
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
  const Profile wheel = a.wheel_file.empty() ? read_profile(setup.wheel_profile) : read_option_profile("--wheel", a.wheel_file);
  const Profile rail = a.rail_file.empty() ? read_profile(setup.rail_profile) : read_option_profile("--rail", a.rail_file);
  if (!a.wheel_file.empty() || !a.rail_file.empty()) {
    description = fmt::format("wheel {}, rail {}", a.wheel_file.empty() ? setup.wheel_profile.filename().string() : a.wheel_file,
                              a.rail_file.empty() ? setup.rail_profile.filename().string() : a.rail_file);
  }
  TrackWheelsetParameters& t = setup.track;
  // The ranges of the library (geometry.hpp), in the options' millimetres.
  const auto length_mm = [&](const char* option, double value_mm, double low_m, double high_m) {
    require(std::isfinite(value_mm) && value_mm >= low_m * 1e3 && value_mm <= high_m * 1e3, [&] {
      return fmt::format("{} {:g} mm must lie in [{:g}, {:g}] mm", option, value_mm, low_m * 1e3, high_m * 1e3);
    });
    return value_mm * 1e-3;
  };
  if (given("--gauge")) t.track_gauge_m = length_mm("--gauge", a.gauge_mm, kMinimumTrackGauge_m, kMaximumTrackGauge_m);
  if (given("--flange-back"))
    t.flange_back_distance_m =
        length_mm("--flange-back", a.flange_back_mm, kMinimumFlangeBackDistance_m, kMaximumFlangeBackDistance_m);
  if (given("--rolling-radius"))
    t.nominal_rolling_radius_m =
        length_mm("--rolling-radius", a.radius_mm, kMinimumNominalRollingRadius_m, kMaximumNominalRollingRadius_m);
  const double play_m = t.track_gauge_m - t.flange_back_distance_m;
  require(play_m >= kMinimumGaugeMinusFlangeBack_m && play_m <= kMaximumGaugeMinusFlangeBack_m, [&] {
    return fmt::format("the gauge {:g} mm less the flange backs' distance {:g} mm (--gauge, --flange-back) is {:g} mm; "
                       "it must lie in [{:g}, {:g}] mm (two flanges and their play: 75 mm on standard gauge)",
                       t.track_gauge_m * 1e3, t.flange_back_distance_m * 1e3, play_m * 1e3,
                       kMinimumGaugeMinusFlangeBack_m * 1e3, kMaximumGaugeMinusFlangeBack_m * 1e3);
  });
  description += fmt::format(", gauge {:g} mm, flange backs {:g} mm", t.track_gauge_m * 1e3,
                             t.flange_back_distance_m * 1e3);
  return WheelsetTrack(wheel, rail, t);
}

int run_geometry(const GeometryArguments& a, const CLI::App& sub) {
  std::string description;
  const WheelsetTrack track = geometry_track(a, sub, description);
  study::ContactGeometryStudy s;
  s.y_from_m = a.y_from_mm * 1e-3;
  s.y_to_m = a.y_to_mm * 1e-3;
  s.y_step_m = a.y_step_mm * 1e-3;
  s.amplitude_m = a.amplitude_mm * 1e-3;
  study::validate(s);
  study::OutputDirectory out(a.out, &std::cerr);
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
             description, r.sweep.size(), a.y_from_mm, a.y_to_mm);
  fmt::print("Equivalent conicity at amplitude {:g} mm (EN 15302): tan γe = {:.4f} (kinematic wavelength, Annex B), "
             "{:.4f} (linear regression, Annex C)\n",
             a.amplitude_mm, e.tan_gamma_e_wavelength, e.tan_gamma_e_regression);
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
  sub->add_option("--gauge", args->gauge_mm, "track gauge (mm; default 1435)");
  sub->add_option("--flange-back", args->flange_back_mm, "distance between the flange backs (mm; default 1360)");
  sub->add_option("--rolling-radius", args->radius_mm, "nominal rolling radius at the taping line (mm; default 460)");
  sub->add_option("--y-from", args->y_from_mm, "first lateral displacement (mm, + to the left; default -6)");
  sub->add_option("--y-to", args->y_to_mm, "last lateral displacement (mm; default 6)");
  sub->add_option("--y-step", args->y_step_mm, "step of the lateral displacement (mm; default 0.1)");
  sub->add_option("--amplitude", args->amplitude_mm, "amplitude of the equivalent conicity (mm; default 3)");
  sub->add_flag("--json", args->json, "print the summary as one JSON object");
  sub->add_option("--out", args->out, "output directory (default railcontact-out/geometry)");
  sub->callback([&action, args, sub] { action = [args, sub] { return run_geometry(*args, *sub); }; });
}

}  // namespace railcontact::cli
