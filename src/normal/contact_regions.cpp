// 4-neighbour connected-component labelling of the contact elements (flood fill with an
// explicit stack: no recursion depth limit on large patches).
#include "railcontact/normal.hpp"

#include <algorithm>

#include "railcontact/error.hpp"

namespace railcontact {

std::vector<ContactRegion> contact_regions(const Mesh& mesh, const std::vector<double>& pressure_Pa) {
  require(pressure_Pa.size() == mesh.size(), "contact regions: one pressure value per mesh element is required");
  const double S = mesh.element_area_m2();
  constexpr int kUnlabelled = -1;
  std::vector<int> label(mesh.size(), kUnlabelled);
  std::vector<ContactRegion> regions;
  std::vector<std::size_t> stack;
  double total_N = 0.0;

  for (std::size_t seed = 0; seed < mesh.size(); ++seed) {
    if (!(pressure_Pa[seed] > 0.0) || label[seed] != kUnlabelled) continue;
    const int id = static_cast<int>(regions.size());
    ContactRegion region;
    double moment1 = 0.0, moment2 = 0.0;
    label[seed] = id;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      const int i1 = static_cast<int>(k % static_cast<std::size_t>(mesh.n1));
      const int i2 = static_cast<int>(k / static_cast<std::size_t>(mesh.n1));
      const double force = pressure_Pa[k] * S;
      region.elements.push_back(k);
      region.normal_force_N += force;
      moment1 += force * mesh.x1(i1);
      moment2 += force * mesh.x2(i2);
      const auto visit = [&](int j1, int j2) {
        if (j1 < 0 || j2 < 0 || j1 >= mesh.n1 || j2 >= mesh.n2) return;
        const std::size_t q = mesh.index(j1, j2);
        if (pressure_Pa[q] > 0.0 && label[q] == kUnlabelled) {
          label[q] = id;
          stack.push_back(q);
        }
      };
      visit(i1 - 1, i2);
      visit(i1 + 1, i2);
      visit(i1, i2 - 1);
      visit(i1, i2 + 1);
    }
    std::sort(region.elements.begin(), region.elements.end());
    region.x1_centre_m = moment1 / region.normal_force_N;
    region.x2_centre_m = moment2 / region.normal_force_N;
    total_N += region.normal_force_N;
    regions.push_back(std::move(region));
  }
  for (ContactRegion& region : regions) region.load_fraction = region.normal_force_N / total_N;
  std::stable_sort(regions.begin(), regions.end(), [](const ContactRegion& a, const ContactRegion& b) {
    return a.normal_force_N > b.normal_force_N;
  });
  return regions;
}

}  // namespace railcontact
