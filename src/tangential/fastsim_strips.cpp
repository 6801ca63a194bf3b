// FastSim's per-patch strip geometry: march steps, traction bound (Eq 1 and its skewed form), S D B (Eq 19).
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

Eigen::Matrix3d adhesion_force_matrix(const ContactPatch& patch, const std::vector<double>& step) {
  const Mesh& mesh = patch.mesh();
  // Columns: unit xi, unit eta, unit phi (with L = 1); rows F1, F2, M3 / S.
  Eigen::Matrix3d DB = Eigen::Matrix3d::Zero();
  for (const StripRun& run : patch.runs()) {
    const double x2 = mesh.x2(run.i2);  // = patch.x2(run.first), without a division
    double p1_xi = 0.0, p2_eta = 0.0, p1_phi = 0.0, p2_phi = 0.0;
    for (std::size_t k = static_cast<std::size_t>(run.length()); k-- > 0;) {  // leading -> trailing
      const std::size_t e = run.first + k;
      const double x1 = mesh.x1(run.i1_trailing + static_cast<int>(k));  // = patch.x1(e)
      p1_xi += step[e];
      p2_eta += step[e];
      p1_phi += -x2 * step[e];
      p2_phi += spin_step_m2(step[e], x1);
      DB(0, 0) += p1_xi;
      DB(2, 0) += -x2 * p1_xi;
      DB(1, 1) += p2_eta;
      DB(2, 1) += x1 * p2_eta;
      DB(0, 2) += p1_phi;
      DB(1, 2) += p2_phi;
      DB(2, 2) += x1 * p2_phi - x2 * p1_phi;
    }
  }
  return patch.mesh().element_area_m2() * DB;
}

}  // namespace railcontact::fastsim_detail
