// The rigid contact geometry over a y-sweep and the equivalent conicity (see the header).
#include "study/contact_geometry_study.hpp"

#include <fmt/core.h>
#include <fmt/ostream.h>

#include <cerrno>
#include <algorithm>
#include <cmath>
#include <string_view>
#include <fstream>
#include <string>

#include "railcontact/error.hpp"
#include "output/output_directory.hpp"
#include "output/figures.hpp"

namespace railcontact::study {
namespace {

constexpr double kMm = 1e-3;

std::ofstream open_csv(const std::filesystem::path& path) {
  std::ofstream csv(path);
  if (!csv) throw output::write_error(path, errno);
  return csv;
}

void close_csv(std::ofstream& csv, const std::filesystem::path& path) {
  csv.close();
  if (csv.fail()) throw output::write_error(path, errno);
}

}  // namespace

void validate(const ContactGeometryStudy& s) {
  require(std::isfinite(s.y_from_m) && std::abs(s.y_from_m) <= 0.1, [&] {
    return fmt::format("--y-from-m {:g} m must be finite and lie in [-0.1, 0.1] m", s.y_from_m);
  });
  require(std::isfinite(s.y_to_m) && std::abs(s.y_to_m) <= 0.1, [&] {
    return fmt::format("--y-to-m {:g} m must be finite and lie in [-0.1, 0.1] m", s.y_to_m);
  });
  require(s.y_from_m < 0.0 && s.y_to_m > 0.0, [&] {
    return fmt::format("--y-from-m {:g} m and --y-to-m {:g} m must enclose the centred wheelset: --y-from-m < 0 < "
                       "--y-to-m",
                       s.y_from_m, s.y_to_m);
  });
  const double range = s.y_to_m - s.y_from_m;
  require(std::isfinite(s.y_step_m) && s.y_step_m >= 1e-6 && s.y_step_m <= 0.25 * range, [&] {
    return fmt::format("--y-step-m {:g} m must lie in [1e-06, {:g}] m (a quarter of the range --y-from-m .. --y-to-m)",
                       s.y_step_m, 0.25 * range);
  });
  require(range / s.y_step_m <= 20000.0, [&] {
    return fmt::format("--y-step-m {:g} m gives {:.0f} positions (at most 20000); use a larger step", s.y_step_m,
                       range / s.y_step_m + 1);
  });
  const double largest = std::min(-s.y_from_m, s.y_to_m);
  require(std::isfinite(s.amplitude_m) && s.amplitude_m > 0.0 && s.amplitude_m <= largest, [&] {
    return fmt::format("--amplitude-m {:g} m must lie in (0, {:g}] m: the motion must stay within the swept y = {:g} "
                       ".. {:g} m (widen --y-from-m / --y-to-m)",
                       s.amplitude_m, largest, s.y_from_m, s.y_to_m);
  });
}

bool is_flange_climb(const Error& e) {
  return std::string_view(e.what()).find("the flange is climbing") != std::string_view::npos;
}

namespace {

// The sweep from --y-from-m to --y-to-m (--y-to-m itself when the step divides the range), the
// positions beyond flange climb left out at either end with stop_at_flange_climb; progress to `log`.
std::vector<RigidContactGeometry> sweep_lateral_displacement(const WheelsetTrack& track,
                                                             const ContactGeometryStudy& study, std::ostream& log) {
  std::vector<RigidContactGeometry> sweep;
  const double range = study.y_to_m - study.y_from_m;
  const auto steps = static_cast<long>(std::floor(range / study.y_step_m + 1e-6));
  sweep.reserve(static_cast<std::size_t>(steps) + 1);
  for (long k = 0; k <= steps; ++k) {
    const double y = k == steps && std::abs(range / study.y_step_m - static_cast<double>(steps)) < 1e-6
                         ? study.y_to_m
                         : study.y_from_m + static_cast<double>(k) * study.y_step_m;
    try {
      sweep.push_back(rigid_contact_geometry(track, y));
    } catch (const Error& e) {
      const bool climbs = is_flange_climb(e);
      if (study.stop_at_flange_climb && climbs && y < 0.0 && sweep.empty()) continue;  // not yet in range
      if (study.stop_at_flange_climb && climbs && y > 0.0) break;                      // out of range
      throw Error(e.kind(), fmt::format("--y-from-m {:g} m .. --y-to-m {:g} m: at y = {:g} m: {}", study.y_from_m,
                                        study.y_to_m, y, e.what()));
    }
    if (sweep.size() == 1) {
      fmt::print(log, "contact geometry: y = {:g} ... {:g} mm in steps of {:g} mm\n", study.y_from_m / kMm,
                 study.y_to_m / kMm, study.y_step_m / kMm);
      if (k > 0) fmt::print(log, "  from y = {:+.3f} mm: the flange climbs beyond it\n", y / kMm);
    }
    if (k % 40 == 0 || k == steps) fmt::print(log, "  y = {:+.3f} mm ({}/{})\n", y / kMm, k + 1, steps + 1);
  }
  return sweep;
}

// The first and last y swept (where the flange climbs, with stop_at_flange_climb); at least 5
// positions for the equivalent conicity.
void record_swept_range(const ContactGeometryStudy& study, ContactGeometryResult& result, std::ostream& log) {
  require(result.sweep.size() >= 5, [&] {
    return fmt::format("y = {:g} .. {:g} m: fewer than 5 positions before the flange climbs", study.y_from_m, study.y_to_m);
  });
  result.swept_from_m = result.sweep.front().lateral_displacement_m;
  result.swept_to_m = result.sweep.back().lateral_displacement_m;
  if (result.swept_to_m < study.y_to_m - 0.5 * study.y_step_m)
    fmt::print(log, "  to y = {:+.3f} mm: the flange climbs beyond it\n", result.swept_to_m / kMm);
}

// The equivalent conicity at --amplitude-m, which the swept range must allow.
void conicity_at_amplitude(const ContactGeometryStudy& study, const RollingRadiusDifference& delta_r,
                           ContactGeometryResult& result) {
  result.largest_amplitude_m = largest_conicity_amplitude_m(delta_r);
  require(study.amplitude_m <= result.largest_amplitude_m, [&] {
    const bool clipped = result.swept_from_m > study.y_from_m + 0.5 * study.y_step_m ||
                         result.swept_to_m < study.y_to_m - 0.5 * study.y_step_m;
    return fmt::format("--amplitude-m {:g} m must lie in (0, {:.5f}] m: the motion must stay within the swept "
                       "y = {:g} .. {:g} m ({})",
                       study.amplitude_m, result.largest_amplitude_m, result.swept_from_m, result.swept_to_m,
                       clipped ? "the flange climbs beyond it: check the track's gauge and flange back distance"
                               : "widen --y-from-m / --y-to-m");
  });
  result.at_amplitude = equivalent_conicity(delta_r, study.amplitude_m);
}

// The swept position nearest y_c, the zero of Δr where the wheelset runs centred (the first of two
// as near).
const RigidContactGeometry& centred_position(const ContactGeometryResult& result) {
  const RigidContactGeometry* centred = &result.sweep.front();
  for (const RigidContactGeometry& g : result.sweep)
    if (std::abs(g.lateral_displacement_m - result.at_amplitude.centre_m) <
        std::abs(centred->lateral_displacement_m - result.at_amplitude.centre_m))
      centred = &g;
  return *centred;
}

// geometry.csv: one row per y swept.
void write_geometry_csv(const output::OutputDirectory& out, const std::vector<RigidContactGeometry>& sweep) {
  const std::filesystem::path geometry_path = out.path("geometry.csv");
  std::ofstream geometry = open_csv(geometry_path);
  fmt::print(geometry,
             "y_mm,roll_mrad,vertical_displacement_mm,delta_r_mm,delta_tan_gamma,"
             "right_rolling_radius_mm,left_rolling_radius_mm,right_contact_angle_rad,left_contact_angle_rad,"
             "right_wheel_profile_y_mm,right_wheel_profile_z_mm,right_rail_profile_y_mm,right_rail_profile_z_mm,"
             "left_wheel_profile_y_mm,left_wheel_profile_z_mm,left_rail_profile_y_mm,left_rail_profile_z_mm,"
             "right_contact_y_mm,right_contact_z_mm,left_contact_y_mm,left_contact_z_mm\n");
  for (const RigidContactGeometry& g : sweep) {
    fmt::print(geometry,
               "{:.6f},{:.8f},{:.8f},{:.8f},{:.8f},{:.6f},{:.6f},{:.8f},{:.8f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},"
               "{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}\n",
               g.lateral_displacement_m / kMm, g.roll_rad * 1e3, g.vertical_displacement_m / kMm,
               g.rolling_radius_difference_m / kMm,
               std::tan(g.left.contact_angle_rad) - std::tan(g.right.contact_angle_rad), g.right.rolling_radius_m / kMm,
               g.left.rolling_radius_m / kMm, g.right.contact_angle_rad, g.left.contact_angle_rad,
               g.right.wheel_profile_y_m / kMm, g.right.wheel_profile_z_m / kMm, g.right.rail_profile_y_m / kMm,
               g.right.rail_profile_z_m / kMm, g.left.wheel_profile_y_m / kMm, g.left.wheel_profile_z_m / kMm,
               g.left.rail_profile_y_m / kMm, g.left.rail_profile_z_m / kMm, g.right.point_track_m[1] / kMm,
               g.right.point_track_m[2] / kMm, g.left.point_track_m[1] / kMm, g.left.point_track_m[2] / kMm);
  }
  close_csv(geometry, geometry_path);
}

// conicity.csv: tan γe (both methods) and the Klingel wavelength from the first amplitude in its
// steps up to the largest allowed (that one the last row). Returns the rows written.
int write_conicity_csv(const output::OutputDirectory& out, const ContactGeometryStudy& study,
                       const RollingRadiusDifference& delta_r, const ContactGeometryResult& result) {
  const std::filesystem::path conicity_path = out.path("conicity.csv");
  std::ofstream conicity = open_csv(conicity_path);
  fmt::print(conicity,
             "amplitude_mm,tan_gamma_e_wavelength,tan_gamma_e_regression,turning_point_low_mm,turning_point_high_mm,"
             "klingel_wavelength_m\n");
  int rows = 0;
  for (int k = 0;; ++k) {
    double amplitude = study.first_amplitude_m + k * study.amplitude_step_m;
    if (amplitude > result.largest_amplitude_m + 1e-9) break;
    amplitude = std::min(amplitude, result.largest_amplitude_m);
    const EquivalentConicity e = equivalent_conicity(delta_r, amplitude);
    const double wavelength =
        e.tan_gamma_e_wavelength > 0.0
            ? klingel_wavelength_m(e.tan_gamma_e_wavelength, result.half_contact_distance_m,
                                   result.nominal_rolling_radius_m)
            : std::nan("");
    fmt::print(conicity, "{:.4f},{:.6f},{:.6f},{:.6f},{:.6f},{:.4f}\n", amplitude / kMm, e.tan_gamma_e_wavelength,
               e.tan_gamma_e_regression, e.turning_point_low_m / kMm, e.turning_point_high_m / kMm, wavelength);
    ++rows;
  }
  close_csv(conicity, conicity_path);
  return rows;
}

// profiles.csv: the smoothed profiles in their profile frames, for the contact-point figure.
void write_profiles_csv(const output::OutputDirectory& out, const WheelsetTrack& track) {
  const std::filesystem::path profiles_path = out.path("profiles.csv");
  std::ofstream profiles = open_csv(profiles_path);
  fmt::print(profiles, "side,body,y_mm,z_mm\n");
  for (WheelSide side : {WheelSide::right, WheelSide::left}) {
    const WheelRailPair& pair = track.pair(side);
    for (const auto& [body, profile] : {std::pair<const char*, const SmoothProfile*>{"wheel", &pair.wheel()},
                                        std::pair<const char*, const SmoothProfile*>{"rail", &pair.rail()}}) {
      const int samples = 600;
      for (int i = 0; i <= samples; ++i) {
        const ProfileCurvePoint p =
            profile->at(profile->s_begin_m() + (profile->s_end_m() - profile->s_begin_m()) * i / samples);
        fmt::print(profiles, "{},{},{:.5f},{:.5f}\n", side_name(side), body, p.y_m / kMm, p.z_m / kMm);
      }
    }
  }
  close_csv(profiles, profiles_path);
}

}  // namespace

ContactGeometryResult run_contact_geometry_study(const WheelsetTrack& track, const ContactGeometryStudy& study,
                                                 output::OutputDirectory& out, std::ostream& log) {
  validate(study);
  ContactGeometryResult result;
  result.sweep = sweep_lateral_displacement(track, study, log);
  record_swept_range(study, result, log);
  const RollingRadiusDifference delta_r(result.sweep);
  conicity_at_amplitude(study, delta_r, result);

  // e0 and r0 of the Klingel wavelength: at the centred running position.
  const RigidContactGeometry& centred = centred_position(result);
  result.half_contact_distance_m = 0.5 * (centred.left.point_track_m[1] - centred.right.point_track_m[1]);
  result.nominal_rolling_radius_m = track.parameters().nominal_rolling_radius_m;

  write_geometry_csv(out, result.sweep);
  result.conicity_rows = write_conicity_csv(out, study, delta_r, result);
  write_profiles_csv(out, track);
  output::draw_figures("plot_contact_geometry.py", out.staging(), log);
  return result;
}

}  // namespace railcontact::study
