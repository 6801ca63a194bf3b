#include "railcontact/contact_patch.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "mesh/hertz_pressure.hpp"
#include "railcontact/error.hpp"

namespace railcontact {

Mesh Mesh::covering(double x1_min, double x1_max, double x2_min, double x2_max, int n1, int n2) {
  require(n1 > 0 && n2 > 0, "mesh: the number of elements along each axis must be positive");
  require(std::isfinite(x1_min) && std::isfinite(x1_max) && x1_max > x1_min,
          "mesh: the X1 extent must be finite and positive");
  require(std::isfinite(x2_min) && std::isfinite(x2_max) && x2_max > x2_min,
          "mesh: the X2 extent must be finite and positive");
  Mesh mesh;
  mesh.n1 = n1;
  mesh.n2 = n2;
  mesh.dx1_m = (x1_max - x1_min) / n1;
  mesh.dx2_m = (x2_max - x2_min) / n2;
  mesh.x1_first_m = x1_min + 0.5 * mesh.dx1_m;
  mesh.x2_first_m = x2_min + 0.5 * mesh.dx2_m;
  return mesh;
}

void validate(const Mesh& mesh, std::size_t max_elements) {
  require(mesh.n1 > 0 && mesh.n2 > 0, "mesh: the number of elements along each axis must be positive");
  require(std::isfinite(mesh.dx1_m) && std::isfinite(mesh.dx2_m) && mesh.dx1_m > 0 && mesh.dx2_m > 0,
          "mesh: element sizes must be positive and finite");
  require(std::isfinite(mesh.x1_first_m) && std::isfinite(mesh.x2_first_m),
          "mesh: element coordinates must be finite");
  require(mesh.size() <= max_elements, [&] {
    return "mesh: " + std::to_string(mesh.n1) + " x " + std::to_string(mesh.n2) +
           " elements would not fit in memory (at most " + std::to_string(max_elements) + ")";
  });
}

ContactElements::ContactElements(const Mesh& mesh, std::vector<std::uint8_t> in_contact)
    : mesh_(mesh), flags_(std::move(in_contact)) {
  require(flags_.size() == mesh_.size(), "contact elements: one flag per mesh element is required");
  for (std::size_t k = 0; k < flags_.size(); ++k) {
    if (flags_[k] != 0) active_.push_back(k);
  }
}

void validate(const Material& material) {
  const double E = material.youngs_modulus_Pa;
  require(std::isfinite(E) && E >= kMinimumYoungsModulus_Pa && E <= kMaximumYoungsModulus_Pa, [&] {
    return fmt::format("material: Young's modulus E = {:g} Pa must lie in [{:g}, {:g}] Pa", E, kMinimumYoungsModulus_Pa,
                       kMaximumYoungsModulus_Pa);
  });
  const double nu = material.poisson_ratio;
  require(std::isfinite(nu) && nu >= 0.0 && nu <= 0.5,
          [&] { return fmt::format("material: Poisson's ratio nu = {:g} must lie in [0, 0.5]", nu); });
}

void validate_normal_force(double normal_force_N, std::string_view what) {
  if (normal_force_N >= kMinimumNormalForce_N && normal_force_N <= kMaximumNormalForce_N) return;
  const char* problem = !(std::isfinite(normal_force_N) && normal_force_N > 0.0) ? "must be positive and finite"
                        : normal_force_N < kMinimumNormalForce_N                  ? "is too small"
                                                                                  : "is too large";
  throw Error(fmt::format("{} {} ({:g} N; allowed [{:g}, {:g}] N)", what, problem, normal_force_N,
                          kMinimumNormalForce_N, kMaximumNormalForce_N));
}

void validate_semi_axis(double value_m, std::string_view name) {
  require(std::isfinite(value_m) && value_m >= kMinimumSemiAxis_m && value_m <= kMaximumSemiAxis_m, [&] {
    return fmt::format("{} = {:g} m must lie in {} (a contact patch from a laboratory micro-contact to beyond a rail "
                       "head{})",
                       name, value_m, fmt::format("[{:g}, {:g}] m", kMinimumSemiAxis_m, kMaximumSemiAxis_m),
                       value_m > kMaximumSemiAxis_m && value_m * 1e-3 <= kMaximumSemiAxis_m
                           ? "; the semi-axes are in metres: is it given in millimetres?"
                           : "");
  });
}

void validate_ellipse(double a_m, double b_m, double normal_force_N, std::string_view inputs) {
  const double ratio = a_m / b_m;
  require(ratio >= kMinimumEllipseAxisRatio && ratio <= kMaximumEllipseAxisRatio, [&] {
    return fmt::format("{} give an ellipse of a/b = {:g}, outside {} (the solvers' meshes cannot resolve a more "
                       "slender patch)",
                       inputs, ratio, fmt::format("[{:g}, {:g}]", kMinimumEllipseAxisRatio, kMaximumEllipseAxisRatio));
  });
  detail::validate_hertz_pressure(a_m, b_m, normal_force_N, inputs);
}

void detail::validate_hertz_pressure(double a_m, double b_m, double normal_force_N, std::string_view inputs) {
  const double p0 = 3.0 * normal_force_N / (2.0 * std::numbers::pi * a_m * b_m);
  require(p0 <= kMaximumHertzPressure_Pa, [&] {
    return fmt::format("{} under F3 = {:g} N give a maximum pressure p0 = 3 F3 / (2 pi a b) = {:.3g} MPa, above {:g} "
                       "MPa: beyond the strength of any solid, where the elastic half-space does not hold (is the "
                       "patch too small or the load too large?)",
                       inputs, normal_force_N, p0 * 1e-6, kMaximumHertzPressure_Pa * 1e-6);
  });
}

void validate_creepage(const Creepage& c, std::string_view names, std::string_view spin_field) {
  const auto check = [&](double value, std::string_view field, double limit, const char* unit, const char* reason) {
    require(std::isfinite(value) && std::fabs(value) <= limit, [&] {
      return fmt::format("{}.{} = {:g}{} must lie in [{:g}, {:g}]{} ({})", names, field, value, unit, -limit, limit,
                         unit, reason);
    });
  };
  constexpr const char* kSliding = "a creepage is a sliding velocity over the rolling speed; beyond 0.5 the wheel "
                                   "slides rather than rolls and the steady-rolling model does not apply";
  check(c.xi, "xi", kMaximumCreepage, "", kSliding);
  check(c.eta, "eta", kMaximumCreepage, "", kSliding);
  check(c.phi, spin_field, kMaximumSpinCreepage_per_m, " 1/m",
        "sin(contact angle) / rolling radius: 100 1/m is a contact angle of 90 degrees on a wheel of radius 10 mm");
}

}  // namespace railcontact
