#include "railcontact/contact_patch.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "railcontact/error.hpp"

namespace railcontact {

ContactPatch::ContactPatch(const Mesh& input_mesh, const std::vector<double>& pressure_Pa, const Material& material)
    : material_(material) {
  validate(material);
  validate(input_mesh);
  require(pressure_Pa.size() == input_mesh.size(), "contact patch: one pressure value per mesh element is required");
  std::vector<std::uint8_t> flags(input_mesh.size(), 0);
  double force = 0.0, moment1 = 0.0, moment2 = 0.0;
  const double S = input_mesh.element_area_m2();
  for (int i2 = 0; i2 < input_mesh.n2; ++i2) {
    for (int i1 = 0; i1 < input_mesh.n1; ++i1) {
      const double p = pressure_Pa[input_mesh.index(i1, i2)];
      require(std::isfinite(p) && p >= 0.0, [&] {
        return "contact patch: pressures must be finite and non-negative (element " + std::to_string(i1) + ", " +
               std::to_string(i2) + ")";
      });
      if (p > 0.0) {
        flags[input_mesh.index(i1, i2)] = 1;
        force += p * S;
        moment1 += p * S * input_mesh.x1(i1);
        moment2 += p * S * input_mesh.x2(i2);
      }
    }
  }
  if (!(force > 0.0)) throw Error(ErrorKind::no_contact, "contact patch: no element carries pressure (no contact)");
  Mesh mesh = input_mesh;
  x1_shift_m_ = -moment1 / force;
  x2_shift_m_ = -moment2 / force;
  mesh.x1_first_m += x1_shift_m_;
  mesh.x2_first_m += x2_shift_m_;
  normal_force_N_ = force;
  elements_ = ContactElements(mesh, std::move(flags));
  pressure_.reserve(elements_.count());
  for (std::size_t k : elements_.indices()) pressure_.push_back(pressure_Pa[k]);

  // Strip runs: indices are sorted strip by strip with x1 increasing.
  const auto& idx = elements_.indices();
  const auto n1 = static_cast<std::size_t>(mesh.n1);
  for (std::size_t e = 0; e < idx.size();) {
    // One division per run: a run ends at a gap or at the end of its strip (row).
    const std::size_t strip = idx[e] / n1, strip_end = (strip + 1) * n1;
    std::size_t last = e;
    while (last + 1 < idx.size() && idx[last + 1] == idx[last] + 1 && idx[last + 1] < strip_end) ++last;
    StripRun run;
    run.i2 = static_cast<int>(strip);
    run.i1_trailing = static_cast<int>(idx[e] - strip * n1);
    run.i1_leading = static_cast<int>(idx[last] - strip * n1);
    run.first = e;
    run.x1_trailing_m = mesh.x1(run.i1_trailing) - 0.5 * mesh.dx1_m;
    run.x1_leading_m = mesh.x1(run.i1_leading) + 0.5 * mesh.dx1_m;
    runs_.push_back(run);
    e = last + 1;
  }
}

ContactPatch coarsened(const ContactPatch& patch, int factor) {
  require(factor >= 1 && factor <= kMaximumCoarsening, [&] {
    return fmt::format("coarsened patch: the factor must lie in [1, {}] (got {})", kMaximumCoarsening, factor);
  });
  return coarsened(patch, CoarseBlocks{factor, factor});
}

ContactPatch coarsened(const ContactPatch& patch, CoarseBlocks blocks) {
  const int f1 = blocks.along, f2 = blocks.across;
  require(f1 >= 1 && f1 <= kMaximumCoarsening + 1 && f2 >= 1 && f2 <= kMaximumCoarsening + 1, [&] {
    return fmt::format("coarsened patch: the blocks {} x {} must each lie in [1, {}]", f1, f2, kMaximumCoarsening + 1);
  });
  if (f1 == 1 && f2 == 1) return patch;
  const Mesh& fine = patch.mesh();
  const int n1 = (fine.n1 + f1 - 1) / f1;
  const int n2 = (fine.n2 + f2 - 1) / f2;
  std::vector<double> block_force(static_cast<std::size_t>(n1) * static_cast<std::size_t>(n2), 0.0);
  std::vector<int> block_count(block_force.size(), 0);
  // Strip by strip, and along a strip block by block: one index division and one update of the
  // block's sums per block, not per element.
  for (const StripRun& run : patch.runs()) {
    const std::size_t row = static_cast<std::size_t>(run.i2 / f2) * static_cast<std::size_t>(n1);
    const double* p3 = patch.pressure_Pa().data() + run.first;  // p3[i1 - run.i1_trailing]
    for (int i1 = run.i1_trailing; i1 <= run.i1_leading;) {
      const int block = i1 / f1;
      const int end = std::min(run.i1_leading + 1, (block + 1) * f1);
      double force = 0.0;
      for (int i = i1; i < end; ++i) force += p3[i - run.i1_trailing];
      block_force[row + static_cast<std::size_t>(block)] += force;
      block_count[row + static_cast<std::size_t>(block)] += end - i1;
      i1 = end;
    }
  }
  // The blocks in contact (at least half of their elements) and their bounding box.
  double kept = 0.0, total = 0.0;
  int lo1 = n1, hi1 = -1, lo2 = n2, hi2 = -1;
  for (int i2 = 0; i2 < n2; ++i2) {
    for (int i1 = 0; i1 < n1; ++i1) {
      const std::size_t k = static_cast<std::size_t>(i2) * static_cast<std::size_t>(n1) + static_cast<std::size_t>(i1);
      total += block_force[k];
      if (2 * block_count[k] < f1 * f2) continue;
      kept += block_force[k];
      lo1 = std::min(lo1, i1);
      hi1 = std::max(hi1, i1);
      lo2 = std::min(lo2, i2);
      hi2 = std::max(hi2, i2);
    }
  }
  require(kept > 0.0, [&] {
    return fmt::format("coarsened patch: the patch is too small to coarsen in blocks of {} x {}", f1, f2);
  });
  Mesh coarse;
  coarse.n1 = hi1 - lo1 + 1;
  coarse.n2 = hi2 - lo2 + 1;
  coarse.dx1_m = f1 * fine.dx1_m;
  coarse.dx2_m = f2 * fine.dx2_m;
  coarse.x1_first_m = fine.x1_first_m + 0.5 * (f1 - 1) * fine.dx1_m + lo1 * coarse.dx1_m;
  coarse.x2_first_m = fine.x2_first_m + 0.5 * (f2 - 1) * fine.dx2_m + lo2 * coarse.dx2_m;
  // Each kept block carries its force (pressure averaged over the whole block), scaled so that the
  // coarse patch carries the whole load.
  std::vector<double> pressure(coarse.size(), 0.0);
  const double scale = total / kept / (f1 * f2);
  for (int i2 = lo2; i2 <= hi2; ++i2) {
    for (int i1 = lo1; i1 <= hi1; ++i1) {
      const std::size_t k = static_cast<std::size_t>(i2) * static_cast<std::size_t>(n1) + static_cast<std::size_t>(i1);
      if (2 * block_count[k] >= f1 * f2) pressure[coarse.index(i1 - lo1, i2 - lo2)] = block_force[k] * scale;
    }
  }
  return ContactPatch(coarse, pressure, patch.material());
}

ContactPatch hertzian_patch(const ContactElements& ellipse, double a_m, double b_m, double normal_force_N,
                            const Material& material) {
  validate_semi_axis(a_m, "Hertzian patch: the semi-axis a");
  validate_semi_axis(b_m, "Hertzian patch: the semi-axis b");
  validate_normal_force(normal_force_N, "Hertzian patch: the normal force F3");
  validate_ellipse(a_m, b_m, normal_force_N,
                   fmt::format("Hertzian patch: the semi-axes a = {:g} m, b = {:g} m", a_m, b_m));
  const Mesh& mesh = ellipse.mesh();
  std::vector<double> pressure(mesh.size(), 0.0);
  double force = 0.0;
  for (std::size_t k : ellipse.indices()) {
    const double x = mesh.x1(static_cast<int>(k % mesh.n1)) / a_m;
    const double y = mesh.x2(static_cast<int>(k / mesh.n1)) / b_m;
    const double shape = std::sqrt(std::max(0.0, 1.0 - x * x - y * y));
    pressure[k] = shape;
    force += shape * mesh.element_area_m2();
  }
  require(force > 0.0, "Hertzian patch: no element lies inside the ellipse");
  for (double& p : pressure) p *= normal_force_N / force;
  return ContactPatch(mesh, pressure, material);
}

}  // namespace railcontact
