// A contact patch cut out of a potential-contact-area mesh (see the header).
#include "wheel_rail/cropped_patch.hpp"

#include <algorithm>

namespace railcontact::detail {

IndexBox bounding_box(const Mesh& mesh, const std::vector<std::size_t>& elements) {
  IndexBox box{mesh.n1, -1, mesh.n2, -1};
  for (std::size_t k : elements) {
    const int i1 = static_cast<int>(k % static_cast<std::size_t>(mesh.n1));
    const int i2 = static_cast<int>(k / static_cast<std::size_t>(mesh.n1));
    box.lo1 = std::min(box.lo1, i1);
    box.hi1 = std::max(box.hi1, i1);
    box.lo2 = std::min(box.lo2, i2);
    box.hi2 = std::max(box.hi2, i2);
  }
  return box;
}

ContactPatch cropped_patch(const Mesh& mesh, const std::vector<double>& pressure_Pa,
                           const std::vector<std::size_t>& elements, const Material& material) {
  const IndexBox box = bounding_box(mesh, elements);
  Mesh crop = mesh;
  crop.n1 = std::max(box.hi1 - box.lo1 + 1, 1);
  crop.n2 = std::max(box.hi2 - box.lo2 + 1, 1);
  crop.x1_first_m = mesh.x1(std::min(box.lo1, mesh.n1 - 1));
  crop.x2_first_m = mesh.x2(std::min(box.lo2, mesh.n2 - 1));
  std::vector<double> p(crop.size(), 0.0);
  for (std::size_t k : elements) {
    const int i1 = static_cast<int>(k % static_cast<std::size_t>(mesh.n1));
    const int i2 = static_cast<int>(k / static_cast<std::size_t>(mesh.n1));
    p[crop.index(i1 - box.lo1, i2 - box.lo2)] = pressure_Pa[k];
  }
  return ContactPatch(crop, p, material);
}

}  // namespace railcontact::detail
