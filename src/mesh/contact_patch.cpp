#include "railcontact/contact_patch.hpp"

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
    std::size_t last = e;
    while (last + 1 < idx.size() && idx[last + 1] == idx[last] + 1 && idx[last + 1] / n1 == idx[e] / n1) ++last;
    StripRun run;
    run.i2 = static_cast<int>(idx[e] / n1);
    run.i1_trailing = static_cast<int>(idx[e] % n1);
    run.i1_leading = static_cast<int>(idx[last] % n1);
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
  if (factor == 1) return patch;
  const Mesh& fine = patch.mesh();
  Mesh coarse;
  coarse.n1 = (fine.n1 + factor - 1) / factor;
  coarse.n2 = (fine.n2 + factor - 1) / factor;
  coarse.dx1_m = factor * fine.dx1_m;
  coarse.dx2_m = factor * fine.dx2_m;
  coarse.x1_first_m = fine.x1_first_m + 0.5 * (factor - 1) * fine.dx1_m;
  coarse.x2_first_m = fine.x2_first_m + 0.5 * (factor - 1) * fine.dx2_m;
  std::vector<double> block_force(coarse.size(), 0.0);
  std::vector<int> block_count(coarse.size(), 0);
  for (const StripRun& run : patch.runs()) {  // strip by strip (no index division per element)
    const std::size_t row = static_cast<std::size_t>(run.i2 / factor) * coarse.n1;
    for (int i1 = run.i1_trailing; i1 <= run.i1_leading; ++i1) {
      const std::size_t k = row + static_cast<std::size_t>(i1 / factor);
      block_force[k] += patch.pressure_Pa()[run.first + static_cast<std::size_t>(i1 - run.i1_trailing)];
      block_count[k] += 1;
    }
  }
  std::vector<double> pressure(coarse.size(), 0.0);
  double kept = 0.0, total = 0.0;
  for (std::size_t k = 0; k < coarse.size(); ++k) {
    total += block_force[k];
    if (2 * block_count[k] >= factor * factor) {
      pressure[k] = block_force[k] / (factor * factor);  // same force on the coarse element
      kept += block_force[k];
    }
  }
  require(kept > 0.0,
          [&] { return "coarsened patch: the patch is too small to coarsen by " + std::to_string(factor); });
  for (double& p : pressure) p *= total / kept;
  return ContactPatch(coarse, pressure, patch.material());
}

ContactPatch hertzian_patch(const ContactElements& ellipse, double a_m, double b_m, double normal_force_N,
                            const Material& material) {
  require(a_m > 0 && b_m > 0 && std::isfinite(a_m) && std::isfinite(b_m), "Hertzian patch: semi-axes must be positive");
  validate_normal_force(normal_force_N, "Hertzian patch: the normal force F3");
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
