// A contact patch cut out of a potential-contact-area mesh (see the header).
#include "tangential/cropped_patch.hpp"

#include "mesh/element_rows.hpp"
#include "railcontact/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace railcontact::detail {

IndexBox bounding_box(const Mesh& mesh, const std::vector<std::size_t>& elements) {
  IndexBox box{mesh.n1, -1, mesh.n2, -1};
  ElementRows rows(static_cast<std::size_t>(mesh.n1));
  for (std::size_t k : elements) {
    const auto [i1, i2] = rows.at(k);
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
  ElementRows rows(static_cast<std::size_t>(mesh.n1));
  for (std::size_t k : elements) {
    const auto [i1, i2] = rows.at(k);
    p[crop.index(i1 - box.lo1, i2 - box.lo2)] = pressure_Pa[k];
  }
  return ContactPatch(crop, p, material);
}

ContactPatch block_aligned_patch(const Mesh& mesh, const std::vector<double>& pressure_Pa,
                                 const std::vector<std::size_t>& elements, const Material& material,
                                 CoarseBlocks blocks) {
  const IndexBox box = bounding_box(mesh, elements);
  // Global element indices: centres at k dx from the reference point (the nearest k for the mesh's
  // first element, the others counted from it: a mesh whose centres lie half-way, at (k + 1/2) dx,
  // keeps every element).
  const long base1 = std::lround(mesh.x1_first_m / mesh.dx1_m), base2 = std::lround(mesh.x2_first_m / mesh.dx2_m);
  const auto global1 = [&](int i1) { return base1 + i1; };
  const auto global2 = [&](int i2) { return base2 + i2; };
  const auto floor_to = [](long k, long block) { return k >= 0 ? k - k % block : k - ((k % block) + block) % block; };
  const long b1 = blocks.along, b2 = blocks.across;
  const long first1 = floor_to(global1(box.lo1), b1), first2 = floor_to(global2(box.lo2), b2);
  const long last1 = global1(box.hi1), last2 = global2(box.hi2);
  Mesh crop = mesh;
  crop.n1 = static_cast<int>(((last1 - first1) / b1 + 1) * b1);
  crop.n2 = static_cast<int>(((last2 - first2) / b2 + 1) * b2);
  crop.x1_first_m = static_cast<double>(first1) * mesh.dx1_m;
  crop.x2_first_m = static_cast<double>(first2) * mesh.dx2_m;
  std::vector<double> p(crop.size(), 0.0);
  ElementRows rows(static_cast<std::size_t>(mesh.n1));
  for (std::size_t k : elements) {
    const auto [i1, i2] = rows.at(k);
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

namespace {

// The narrowest neck in `width` (elements per strip, strips in order): its strip and ratio (-1 and
// +infinity without a valley).
struct Neck {
  int strip = -1;
  double ratio = std::numeric_limits<double>::infinity();
};
Neck narrowest_neck(const std::vector<int>& width) {
  const int n = static_cast<int>(width.size());
  std::vector<int> below(static_cast<std::size_t>(n), 0), above(static_cast<std::size_t>(n), 0);
  for (int i = 1; i < n; ++i) below[i] = std::max(below[i - 1], width[i - 1]);
  for (int i = n - 2; i >= 0; --i) above[i] = std::max(above[i + 1], width[i + 1]);
  Neck neck;
  for (int i = 1; i + 1 < n; ++i) {
    const int sides = std::min(below[i], above[i]);
    if (width[i] <= 0 || sides <= 0 || width[i] >= sides) continue;
    const double ratio = static_cast<double>(width[i]) / sides;
    if (ratio <= neck.ratio) neck = {i, ratio};
  }
  return neck;
}

// Elements per strip of a patch, from its strip runs.
std::vector<int> strip_widths(const ContactPatch& patch) {
  const std::vector<StripRun>& runs = patch.runs();  // strip by strip
  if (runs.empty()) return {};
  const int first = runs.front().i2;
  std::vector<int> width(static_cast<std::size_t>(runs.back().i2 - first + 1), 0);
  for (const StripRun& r : runs) width[static_cast<std::size_t>(r.i2 - first)] += r.length();
  return width;
}

ContactRegion region_of(const Mesh& mesh, const std::vector<double>& pressure_Pa, std::vector<std::size_t> elements) {
  ContactRegion r;
  double x1 = 0.0, x2 = 0.0, p = 0.0;
  for (std::size_t k : elements) {
    const double pk = pressure_Pa[k];
    p += pk;
    x1 += pk * mesh.x1(static_cast<int>(k % static_cast<std::size_t>(mesh.n1)));
    x2 += pk * mesh.x2(static_cast<int>(k / static_cast<std::size_t>(mesh.n1)));
  }
  r.elements = std::move(elements);
  r.normal_force_N = p * mesh.element_area_m2();
  r.x1_centre_m = p > 0.0 ? x1 / p : 0.0;
  r.x2_centre_m = p > 0.0 ? x2 / p : 0.0;
  return r;
}

void split_region(const Mesh& mesh, const std::vector<double>& pressure_Pa, ContactRegion region, double fraction,
                  std::vector<ContactRegion>& out) {
  const auto row = [&](std::size_t k) { return static_cast<int>(k / static_cast<std::size_t>(mesh.n1)); };
  const int first = row(region.elements.front()), last = row(region.elements.back());  // increasing indices
  std::vector<int> width(static_cast<std::size_t>(last - first + 1), 0);
  for (std::size_t k : region.elements) ++width[static_cast<std::size_t>(row(k) - first)];
  const Neck neck = narrowest_neck(width);
  if (neck.ratio > fraction) {
    out.push_back(std::move(region));
    return;
  }
  std::vector<std::size_t> lower, upper;
  for (std::size_t k : region.elements) (row(k) - first <= neck.strip ? lower : upper).push_back(k);
  split_region(mesh, pressure_Pa, region_of(mesh, pressure_Pa, std::move(lower)), fraction, out);
  split_region(mesh, pressure_Pa, region_of(mesh, pressure_Pa, std::move(upper)), fraction, out);
}

}  // namespace

double neck_ratio(const ContactPatch& patch) { return narrowest_neck(strip_widths(patch)).ratio; }

bool has_neck(const ContactPatch& patch) { return neck_ratio(patch) <= kNeckWidthFraction; }

std::vector<ContactRegion> split_at_necks(const Mesh& mesh, const std::vector<double>& pressure_Pa,
                                          std::vector<ContactRegion> regions, double fraction) {
  std::vector<ContactRegion> out;
  double total = 0.0;
  for (ContactRegion& r : regions) {
    total += r.normal_force_N;
    split_region(mesh, pressure_Pa, std::move(r), fraction, out);
  }
  for (ContactRegion& r : out) r.load_fraction = total > 0.0 ? r.normal_force_N / total : 0.0;
  std::stable_sort(out.begin(), out.end(),
                   [](const ContactRegion& a, const ContactRegion& b) { return a.normal_force_N > b.normal_force_N; });
  return out;
}

std::optional<NhFastSim> nh_fastsim_unless_too_small(const ContactPatch& patch, const NhFastSimOptions& options) {
  std::optional<NhFastSim> nh;
  if (patch.elements().count() < kMinimumElementsForK2) return nh;
  try {
    nh.emplace(patch, options);
  } catch (const Error&) {
    if (patch.elements().count() >= kFallbackElementsForK2) throw;
  }
  return nh;
}

}  // namespace railcontact::detail
