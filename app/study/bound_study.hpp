#pragma once
// `railcontact study bound`: how FastSim's traction-bound skew (TractionBound, docs/FASTSIM.md
// "Traction bound skewed towards the trailing edge") affects nH-FastSim's creep-force error
// against `exact`: the calibration on Hertzian ellipses a/b = 0.1 ... 10 and the check on the
// S1002/UIC60 patches. Writes bound_sweep.csv and summary.md.
#include <filesystem>
#include <ostream>

namespace railcontact::study {

struct BoundStudyOptions {
  std::filesystem::path output_directory;
  int elements = 3000;       // elements in contact per patch
  double y_step_m = 0.5e-3;  // wheel-rail positions from -4.5 to 4.5 mm
  int threads = 1;           // the patches on threads (the files do not depend on it)
};

void run_bound_study(const BoundStudyOptions& options, std::ostream& progress);

}  // namespace railcontact::study
