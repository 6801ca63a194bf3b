#pragma once
// The wheel–rail set-ups a study sweeps: the files given, or every shipped one, and the wheelset
// track of one (its profiles read as they are, with its track dimensions).
#include <filesystem>
#include <vector>

#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact::study {

// `given` when not empty, else every *.json of the shipped data/wheel_rail/, by name.
std::vector<std::filesystem::path> wheel_rail_setup_files(const std::vector<std::filesystem::path>& given);

WheelsetTrack wheelset_track_of(const WheelRailSetup& setup);

// A sweep's options, named as the study's command line has them: --element-size-m in [0.05, 2]
// mm, --y-step-m in [0.01, largest_y_step_m / 1 mm] mm, --yaw-rad 1 to 10 angles within ±0.05 rad.
void validate_sweep(double element_size_m, double y_step_m, double largest_y_step_m, const std::vector<double>& yaws_rad);

}  // namespace railcontact::study
