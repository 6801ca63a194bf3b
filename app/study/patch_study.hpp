#pragma once
// `railcontact study patches`: the wheel–rail normal contact of the paper's test set (METHOD.md
// §9) over the wheelset displacement y: contact position and angle, patch size and shape,
// pressure, compared with Hertz for the local curvatures (docs/WHEEL_RAIL.md §6).
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

namespace railcontact::study {

struct PatchStudyOptions {
  std::filesystem::path output_directory;
  // y from y_from to y_to (inclusive) in steps of y_step (m): the paper's range by default.
  double y_from_m = -4.5e-3;
  double y_to_m = 4.5e-3;
  double y_step_m = 0.5e-3;
  double vertical_load_N = 98100;
  int elements = 3000;
  // Profile files; the shipped S1002 / UIC60 1:40 when empty.
  std::optional<std::filesystem::path> wheel_profile;
  std::optional<std::filesystem::path> rail_profile;
  bool figures = true;
  int threads = 1;  // the y values on threads (the files do not depend on it)
};

// Writes patches.csv (one row per y with a status column: single / several_patches / error),
// patch_y<±mm>mm.csv (the pressure of each solved patch), contact_position.png,
// patch_shapes.png and summary.md into the output directory; progress goes to `progress`.
// Returns the number of y values that gave a single patch.
int run_patch_study(const PatchStudyOptions& options, std::ostream& progress);

}  // namespace railcontact::study
