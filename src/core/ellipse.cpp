#include "railcontact/ellipse.hpp"

#include <cmath>
#include <string>

#include "railcontact/error.hpp"

namespace railcontact {

ContactElements elliptical_contact(double a_m, double b_m, int n) {
  require(std::isfinite(a_m) && std::isfinite(b_m) && a_m > 0 && b_m > 0,
          "ellipse: semi-axes must be positive and finite");
  require(n >= 2, "ellipse: at least 2 elements per axis are needed");
  const Mesh mesh = Mesh::covering(-a_m, a_m, -b_m, b_m, n, n);
  validate(mesh);
  std::vector<std::uint8_t> flags(mesh.size(), 0);
  for (int i2 = 0; i2 < n; ++i2) {
    const double y = mesh.x2(i2) / b_m;
    for (int i1 = 0; i1 < n; ++i1) {
      const double x = mesh.x1(i1) / a_m;
      flags[mesh.index(i1, i2)] = (x * x + y * y < 1.0) ? 1 : 0;
    }
  }
  return ContactElements(mesh, std::move(flags));
}

ContactElements elliptical_contact_with_count(double a_m, double b_m, int target_elements) {
  require(target_elements >= 4, "ellipse: the number of elements in contact must be at least 4, got " +
                                    std::to_string(target_elements));
  require(target_elements <= 4'000'000,
          "ellipse: " + std::to_string(target_elements) + " elements in contact would not fit in memory");
  const int n = std::max(2, static_cast<int>(std::lround(std::sqrt(4.0 * target_elements / M_PI))));
  return elliptical_contact(a_m, b_m, n);
}

}  // namespace railcontact
