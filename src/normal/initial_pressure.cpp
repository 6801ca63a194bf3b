// Hertz-like starting pressure for the normal solver; see the header.
#include "normal/initial_pressure.hpp"

#include <algorithm>
#include <cmath>

namespace railcontact::detail {
namespace {

// p = sqrt(1 - z/d) on z < d, scaled to sum p = pressure_sum (d > 0).
void fill_ellipsoidal(std::span<const double> h, double h_min, double d, double pressure_sum, std::span<double> p) {
  double sum = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double z = h[i] - h_min;
    p[i] = z < d ? std::sqrt(1.0 - z / d) : 0.0;
    sum += p[i];
  }
  const double scale = pressure_sum / sum;  // sum >= 1: the deepest element has p = 1
  for (double& value : p) value *= scale;
}

}  // namespace

void hertz_like_initial_pressure(InfluenceOperator& A, std::span<const double> h, double pressure_sum,
                                 std::span<double> p, std::vector<double>& work) {
  const std::size_t n = h.size();
  const auto [min_it, max_it] = std::minmax_element(h.begin(), h.end());
  const double h_min = *min_it;
  const double z_max = *max_it - h_min;
  if (!(z_max > 0.0)) {  // flat: every element touches at once; uniform pressure
    std::fill(p.begin(), p.end(), pressure_sum / static_cast<double>(n));
    return;
  }
  // Initial region: the lower quartile of z (or everything if a flat bottom is that large).
  work.assign(h.begin(), h.end());
  const auto quartile = work.begin() + static_cast<std::ptrdiff_t>(n / 4);
  std::nth_element(work.begin(), quartile, work.end());
  double d = *quartile - h_min;
  if (!(d > 0.0)) d = z_max;
  fill_ellipsoidal(h, h_min, d, pressure_sum, p);

  constexpr int kUpdates = 1;
  for (int update = 0; update < kUpdates; ++update) {
    A.apply_on_grid(p, work);
    // Least-squares slope of u = A p against z over the region p > 0.
    double count = 0.0, z_mean = 0.0, u_mean = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (p[i] > 0.0) {
        count += 1.0;
        z_mean += h[i] - h_min;
        u_mean += work[i];
      }
    }
    z_mean /= count;
    u_mean /= count;
    double zz = 0.0, zu = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (p[i] > 0.0) {
        const double dz = h[i] - h_min - z_mean;
        zz += dz * dz;
        zu += dz * (work[i] - u_mean);
      }
    }
    const double slope = zz > 0.0 ? -zu / zz : 0.0;
    if (!(slope > 0.0) || !std::isfinite(slope)) break;  // flat-bottomed region: keep it
    d *= std::cbrt(slope * slope);
    fill_ellipsoidal(h, h_min, d, pressure_sum, p);
  }
}

}  // namespace railcontact::detail
