#pragma once
// A sweep of the wheelset over its lateral displacement (docs/WHEELSET.md §7): one evaluation per
// y, one CSV row per patch (wheelset_sweep.csv) and the figures of scripts/plot_wheelset_sweep.py.
#include <ostream>

#include "railcontact/wheelset.hpp"
#include "study/output_directory.hpp"

namespace railcontact::study {

struct WheelsetSweep {
  double y_from_m = 0.0, y_to_m = 0.0, y_step_m = 0.1e-3;
};

// Evaluates the wheelset at y_from, y_from ± step, ... up to y_to (the other state values as in
// `state`), writes the CSV into `out` and draws the figures. Progress with the time left goes to
// `log`. Returns the number of evaluations.
int run_wheelset_sweep(Wheelset& wheelset, const WheelsetState& state, const WheelsetSweep& sweep,
                       OutputDirectory& out, std::ostream& log);

}  // namespace railcontact::study
