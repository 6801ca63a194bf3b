#pragma once
// `railcontact study profiles` (docs/VALIDATION.md "Other profile pairs"): each wheel–rail set-up
// checked end to end — the rigid contact geometry and its equivalent conicity, then the wheelset
// by load from y = 0 towards the right wheel's flange until the flange climbs, at each yaw, with
// the exact solver and nH-FastSim on every patch: the patches found, nH-FastSim against the exact
// solver, and the steps of the wheel forces, reference point and contact angle along y; and a
// wheelset table of the set-up, built with its nodes midway between the sweep's positions, against
// nH-FastSim on the fly at every state.
#include <filesystem>
#include <ostream>
#include <vector>

#include "railcontact/wheelset.hpp"

namespace railcontact::study {

struct ProfilePairStudyOptions {
  std::filesystem::path output_directory;
  // Wheel–rail set-up files (docs/WHEEL_RAIL.md "Set-up files"); empty: every *.json of the shipped
  // data/wheel_rail/.
  std::vector<std::filesystem::path> setups;
  double element_size_m = 0.2e-3;  // the accuracy targets' mesh
  double y_step_m = 0.1e-3;
  std::vector<double> yaws_rad{0.0, 0.01, -0.01};
  ContactSurface contact_surface = ContactSurface::planar;  // of the sweeps and the tables
  // Build a wheelset table per set-up and compare it with the sweep's on-the-fly states.
  bool table = true;
  int threads = 1;  // the table builds' threads
  bool figures = true;
};

// Writes profile_pairs.csv (one row per patch), pairs.csv (one row per set-up and yaw),
// table_check.csv (one row per state and wheel, with `table`), summary.md and the figure; progress with the time left on `log`. Throws Error for a set-up that cannot be
// read or whose centred wheelset has no contact.
void run_profile_pair_study(const ProfilePairStudyOptions& options, std::ostream& log);

// Nadal's flange-climb limit of Y/Q at a contact angle (rad) and friction coefficient:
// (tan γ − μ)/(1 + μ tan γ). The study lists a state the wheelset table refuses apart (the flange
// climbs there) when a wheel's Y/Q is beyond it at the contact angle of its steepest patch.
double nadal_limit(double contact_angle_rad, double mu);

}  // namespace railcontact::study
