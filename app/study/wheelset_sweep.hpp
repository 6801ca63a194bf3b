#pragma once
// A sweep of the wheelset over its lateral displacement (docs/WHEELSET.md §7): one evaluation per
// y, one CSV row per patch (wheelset_sweep.csv) and the figures of scripts/plot_wheelset_sweep.py.
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "railcontact/error.hpp"

#include "railcontact/wheelset.hpp"
#include "output/output_directory.hpp"

namespace railcontact::study {

struct WheelsetSweep {
  double y_from_m = 0.0, y_to_m = 0.0, y_step_m = 0.1e-3;
};

// What a sweep did: the evaluations written and, when a position after the first could not be
// evaluated (typically the flange climbing over the rail: the end of the y range this wheelset can
// reach), where and why it stopped.
struct WheelsetSweepResult {
  int evaluations = 0;
  bool stopped = false;
  double stopped_at_y_m = 0.0;
  ErrorKind stop_kind = ErrorKind::invalid_input;
  std::string stop_message;
};

// Evaluates the wheelset at y_from, y_from ± step, ... up to y_to (the other state values as in
// `state`), writes the CSV into `out` and draws the figures. Progress with the time left goes to
// `log`. A position that fails after the first ends the sweep: the rows before it are written and
// the result says where and why (the first position failing throws).
WheelsetSweepResult run_wheelset_sweep(Wheelset& wheelset, const WheelsetState& state, const WheelsetSweep& sweep,
                                       output::OutputDirectory& out, std::ostream& log);
// The same with another evaluation of a state (e.g. WheelsetTable::evaluate) whose patches carry
// the forces of `solvers`, in that order.
using WheelsetEvaluation = std::function<WheelsetResult(const WheelsetState&)>;
WheelsetSweepResult run_wheelset_sweep(const WheelsetEvaluation& evaluate, const std::vector<TangentialSolver>& solvers,
                                       const WheelsetState& state, const WheelsetSweep& sweep, output::OutputDirectory& out,
                                       std::ostream& log);

}  // namespace railcontact::study
