#include "railcontact/contact_patch.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "railcontact/error.hpp"

namespace railcontact {

ContactElements elliptical_contact(double a_m, double b_m, int n1, int n2) {
  require(std::isfinite(a_m) && std::isfinite(b_m) && a_m > 0 && b_m > 0,
          "ellipse: semi-axes must be positive and finite");
  require(n1 >= 2 && n2 >= 2, "ellipse: at least 2 elements per axis are needed");
  const Mesh mesh = Mesh::covering(-a_m, a_m, -b_m, b_m, n1, n2);
  validate(mesh);
  std::vector<std::uint8_t> flags(mesh.size(), 0);
  for (int i2 = 0; i2 < n2; ++i2) {
    const double y = mesh.x2(i2) / b_m;
    for (int i1 = 0; i1 < n1; ++i1) {
      const double x = mesh.x1(i1) / a_m;
      flags[mesh.index(i1, i2)] = (x * x + y * y < 1.0) ? 1 : 0;
    }
  }
  return ContactElements(mesh, std::move(flags));
}

ContactElements elliptical_contact(double a_m, double b_m, int n) { return elliptical_contact(a_m, b_m, n, n); }

ContactElements elliptical_contact_with_count(double a_m, double b_m, int target_elements, EllipseMeshLayout layout) {
  require(target_elements >= 4, [&] {
    return "ellipse: the number of elements in contact must be at least 4, got " + std::to_string(target_elements);
  });
  require(target_elements <= 4'000'000, [&] {
    return "ellipse: " + std::to_string(target_elements) + " elements in contact would not fit in memory";
  });
  require(std::isfinite(a_m) && std::isfinite(b_m) && a_m > 0 && b_m > 0,
          "ellipse: semi-axes must be positive and finite");
  // n1 n2 pi/4 = N with n1/n2 = 1 (equal counts) or max(1, a/b) (rolling resolved).
  const double ratio = layout == EllipseMeshLayout::equal_counts ? 1.0 : std::max(1.0, a_m / b_m);
  const int n2 = std::max(2, static_cast<int>(std::lround(std::sqrt(4.0 * target_elements / (M_PI * ratio)))));
  const int n1 = std::max(2, static_cast<int>(std::lround(ratio * n2)));
  return elliptical_contact(a_m, b_m, n1, n2);
}

}  // namespace railcontact
