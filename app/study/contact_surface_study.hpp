#pragma once
// `railcontact study surfaces` (docs/WHEELSET.md §4 "Choosing the surface"): where the planar
// contact surface stops being trustworthy, and whether the automatic surface is smooth. Each
// wheel–rail set-up by load from y = 0 towards the right wheel's flange until the flange climbs,
// at each yaw, with the exact solver on the planar and on the conformal surface: per patch the
// difference of the two surfaces' track-frame forces against the automatic surface's measure
// (contact angle spread / cos γ, ContactSurfaceSwitch), and the automatic surface's own forces.
// Then, per set-up at the first yaw, the lateral window where the right wheel's conformal weight
// changes most, swept in fine steps with all three surfaces: the largest step of the automatic
// surface's forces against the planar and conformal ones'.
#include <filesystem>
#include <ostream>
#include <vector>

#include "railcontact/wheelset.hpp"

namespace railcontact::study {

struct ContactSurfaceStudyOptions {
  std::filesystem::path output_directory;
  // Wheel–rail set-up files; empty: every *.json of the shipped data/wheel_rail/.
  std::vector<std::filesystem::path> setups;
  double element_size_m = 0.2e-3;   // the accuracy targets' mesh
  double y_step_m = 0.25e-3;        // of the sweeps
  double fine_y_step_m = 0.01e-3;   // of the window where the automatic surface blends
  std::vector<double> yaws_rad{0.0, -0.01};
  ContactSurfaceSwitch surface_switch{};
  bool figures = true;
};

// Writes surfaces.csv (one row per patch and state), smoothness.csv (the fine windows, one row per
// state), summary.md and the figure; progress with the time left on `log`. Throws Error for a
// set-up that cannot be read or whose centred wheelset has no contact.
void run_contact_surface_study(const ContactSurfaceStudyOptions& options, std::ostream& log);

}  // namespace railcontact::study
