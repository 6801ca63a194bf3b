// FastSim's per-patch strip geometry: march steps, traction bound (Eq 1 and its skewed form).
#include "tangential/fastsim_strips.hpp"

#include <cstddef>

namespace railcontact::fastsim_detail {

std::vector<double> march_steps_m(const ContactPatch& patch) {
  const double dx1_m = patch.mesh().dx1_m;
  std::vector<double> step(patch.elements().count(), -dx1_m);
  // Runs are stored trailing -> leading: the leading element is the run's last one.
  for (const StripRun& run : patch.runs()) {
    step[run.first + static_cast<std::size_t>(run.length()) - 1] = -0.5 * dx1_m;
  }
  return step;
}

std::vector<double> traction_bound_Pa(const ContactPatch& patch, double skew) {
  const Mesh& mesh = patch.mesh();
  const std::vector<double>& p3 = patch.pressure_Pa();
  std::vector<double> bound(p3.size(), 0.0);
  for (const StripRun& run : patch.runs()) {
    const double inverse_length = 1.0 / (run.x1_leading_m - run.x1_trailing_m);  // 1 / (x_l - x_t)
    const std::size_t end = run.first + static_cast<std::size_t>(run.length());
    double strip_force = 0.0, shape_sum = 0.0;  // per unit strip area: sum p3, sum of the bound's shape
    for (std::size_t e = run.first; e < end; ++e) {
      const double x1 = mesh.x1(run.i1_trailing + static_cast<int>(e - run.first));  // = patch.x1(e)
      const double t = (run.x1_leading_m - x1) * inverse_length;  // 0 at the leading edge, 1 at the trailing
      bound[e] = t * (1.0 - t) * (1.0 + skew * t);  // shape, > 0 at every centre inside the run
      shape_sum += bound[e];
      strip_force += p3[e];
    }
    const double height_Pa = strip_force / shape_sum;  // h (Eq 1 for skew = 0, up to the factor 4)
    for (std::size_t e = run.first; e < end; ++e) bound[e] *= height_Pa;
  }
  return bound;
}

}  // namespace railcontact::fastsim_detail
