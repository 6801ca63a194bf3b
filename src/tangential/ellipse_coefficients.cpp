#include "railcontact/tangential.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "railcontact/error.hpp"

namespace railcontact {

EllipseCoefficientResult ellipse_creepage_coefficients(double a_over_b, double nu,
                                                       const EllipseCoefficientOptions& options) {
  require(std::isfinite(a_over_b) && a_over_b >= 0.01 && a_over_b <= 100.0,
          [&] { return fmt::format("a/b must lie in [0.01, 100] (got {})", a_over_b); });
  require(std::isfinite(nu) && nu >= 0.0 && nu <= 0.5,
          [&] { return fmt::format("Poisson's ratio nu = {:g} must lie in [0, 0.5]", nu); });
  require(options.target_elements >= 4, [&] {
    return fmt::format("the number of elements in contact must be at least 4 (got {})", options.target_elements);
  });
  const double c_m = 6e-3;
  const double a_m = c_m * std::sqrt(a_over_b);
  const double b_m = c_m / std::sqrt(a_over_b);
  const Material material{2.1e11, nu};

  const auto start = std::chrono::steady_clock::now();
  const ContactElements elements = elliptical_contact_with_count(a_m, b_m, options.target_elements, options.layout);
  const AdhesionSolution solution = solve_full_adhesion(elements, material, options.adhesion);
  const auto stop = std::chrono::steady_clock::now();

  EllipseCoefficientResult result;
  result.creepage_matrix = solution.creepage_matrix;
  result.elements_in_contact = elements.count();
  result.n1 = elements.mesh().n1;
  result.n2 = elements.mesh().n2;
  const double area = static_cast<double>(elements.count()) * elements.mesh().element_area_m2();
  result.area_error = area / (M_PI * a_m * b_m) - 1.0;
  const double c_used = options.c_from_discrete_area ? std::sqrt(area / M_PI) : c_m;
  result.coefficients = creepage_coefficients(solution.creepage_matrix, material.shear_modulus_Pa(), c_used);
  result.iterations = solution.iterations;
  result.solve_time_s = std::chrono::duration<double>(stop - start).count();
  return result;
}

}  // namespace railcontact
