#include "tangential/steady_rolling_preconditioner.hpp"

#include <algorithm>
#include <cmath>

namespace railcontact {

SteadyRollingPreconditioner::SteadyRollingPreconditioner(const ContactElements& elements, double gamma)
    : count_(elements.count()),
      ahead_in_contact_(count_, 0),
      has_left_(count_, 0.0),
      has_right_(count_, 0.0),
      down_(count_, 0),
      up_(count_, 0),
      work_(2 * count_),
      padded_(count_ + 2, 0.0) {
  const Mesh& mesh = elements.mesh();
  const auto n1 = static_cast<std::size_t>(mesh.n1);
  const auto n2 = static_cast<std::size_t>(mesh.n2);
  dx1_ = mesh.dx1_m;
  inv_dx1_sq_ = 1.0 / (mesh.dx1_m * mesh.dx1_m);
  inv_dx2_sq_ = 1.0 / (mesh.dx2_m * mesh.dx2_m);
  const double size = std::sqrt(static_cast<double>(count_) * mesh.element_area_m2());
  c0_ = gamma * M_PI * M_PI / (size * std::sqrt(mesh.dx1_m * mesh.dx2_m));

  // where[k]: 1 + the element at mesh index k, 0 when not in contact (its index in padded_).
  std::vector<std::uint32_t> where(mesh.size(), 0);
  const auto& idx = elements.indices();
  for (std::size_t e = 0; e < count_; ++e) where[idx[e]] = static_cast<std::uint32_t>(e + 1);
  for (std::size_t e = 0; e < count_; ++e) {
    const std::size_t k = idx[e];
    const std::size_t i1 = k % n1, i2 = k / n1;
    // Elements are ordered strip by strip with x1 increasing: in contact, the neighbours along X1
    // are e - 1 and e + 1.
    has_left_[e] = i1 > 0 && where[k - 1] != 0 ? 1.0 : 0.0;
    has_right_[e] = i1 + 1 < n1 && where[k + 1] != 0 ? 1.0 : 0.0;
    if (i2 > 0) down_[e] = where[k - n1];
    if (i2 + 1 < n2) up_[e] = where[k + n1];
    ahead_in_contact_[e] = has_right_[e] != 0.0 ? 1 : 0;
  }
  // The strip-run start closest to the middle (element 0 when there is one run).
  for (std::size_t e = 0; e < count_; ++e) {
    const bool run_start = e == 0 || ahead_in_contact_[e - 1] == 0;
    const auto distance = [this](std::size_t x) { return x > count_ / 2 ? x - count_ / 2 : count_ / 2 - x; };
    if (run_start && distance(e) < distance(split_)) split_ = e;
  }
}

void SteadyRollingPreconditioner::march(const double* r, double* u) const {
  const std::size_t n = count_;
  // Elements are ordered strip by strip with x1 increasing: the element ahead is e + 1. March each
  // half of the elements from its end; element split_ - 1 ends a run, so the halves do not meet.
  const auto step = [&](std::size_t e, std::size_t end) {
    const bool ahead = e + 1 < end && ahead_in_contact_[e] != 0;
    u[e] = (ahead ? u[e + 1] : 0.0) - dx1_ * r[e];
    u[n + e] = (ahead ? u[n + e + 1] : 0.0) - dx1_ * r[n + e];
  };
  const std::size_t first = split_, second = n - split_;  // the halves' lengths
  for (std::size_t i = 0; i < std::max(first, second); ++i) {
    if (i < first) step(first - 1 - i, split_);
    if (i < second) step(n - 1 - i, n);
  }
}

void SteadyRollingPreconditioner::march_transpose(const double* r, double* u) const {
  const std::size_t n = count_;
  // Transpose of march(): u_e = u_{e-1} - dx1 r_e when element e - 1 (behind) is in contact; each
  // half from its start (split_ starts a run).
  const auto step = [&](std::size_t e, std::size_t begin) {
    const bool behind = e > begin && ahead_in_contact_[e - 1] != 0;
    u[e] = (behind ? u[e - 1] : 0.0) - dx1_ * r[e];
    u[n + e] = (behind ? u[n + e - 1] : 0.0) - dx1_ * r[n + e];
  };
  const std::size_t first = split_, second = n - split_;
  for (std::size_t i = 0; i < std::max(first, second); ++i) {
    if (i < first) step(i, 0);
    if (i < second) step(split_ + i, split_);
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
  double* const p = padded_.data();  // p[0] = p[n + 1] = 0
  // Locals and restrict-qualified pointers: the loop then vectorises (z aliases none of them).
  const double c0 = c0_, w1 = inv_dx1_sq_, w2 = inv_dx2_sq_;
  const double* __restrict left = has_left_.data();
  const double* __restrict right = has_right_.data();
  const std::uint32_t* __restrict down = down_.data();
  const std::uint32_t* __restrict up = up_.data();
  for (std::size_t c = 0; c < 2; ++c) {
    std::copy_n(source + c * n, n, p + 1);
    const double* __restrict u = p + 1;
    double* __restrict zc = z + c * n;
    for (std::size_t e = 0; e < n; ++e) {
      // u[e - 1] as p[e]: at e = 0 the unsigned e - 1 wrapped around, an overflowing pointer
      // addition (UBSan, fuzz/crashes/wheelset_table_lookup/), though it landed on p[0].
      const double laplacian =
          (left[e] * p[e] - 2.0 * u[e] + right[e] * u[e + 1]) * w1 + (p[down[e]] - 2.0 * u[e] + p[up[e]]) * w2;
      zc[e] = c0 * u[e] - laplacian;
    }
  }
}

}  // namespace railcontact
