#pragma once
// Stage: assembly, the last of the wheelset's (docs/ARCHITECTURE.md): a wheel's forces from its
// patches, the wheelset's from its wheels. Wheelset::evaluate and WheelsetTable::evaluate, two
// providers of patches, assemble their results here.
#include <cstddef>

#include "railcontact/wheelset.hpp"

namespace railcontact::detail {

// The wheel's contact force per solver (solver_force_track_N: its patches' PatchSolverResult::
// force_track_N summed, in the order of the patches' solvers) and the first solver's (force_track_N).
// Every patch carries `solvers` results.
void sum_wheel_forces(WheelResult& wheel, std::size_t solvers);

// The wheelset's contact force per solver and the first solver's, from its wheels'. Throws Error
// (internal) unless every force, creepage and normal force of the result is finite.
void sum_wheelset_forces(WheelsetResult& result, std::size_t solvers);

}  // namespace railcontact::detail
