// The wheelset's assembly stage (see the header).
#include "wheel_rail/wheelset_assembly.hpp"

#include <cmath>

#include "railcontact/error.hpp"

namespace railcontact::detail {

namespace {

void require_finite(const WheelsetResult& r) {
  bool ok = true;
  for (double f : r.force_track_N) ok = ok && std::isfinite(f);
  for (const WheelResult& w : r.wheels) {
    for (double f : w.force_track_N) ok = ok && std::isfinite(f);
    for (const WheelsetPatch& p : w.patches) {
      ok = ok && std::isfinite(p.normal_force_N) && std::isfinite(p.creepage.xi) && std::isfinite(p.creepage.eta) &&
           std::isfinite(p.creepage.phi);
      for (const PatchSolverResult& s : p.solvers)
        ok = ok && std::isfinite(s.forces.F1_N) && std::isfinite(s.forces.F2_N) && std::isfinite(s.forces.M3_Nm);
    }
  }
  if (!ok) throw Error(ErrorKind::internal, "wheelset: a result is not finite (a solver invariant broken)");
}

}  // namespace

void sum_wheel_forces(WheelResult& wheel, std::size_t solvers) {
  wheel.solver_force_track_N.assign(solvers, Vector3{});
  for (const WheelsetPatch& p : wheel.patches)
    for (std::size_t s = 0; s < solvers; ++s)
      for (std::size_t i = 0; i < 3; ++i) wheel.solver_force_track_N[s][i] += p.solvers[s].force_track_N[i];
  wheel.force_track_N = solvers > 0 ? wheel.solver_force_track_N.front() : Vector3{};
}

void sum_wheelset_forces(WheelsetResult& result, std::size_t solvers) {
  result.solver_force_track_N.assign(solvers, Vector3{});
  for (const WheelResult& w : result.wheels)
    for (std::size_t s = 0; s < solvers; ++s)
      for (std::size_t i = 0; i < 3; ++i) result.solver_force_track_N[s][i] += w.solver_force_track_N[s][i];
  result.force_track_N = solvers > 0 ? result.solver_force_track_N.front() : Vector3{};
  require_finite(result);
}

}  // namespace railcontact::detail
