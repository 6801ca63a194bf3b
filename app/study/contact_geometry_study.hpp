#pragma once
// The rigid contact geometry of a wheelset over a y-sweep and its equivalent conicity
// (`railcontact geometry`, docs/CONTACT_GEOMETRY.md): geometry.csv (one row per y), conicity.csv
// (tan γe against the amplitude, both methods), profiles.csv (the smoothed profiles, for the
// figures) and the figures of scripts/plot_contact_geometry.py.
#include <ostream>
#include <vector>

#include "railcontact/contact_geometry.hpp"
#include "output/output_directory.hpp"

#include "railcontact/error.hpp"

namespace railcontact::study {

struct ContactGeometryStudy {
  double y_from_m = -6e-3, y_to_m = 6e-3, y_step_m = 0.1e-3;
  double amplitude_m = 3e-3;          // the amplitude of the summary
  double amplitude_step_m = 0.1e-3;   // conicity.csv: ŷ = 0.5 mm, 0.6 mm, ... up to the largest allowed
  double first_amplitude_m = 0.5e-3;
  // The default range: positions beyond flange climb at either end (a worn or thin flange climbs
  // before ±6 mm) are left out and the swept range ends there; a range the user gave is kept whole
  // (a position beyond flange climb is an error).
  bool stop_at_flange_climb = false;
};

// The rigid contact geometry's refusal of a position beyond flange contact (check_flange in
// src/geometry/contact_geometry.cpp): where a default y range ends.
bool is_flange_climb(const Error& e);

struct ContactGeometryResult {
  std::vector<RigidContactGeometry> sweep;
  double swept_from_m = 0.0, swept_to_m = 0.0;  // the first and last y swept
  EquivalentConicity at_amplitude;
  double largest_amplitude_m = 0.0;
  double half_contact_distance_m = 0.0;  // e0: half the lateral distance of the contact points at y_c
  double nominal_rolling_radius_m = 0.0;
  int conicity_rows = 0;
};

// Throws Error naming the option (--y-from-m, --y-to-m, --y-step-m, --amplitude-m) and its allowed range.
void validate(const ContactGeometryStudy& study);

// Sweeps y, writes the CSV files into `out` and draws the figures (progress to `log`). Throws Error
// naming the option (--y-from-m, --y-to-m, --y-step-m, --amplitude-m) for a bad range or amplitude.
ContactGeometryResult run_contact_geometry_study(const WheelsetTrack& track, const ContactGeometryStudy& study,
                                                 output::OutputDirectory& out, std::ostream& log);

}  // namespace railcontact::study
