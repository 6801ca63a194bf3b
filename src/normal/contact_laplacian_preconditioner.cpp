// Stencil preconditioner of the normal iteration; see the header.
#include "normal/contact_laplacian_preconditioner.hpp"

#include <cmath>
#include <numbers>

namespace railcontact::detail {

ContactLaplacianPreconditioner::ContactLaplacianPreconditioner(const Mesh& mesh, double gamma)
    : mesh_(mesh),
      gamma_(gamma),
      inv_dx1_sq_(1.0 / (mesh.dx1_m * mesh.dx1_m)),
      inv_dx2_sq_(1.0 / (mesh.dx2_m * mesh.dx2_m)) {}

void ContactLaplacianPreconditioner::apply(std::span<const std::uint8_t> in_contact, std::size_t contact_count,
                                           std::span<const double> r, std::span<double> z) const {
  const double size_m = std::sqrt(static_cast<double>(contact_count) * mesh_.element_area_m2());
  const double c0 = gamma_ * std::numbers::pi * std::numbers::pi / (size_m * std::sqrt(mesh_.dx1_m * mesh_.dx2_m));
  const auto n1 = static_cast<std::size_t>(mesh_.n1);
  const auto n2 = static_cast<std::size_t>(mesh_.n2);
  // r on Ic, 0 outside (Dirichlet) and beyond the mesh.
  auto value = [&](std::size_t k) { return in_contact[k] != 0 ? r[k] : 0.0; };
  for (std::size_t i2 = 0; i2 < n2; ++i2) {
    for (std::size_t i1 = 0; i1 < n1; ++i1) {
      const std::size_t k = i2 * n1 + i1;
      if (in_contact[k] == 0) {
        z[k] = 0.0;
        continue;
      }
      const double centre = r[k];
      const double left = i1 > 0 ? value(k - 1) : 0.0;
      const double right = i1 + 1 < n1 ? value(k + 1) : 0.0;
      const double down = i2 > 0 ? value(k - n1) : 0.0;
      const double up = i2 + 1 < n2 ? value(k + n1) : 0.0;
      const double laplacian =
          (left - 2.0 * centre + right) * inv_dx1_sq_ + (down - 2.0 * centre + up) * inv_dx2_sq_;
      z[k] = c0 * centre - laplacian;
    }
  }
}

}  // namespace railcontact::detail
