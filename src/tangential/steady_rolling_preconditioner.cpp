#include "tangential/steady_rolling_preconditioner.hpp"

#include <cmath>

namespace railcontact {

SteadyRollingPreconditioner::SteadyRollingPreconditioner(const ContactElements& elements, double gamma)
    : count_(elements.count()),
      ahead_in_contact_(count_, 0),
      left_(count_, kOutside),
      right_(count_, kOutside),
      down_(count_, kOutside),
      up_(count_, kOutside),
      work_(2 * count_) {
  const Mesh& mesh = elements.mesh();
  const auto n1 = static_cast<std::size_t>(mesh.n1);
  const auto n2 = static_cast<std::size_t>(mesh.n2);
  dx1_ = mesh.dx1_m;
  inv_dx1_sq_ = 1.0 / (mesh.dx1_m * mesh.dx1_m);
  inv_dx2_sq_ = 1.0 / (mesh.dx2_m * mesh.dx2_m);
  const double size = std::sqrt(static_cast<double>(count_) * mesh.element_area_m2());
  c0_ = gamma * M_PI * M_PI / (size * std::sqrt(mesh.dx1_m * mesh.dx2_m));

  std::vector<std::int32_t> where(mesh.size(), kOutside);
  const auto& idx = elements.indices();
  for (std::size_t e = 0; e < count_; ++e) where[idx[e]] = static_cast<std::int32_t>(e);
  for (std::size_t e = 0; e < count_; ++e) {
    const std::size_t k = idx[e];
    const std::size_t i1 = k % n1, i2 = k / n1;
    if (i1 > 0) left_[e] = where[k - 1];
    if (i1 + 1 < n1) right_[e] = where[k + 1];
    if (i2 > 0) down_[e] = where[k - n1];
    if (i2 + 1 < n2) up_[e] = where[k + n1];
    ahead_in_contact_[e] = right_[e] != kOutside ? 1 : 0;
  }
}

void SteadyRollingPreconditioner::march(const double* r, double* u) const {
  const std::size_t n = count_;
  // Elements are ordered strip by strip with x1 increasing: the element ahead is e + 1.
  for (std::size_t e = n; e-- > 0;) {
    const bool ahead = ahead_in_contact_[e] != 0;
    u[e] = (ahead ? u[e + 1] : 0.0) - dx1_ * r[e];
    u[n + e] = (ahead ? u[n + e + 1] : 0.0) - dx1_ * r[n + e];
  }
}

void SteadyRollingPreconditioner::march_transpose(const double* r, double* u) const {
  const std::size_t n = count_;
  // Transpose of march(): u_e = u_{e-1} - dx1 r_e when element e - 1 (behind) is in contact.
  for (std::size_t e = 0; e < n; ++e) {
    const bool behind = e > 0 && ahead_in_contact_[e - 1] != 0;
    u[e] = (behind ? u[e - 1] : 0.0) - dx1_ * r[e];
    u[n + e] = (behind ? u[n + e - 1] : 0.0) - dx1_ * r[n + e];
  }
}

void SteadyRollingPreconditioner::apply(const double* r, double* z) const {
  if (c0_ <= 0.0) {
    march(r, z);
    return;
  }
  march(r, work_.data());
  apply_stencil(work_.data(), z);
}

void SteadyRollingPreconditioner::apply_transpose(const double* r, double* z) const {
  if (c0_ <= 0.0) {
    march_transpose(r, z);
    return;
  }
  apply_stencil(r, work_.data());  // the stencil is symmetric
  march_transpose(work_.data(), z);
}

void SteadyRollingPreconditioner::apply_stencil(const double* source, double* z) const {
  const std::size_t n = count_;
  for (std::size_t c = 0; c < 2; ++c) {
    const double* u = source + c * n;
    double* zc = z + c * n;
    auto at = [u](std::int32_t j) { return j == kOutside ? 0.0 : u[j]; };
    for (std::size_t e = 0; e < n; ++e) {
      const double laplacian = (at(left_[e]) - 2.0 * u[e] + at(right_[e])) * inv_dx1_sq_ +
                               (at(down_[e]) - 2.0 * u[e] + at(up_[e])) * inv_dx2_sq_;
      zc[e] = c0_ * u[e] - laplacian;
    }
  }
}

}  // namespace railcontact
