#pragma once
// Files of a wheel–rail patch shared by `railcontact patch --out` and `railcontact study patches`:
// the pressure per contact element (CSV) and the patch as one JSON object.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact::study {

// x1_m, x2_m, pressure_Pa per element of the patch, coordinates in the contact frame (origin at
// the centre of pressure, X1 rolling direction, X2 towards the flange / gauge side).
void write_pressure_csv(const std::filesystem::path& path, const ContactPatch& patch);

// The patch's numbers: y, contact_angle_rad, rolling_radius_m, spin_per_m, normal_force_N,
// area_m2, elements_in_contact, extent_x1_m, extent_x2_m, max_pressure_Pa, approach_m,
// iterations, and more (contact point, mesh, Hertz comparison).
nlohmann::json patch_json(const WheelRailPatch& patch);

// A wheelset's patch as `railcontact wheelset --json` and `railcontact patch --contact-surface
// conformal|auto --json` write it: geometry, normal results, surface, and each solver's forces.
nlohmann::json wheelset_patch_json(const WheelsetPatch& patch);
nlohmann::json vector_json(const Vector3& v);

}  // namespace railcontact::study
