// Regularised Coulomb friction in steady rolling (paper Appendix, Eq A1): Newton on the slip s,
//   F(s) = s - w + R P(s) = 0,   P(s) = -(2 g / pi) atan(|s|/eps) s/|s|,  g = mu p3,
// with a Krylov inner solve. With D = dP/ds (block diagonal, negative definite) the Newton step
// (I + R D) ds = -F is solved for dp = D ds as (D^-1 + R) dp = -F, which is well scaled where
// D is huge (adhesion, |s| << eps) and where it is tiny (slip, |s| >> eps). The regularisation
// is reached by continuation: eps decreases by 10 per level from ~|w| to the requested value.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"
#include "tangential/rolling_system.hpp"

namespace railcontact {
namespace {

struct RegularisedState {
  std::vector<double> s, p, F;
  double residual = 0.0;  // max |F_e| / slip scale
};

// Traction of the regularised law and its derivative block D = dP/ds at slip (s1, s2).
void regularised_law(double s1, double s2, double g, double eps, double& p1, double& p2, Block2* D_inverse) {
  const double r = std::hypot(s1, s2);
  const double magnitude = 2.0 * g / M_PI * std::atan(r / eps);               // phi(r)
  const double slope = 2.0 * g / M_PI / (eps * (1.0 + (r / eps) * (r / eps)));  // phi'(r)
  if (r == 0.0) {
    p1 = p2 = 0.0;
    if (D_inverse) *D_inverse = {-1.0 / slope, 0, 0, -1.0 / slope};
    return;
  }
  const double u1 = s1 / r, u2 = s2 / r;
  p1 = -magnitude * u1;
  p2 = -magnitude * u2;
  if (D_inverse) {
    // D = -[(phi/r)(I - uu^T) + phi' uu^T]  =>  D^-1 = -[(r/phi)(I - uu^T) + (1/phi') uu^T]
    const double t = r / magnitude, q = 1.0 / slope;
    *D_inverse = {-(t * (1 - u1 * u1) + q * u1 * u1), -(q - t) * u1 * u2, -(q - t) * u1 * u2,
                  -(t * (1 - u2 * u2) + q * u2 * u2)};
  }
}

void evaluate(RollingSystem& system, const std::vector<double>& w, const std::vector<double>& bound, double eps,
              double slip_scale, RegularisedState& st) {
  const std::size_t n = system.count();
  for (std::size_t e = 0; e < n; ++e) regularised_law(st.s[e], st.s[n + e], bound[e], eps, st.p[e], st.p[n + e], nullptr);
  system.apply_R(st.p.data(), st.F.data());
  st.residual = 0.0;
  for (std::size_t e = 0; e < n; ++e) {
    st.F[e] += st.s[e] - w[e];
    st.F[n + e] += st.s[n + e] - w[n + e];
    st.residual = max_or_nan(st.residual, std::hypot(st.F[e], st.F[n + e]) / slip_scale);  // NaN is not hidden
  }
}

// The solver on a system with its rigid slip w (from one creepage or from strip creepages).
RollingSolution solve(RollingSystem& system, const std::vector<double>& w, double mu, const RollingOptions& options) {
  const std::size_t n = system.count();
  const std::vector<double> bound = system.traction_bound(mu);
  double w_max = 0.0;
  for (std::size_t e = 0; e < n; ++e) w_max = std::max(w_max, std::hypot(w[e], w[n + e]));
  RollingSolution solution;
  RegularisedState st{std::vector<double>(2 * n, 0.0), std::vector<double>(2 * n), std::vector<double>(2 * n), 0.0};
  if (w_max == 0.0) {  // no creepage: no traction
    fill_rolling_solution(system, st.p, st.s, std::vector<std::uint8_t>(n, 0), solution);
    return solution;
  }
  const double slip_scale = w_max;
  NewtonMatrix J(system);
  std::vector<double> rhs(2 * n), dp(2 * n);
  RegularisedState trial = st;
  // Continuation in epsilon, from the rigid-slip scale down to the requested regularisation.
  std::vector<double> levels;
  for (double eps = w_max; eps > options.regularisation; eps *= 0.1) levels.push_back(eps);
  levels.push_back(options.regularisation);
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const double eps = levels[level];
    const bool last = level + 1 == levels.size();
    const double target = last ? options.tolerance : 1e-3;
    evaluate(system, w, bound, eps, slip_scale, st);
    while (!(st.residual <= target)) {  // a NaN residual is not convergence
      if (!std::isfinite(st.residual))
        throw Error(ErrorKind::not_converged,
                    fmt::format("regularised rolling solver: the Newton iteration broke down after {} iterations "
                                "(epsilon {:.1e}: non-finite residual, the law's slope or the tractions left the range "
                                "of double precision); no solution",
                                solution.newton_iterations, eps));
      if (solution.newton_iterations >= options.max_newton_iterations)
        throw Error(ErrorKind::not_converged,
                    fmt::format("regularised rolling solver: Newton did not converge in {} iterations (epsilon "
                                "{:.1e}, residual {:.2e} > {:.1e})",
                                options.max_newton_iterations, eps, st.residual, target));
      ++solution.newton_iterations;
      for (std::size_t e = 0; e < n; ++e) {
        double p1, p2;
        Block2 D_inverse;
        regularised_law(st.s[e], st.s[n + e], bound[e], eps, p1, p2, &D_inverse);
        J.A()[e] = {1, 0, 0, 1};
        J.B()[e] = D_inverse;
        rhs[e] = -st.F[e];
        rhs[n + e] = -st.F[n + e];
      }
      const NewtonStepReport step =
          solve_newton_step(J, rhs, dp, options.krylov_tolerance, options.max_krylov_iterations);
      solution.krylov_iterations += step.krylov_iterations;
      // ds = D^-1 dp, then a backtracking line search on max |F|.
      std::vector<double> ds(2 * n);
      for (std::size_t e = 0; e < n; ++e) {
        double p1, p2;
        Block2 Di;
        regularised_law(st.s[e], st.s[n + e], bound[e], eps, p1, p2, &Di);
        ds[e] = Di[0] * dp[e] + Di[1] * dp[n + e];
        ds[n + e] = Di[2] * dp[e] + Di[3] * dp[n + e];
      }
      double t = 1.0;
      for (int k = 0;; ++k) {
        for (std::size_t i = 0; i < 2 * n; ++i) trial.s[i] = st.s[i] + t * ds[i];
        evaluate(system, w, bound, eps, slip_scale, trial);
        if (trial.residual < (1.0 - 1e-4 * t) * st.residual || k == 20) break;
        t *= 0.5;
      }
      std::swap(st, trial);
    }
  }
  // Slip where the traction is close to the bound (|s| > 100 eps: |p| > 0.994 g).
  std::vector<std::uint8_t> slip(n, 0);
  for (std::size_t e = 0; e < n; ++e) slip[e] = std::hypot(st.s[e], st.s[n + e]) > 100.0 * options.regularisation;
  solution.residual = st.residual;
  fill_rolling_solution(system, st.p, st.s, slip, solution);
  require_finite_rolling_result("regularised", solution);
  return solution;
}

}  // namespace

RollingSolution solve_rolling_regularised(const ContactPatch& patch, const Creepage& creepage, double mu,
                                          const RollingOptions& options) {
  validate_rolling_input(patch, creepage, mu, options);
  RollingSystem system(patch, options.collocation_offset);
  return solve(system, system.rigid_slip(creepage), mu, options);
}

RollingSolution solve_rolling_regularised(const ContactPatch& patch, const StripCreepages& creepages, double mu,
                                          const RollingOptions& options) {
  validate_rolling_input(patch, creepages, mu, options);
  RollingSystem system(patch, options.collocation_offset);
  return solve(system, system.rigid_slip(creepages), mu, options);
}

}  // namespace railcontact
