// A contact patch cut out of a potential-contact-area mesh (see the header).
#include "wheel_rail/cropped_patch.hpp"

#include <algorithm>
#include <cmath>

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

ContactPatch block_aligned_patch(const Mesh& mesh, const std::vector<double>& pressure_Pa,
                                 const std::vector<std::size_t>& elements, const Material& material, int block) {
  const IndexBox box = bounding_box(mesh, elements);
  // Global element indices: centres at k dx from the reference point.
  const auto global1 = [&](int i1) { return static_cast<long>(std::lround(mesh.x1(i1) / mesh.dx1_m)); };
  const auto global2 = [&](int i2) { return static_cast<long>(std::lround(mesh.x2(i2) / mesh.dx2_m)); };
  const auto floor_to = [&](long k) { return k >= 0 ? k - k % block : k - ((k % block) + block) % block; };
  const long first1 = floor_to(global1(box.lo1)), first2 = floor_to(global2(box.lo2));
  const long last1 = global1(box.hi1), last2 = global2(box.hi2);
  Mesh crop = mesh;
  crop.n1 = static_cast<int>((last1 - first1) / block + 1) * block;
  crop.n2 = static_cast<int>((last2 - first2) / block + 1) * block;
  crop.x1_first_m = static_cast<double>(first1) * mesh.dx1_m;
  crop.x2_first_m = static_cast<double>(first2) * mesh.dx2_m;
  std::vector<double> p(crop.size(), 0.0);
  for (std::size_t k : elements) {
    const int i1 = static_cast<int>(k % static_cast<std::size_t>(mesh.n1));
    const int i2 = static_cast<int>(k / static_cast<std::size_t>(mesh.n1));
    p[crop.index(static_cast<int>(global1(i1) - first1), static_cast<int>(global2(i2) - first2))] = pressure_Pa[k];
  }
  return ContactPatch(crop, p, material);
}

bool has_several_lobes(const ContactPatch& patch) {
  const std::vector<StripRun>& runs = patch.runs();  // strip by strip, x1 increasing
  std::vector<std::size_t> parent(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k) parent[k] = k;
  const auto root = [&](std::size_t k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  std::size_t previous_first = 0, previous_end = 0;  // the runs of the strip before
  for (std::size_t first = 0; first < runs.size();) {
    std::size_t end = first;
    while (end < runs.size() && runs[end].i2 == runs[first].i2) ++end;
    if (first > 0 && runs[previous_first].i2 == runs[first].i2 - 1) {
      for (std::size_t a = previous_first; a < previous_end; ++a)
        for (std::size_t b = first; b < end; ++b)
          if (runs[a].i1_trailing <= runs[b].i1_leading && runs[b].i1_trailing <= runs[a].i1_leading)
            parent[root(a)] = root(b);
    }
    previous_first = first;
    previous_end = end;
    first = end;
  }
  for (std::size_t k = 1; k < runs.size(); ++k)
    if (root(k) != root(0)) return true;
  return false;
}

}  // namespace railcontact::detail
