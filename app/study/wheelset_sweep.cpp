// A sweep of the wheelset over its lateral displacement (see the header).
#include "study/wheelset_sweep.hpp"

#include <fmt/core.h>
#include <fmt/ostream.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <fstream>

#include "railcontact/error.hpp"
#include "output/output_directory.hpp"
#include "output/figures.hpp"

namespace railcontact::study {

WheelsetSweepResult run_wheelset_sweep(Wheelset& wheelset, const WheelsetState& state, const WheelsetSweep& sweep,
                                       output::OutputDirectory& out, std::ostream& log) {
  return run_wheelset_sweep([&](const WheelsetState& s) { return wheelset.evaluate(s); }, wheelset.options().solvers,
                            state, sweep, out, log);
}

WheelsetSweepResult run_wheelset_sweep(const WheelsetEvaluation& evaluate, const std::vector<TangentialSolver>& solvers,
                                       const WheelsetState& state, const WheelsetSweep& sweep, output::OutputDirectory& out,
                                       std::ostream& log) {
  WheelsetSweepResult result;
  require(std::isfinite(sweep.y_from_m) && std::isfinite(sweep.y_to_m) && std::isfinite(sweep.y_step_m) &&
              sweep.y_step_m >= 1e-6 && sweep.y_step_m <= 10e-3,
          [&] {
            return fmt::format("wheelset sweep: the y step {:g} mm must lie in [0.001, 10] mm", sweep.y_step_m * 1e3);
          });
  const double span = sweep.y_to_m - sweep.y_from_m;
  const auto steps = static_cast<long>(std::floor(std::abs(span) / sweep.y_step_m + 1e-9));
  require(steps <= 100000, [&] {
    return fmt::format("wheelset sweep: {} evaluations asked for (at most 100000); use a larger step", steps + 1);
  });
  const double direction = span < 0.0 ? -1.0 : 1.0;

  const std::filesystem::path csv_path = out.path("wheelset_sweep.csv");
  std::ofstream csv(csv_path);
  if (!csv) throw output::write_error(csv_path, errno);
  fmt::print(csv,
             "y_mm,vertical_displacement_mm,roll_mrad,side,patch,patches,reference_x_mm,reference_y_mm,reference_z_mm,"
             "rail_profile_y_mm,wheel_profile_y_mm,contact_angle_rad,rolling_radius_mm,xi,eta,phi_per_m,"
             "normal_force_N,area_mm2,max_pressure_MPa,elements");
  for (TangentialSolver s : solvers) fmt::print(csv, ",{0}_F1_N,{0}_F2_N,{0}_M3_Nm", solver_name(s));
  fmt::print(csv, ",wheel_Fx_N,wheel_Fy_N,wheel_Fz_N\n");

  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k <= steps; ++k) {
    WheelsetState s = state;
    s.position.lateral_displacement_m = sweep.y_from_m + direction * static_cast<double>(k) * sweep.y_step_m;
    WheelsetResult r;
    try {
      r = evaluate(s);
    } catch (const Error& e) {
      if (k == 0) throw;
      result.stopped = true;
      result.stopped_at_y_m = s.position.lateral_displacement_m;
      result.stop_kind = e.kind();
      result.stop_message = e.what();
      fmt::print(log, "  y = {:+.3f} mm: stopped ({})\n", s.position.lateral_displacement_m * 1e3, e.what());
      break;
    }
    ++result.evaluations;
    for (const WheelResult& w : r.wheels) {
      for (std::size_t p = 0; p < w.patches.size(); ++p) {
        const WheelsetPatch& patch = w.patches[p];
        const InterpenetrationRegion& g = patch.region;
        fmt::print(csv, "{:.6f},{:.6f},{:.6f},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.8f},{:.6f},{:.8e},{:.8e},{:.8e},"
                        "{:.3f},{:.6f},{:.3f},{}",
                   s.position.lateral_displacement_m * 1e3, w.vertical_displacement_m * 1e3, r.state.position.roll_rad * 1e3,
                   side_name(w.side), p, w.patches.size(), g.reference_point_track_m[0] * 1e3,
                   g.reference_point_track_m[1] * 1e3, g.reference_point_track_m[2] * 1e3, g.rail_profile_y_m * 1e3,
                   g.wheel_profile_y_m * 1e3, g.contact_angle_rad, patch.rolling_radius_m * 1e3, patch.creepage.xi,
                   patch.creepage.eta, patch.creepage.phi, patch.normal_force_N, patch.area_m2 * 1e6,
                   patch.max_pressure_Pa * 1e-6, patch.elements_in_contact);
        for (const PatchSolverResult& sr : patch.solvers)
          fmt::print(csv, ",{:.3f},{:.3f},{:.5f}", sr.forces.F1_N, sr.forces.F2_N, sr.forces.M3_Nm);
        fmt::print(csv, ",{:.3f},{:.3f},{:.3f}\n", w.force_track_N[0], w.force_track_N[1], w.force_track_N[2]);
      }
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (k % 10 == 0 || k == steps) {
      fmt::print(log, "  y = {:+.3f} mm ({}/{}), {:.1f} s left\n", s.position.lateral_displacement_m * 1e3, k + 1,
                 steps + 1, elapsed / static_cast<double>(k + 1) * static_cast<double>(steps - k));
    }
  }
  csv.close();
  if (csv.fail()) throw output::write_error(csv_path, errno);
  output::draw_figures("plot_wheelset_sweep.py", out.staging(), log);
  return result;
}

}  // namespace railcontact::study
