// Stencil preconditioner of the normal iteration; see the header.
#include "normal/contact_laplacian_preconditioner.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace railcontact::detail {

ContactLaplacianPreconditioner::ContactLaplacianPreconditioner(const Mesh& mesh, double gamma)
    : mesh_(mesh),
      gamma_(gamma),
      inv_dx1_sq_(1.0 / (mesh.dx1_m * mesh.dx1_m)),
      inv_dx2_sq_(1.0 / (mesh.dx2_m * mesh.dx2_m)) {}

void ContactLaplacianPreconditioner::apply(std::span<const double> contact_mask, std::size_t contact_count,
                                           std::span<const double> r, std::span<double> z) const {
  const double size_m = std::sqrt(static_cast<double>(contact_count) * mesh_.element_area_m2());
  const double c0 = gamma_ * std::numbers::pi * std::numbers::pi / (size_m * std::sqrt(mesh_.dx1_m * mesh_.dx2_m));
  const auto n1 = static_cast<std::size_t>(mesh_.n1);
  const auto n2 = static_cast<std::size_t>(mesh_.n2);
  // r on Ic, 0 outside (Dirichlet) and beyond the mesh: rows -1 and n2 of masked_ are zero.
  masked_.resize((n2 + 2) * n1);
  std::fill_n(masked_.begin(), n1, 0.0);
  std::fill_n(masked_.end() - static_cast<std::ptrdiff_t>(n1), n1, 0.0);
  double* const v = masked_.data() + n1;  // row 0
  for (std::size_t k = 0; k < n1 * n2; ++k) v[k] = contact_mask[k] * r[k];
  const double w1 = inv_dx1_sq_, w2 = inv_dx2_sq_;
  // z = c0 r - Laplacian_h r on Ic (r = v there), 0 elsewhere (the mask's product: the stencil is
  // finite).
  const auto stencil = [&](double left, double centre, double right, double down, double up) {
    return c0 * centre - ((left - 2.0 * centre + right) * w1 + (down - 2.0 * centre + up) * w2);
  };
  for (std::size_t i2 = 0; i2 < n2; ++i2) {
    const double* row = v + i2 * n1;
    const double* down = row - n1;
    const double* up = row + n1;
    const double* in = contact_mask.data() + i2 * n1;
    double* out = z.data() + i2 * n1;
    if (n1 == 1) {
      out[0] = in[0] * stencil(0.0, row[0], 0.0, down[0], up[0]);
      continue;
    }
    out[0] = in[0] * stencil(0.0, row[0], row[1], down[0], up[0]);
    for (std::size_t i1 = 1; i1 + 1 < n1; ++i1)
      out[i1] = in[i1] * stencil(row[i1 - 1], row[i1], row[i1 + 1], down[i1], up[i1]);
    const std::size_t last = n1 - 1;
    out[last] = in[last] * stencil(row[last - 1], row[last], 0.0, down[last], up[last]);
  }
}

}  // namespace railcontact::detail
