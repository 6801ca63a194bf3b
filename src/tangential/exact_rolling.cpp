// Exact Coulomb friction in steady rolling: semismooth Newton on the projection form of the
// friction law (docs/ROLLING.md; Alart & Curnier 1991, in the spirit of Kalker's TANG active sets).
//
// With z = p - c s, Coulomb's law (adhesion: s = 0, |p| <= g; slip: p = -g s/|s|, g = mu p3)
// is  Phi(p) = p - proj_{|.| <= g}(z) = 0  element by element, s = w - R p.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"
#include "tangential/rolling_system.hpp"

namespace railcontact {
namespace {

struct ExactState {
  std::vector<double> p, s, phi;
  std::vector<std::uint8_t> slip;
  double residual = 0.0;  // max |Phi_e| / (mu max p3): the convergence test
  double merit = 0.0;     // sum |Phi_e|^2: the line search's (smooth away from the kinks)
};

// Evaluates s, Phi and the slip set at p.
void evaluate(RollingSystem& system, const std::vector<double>& w, const std::vector<double>& bound, double c,
              double scale, ExactState& st) {
  const std::size_t n = system.count();
  system.apply_R(st.p.data(), st.s.data());
  st.residual = 0.0;
  st.merit = 0.0;
  for (std::size_t e = 0; e < n; ++e) {
    const double s1 = w[e] - st.s[e], s2 = w[n + e] - st.s[n + e];
    st.s[e] = s1;
    st.s[n + e] = s2;
    const double p1 = st.p[e], p2 = st.p[n + e];
    const double z1 = p1 - c * s1, z2 = p2 - c * s2;
    const double zn = std::hypot(z1, z2);
    double f1, f2;
    if (zn <= bound[e]) {
      st.slip[e] = 0;
      f1 = c * s1;
      f2 = c * s2;
    } else {
      st.slip[e] = 1;
      f1 = p1 - bound[e] * z1 / zn;
      f2 = p2 - bound[e] * z2 / zn;
    }
    st.phi[e] = f1;
    st.phi[n + e] = f2;
    st.residual = max_or_nan(st.residual, std::hypot(f1, f2) / scale);  // a NaN element is not hidden
    st.merit += f1 * f1 + f2 * f2;
  }
}

// Inexact Newton (Eisenstat and Walker's forcing terms, SIAM J. Sci. Comput. 17, 1996): a Newton
// step's linear system needs solving only as far as the Newton residual warrants. Far from the
// solution the step is dominated by the slip/adhesion pattern it changes, not by the last digits
// of GMRES; near it the step must be accurate, or Newton's fast convergence is lost. Each step is
// solved to eta_k = max(krylov_tolerance, min(residual_k, 0.1)) (residual_k: max |Phi_e| / (mu
// max p3) before the step), the starting guess to max(krylov_tolerance, 0.1). The converged
// solution is the same (the Newton test on the true residual decides), with 45-60 % fewer GMRES
// iterations: 3442 against 7158 over 48 S1002/UIC60 cases of 1000-4900 elements, forces within
// 2e-10 mu F3 (build/bench/exact_newton_cases; docs/BENCHMARKS.md "Speed on the S1002/UIC60 patch").
constexpr double kLoosestKrylovTolerance = 0.1;
constexpr int kMaximumHalvings = 10;  // of the line search's step, before the full step is taken

double initial_guess_krylov_tolerance(const RollingOptions& options) {
  return options.inexact_newton ? std::max(options.krylov_tolerance, kLoosestKrylovTolerance)
                                : options.krylov_tolerance;
}

double newton_step_krylov_tolerance(double residual, const RollingOptions& options) {
  if (!options.inexact_newton) return options.krylov_tolerance;
  return std::max(options.krylov_tolerance, std::min(residual, kLoosestKrylovTolerance));
}

// The solver's constants on one system: the traction bound mu p3 per element, its largest value,
// and c, which scales slip to traction (c R ~ -I locally).
struct ExactScales {
  std::vector<double> bound;
  double max_bound, c;
};

// Initial guess: the full-adhesion tractions (R p = w, Eq 14) limited to the traction bound.
int full_adhesion_guess(NewtonMatrix& J, const std::vector<double>& w, const ExactScales& k,
                        const RollingOptions& options, std::vector<double>& p) {
  const std::size_t n = k.bound.size();
  for (std::size_t e = 0; e < n; ++e) {
    J.A()[e] = {1, 0, 0, 1};
    J.B()[e] = {0, 0, 0, 0};
  }
  const NewtonStepReport step =
      solve_newton_step(J, w, p, initial_guess_krylov_tolerance(options), options.max_krylov_iterations);
  for (std::size_t e = 0; e < n; ++e) {
    const double magnitude = std::hypot(p[e], p[n + e]);
    if (magnitude > k.bound[e]) {
      p[e] *= k.bound[e] / magnitude;
      p[n + e] *= k.bound[e] / magnitude;
    }
  }
  return step.krylov_iterations;
}

// Generalised Jacobian of Phi at the state, row blocks A_e (R dp)_e + B_e dp_e = rhs_e.
void newton_system(const ExactState& st, const ExactScales& k, NewtonMatrix& J, std::vector<double>& rhs) {
  const std::size_t n = k.bound.size();
  const double c = k.c;
  for (std::size_t e = 0; e < n; ++e) {
    if (st.slip[e] == 0) {  // Phi_e = c s_e: -c (R dp)_e = -c s_e
      J.A()[e] = {1, 0, 0, 1};
      J.B()[e] = {0, 0, 0, 0};
      rhs[e] = st.s[e];
      rhs[n + e] = st.s[n + e];
    } else {  // Phi_e = p_e - g z/|z|: (I - M) dp_e - c M (R dp)_e = -Phi_e, M = g/|z| (I - zz^T/|z|^2)
      const double z1 = st.p[e] - c * st.s[e], z2 = st.p[n + e] - c * st.s[n + e];
      const double zn = std::hypot(z1, z2);
      const double u1 = z1 / zn, u2 = z2 / zn, m = k.bound[e] / zn;
      const Block2 M{m * (1 - u1 * u1), -m * u1 * u2, -m * u1 * u2, m * (1 - u2 * u2)};
      J.A()[e] = {-c * M[0], -c * M[1], -c * M[2], -c * M[3]};
      J.B()[e] = {1 - M[0], -M[1], -M[2], 1 - M[3]};
      rhs[e] = -st.phi[e];
      rhs[n + e] = -st.phi[n + e];
    }
  }
}

// Backtracking line search on sum |Phi|^2 along dp from st, into trial. Where elements sit on the
// kink of Phi (|z| = mu p3, as the clipped starting guess puts them), the generalised Newton step
// need not descend for any step length; after kMaximumHalvings halvings the full step is taken
// (semismooth Newton converges locally with full steps). Taking the 2^-30 step instead, Newton
// stalled for good on 5 of 90 elliptical cases with small creepage (xi = 2e-5 ... 1e-4, 300-3000
// elements; test ExactRolling.ConvergesWhereTheLineSearchFindsNoDescent).
void line_search(RollingSystem& system, const std::vector<double>& w, const ExactScales& k, const ExactState& st,
                 const std::vector<double>& dp, ExactState& trial) {
  const std::size_t n2 = dp.size();
  double t = 1.0;
  for (int halvings = 0;; ++halvings) {
    for (std::size_t i = 0; i < n2; ++i) trial.p[i] = st.p[i] + t * dp[i];
    evaluate(system, w, k.bound, k.c, k.max_bound, trial);
    if (trial.merit < (1.0 - 1e-4 * t) * st.merit) return;
    if (halvings == kMaximumHalvings) {
      for (std::size_t i = 0; i < n2; ++i) trial.p[i] = st.p[i] + dp[i];
      evaluate(system, w, k.bound, k.c, k.max_bound, trial);
      return;
    }
    t *= 0.5;
  }
}

// Refuses a state that cannot go on: a non-finite residual, or the Newton iterations used up.
void require_newton_can_go_on(const ExactState& st, int newton_iterations, const RollingOptions& options) {
  if (!std::isfinite(st.residual))
    throw Error(ErrorKind::not_converged,
                fmt::format("exact rolling solver: the Newton iteration broke down after {} iterations (non-finite "
                            "residual: the tractions overflowed or the traction bound mu p3 underflowed); no solution",
                            newton_iterations));
  if (newton_iterations >= options.max_newton_iterations)
    throw Error(ErrorKind::not_converged,
                fmt::format("exact rolling solver: Newton did not converge in {} iterations (residual {:.2e} > "
                            "tolerance {:.1e})",
                            options.max_newton_iterations, st.residual, options.tolerance));
}

// The solver on a system with its rigid slip w (from one creepage or from strip creepages):
// semismooth Newton from the clipped full-adhesion tractions, each step's linear system by GMRES,
// a backtracking line search.
RollingSolution solve(RollingSystem& system, const std::vector<double>& w, double mu, const RollingOptions& options) {
  const std::size_t n = system.count();
  ExactScales k{system.traction_bound(mu), 0.0, 2.0 / (system.lambda1() + system.lambda2())};
  k.max_bound = *std::max_element(k.bound.begin(), k.bound.end());

  ExactState st{std::vector<double>(2 * n, 0.0), std::vector<double>(2 * n), std::vector<double>(2 * n),
                std::vector<std::uint8_t>(n, 0), 0.0, 0.0};
  NewtonMatrix J(system);
  std::vector<double> rhs(2 * n), dp(2 * n);
  RollingSolution solution;
  solution.krylov_iterations += full_adhesion_guess(J, w, k, options, st.p);
  evaluate(system, w, k.bound, k.c, k.max_bound, st);
  ExactState trial = st;
  while (!(st.residual <= options.tolerance)) {  // a NaN residual is not convergence
    require_newton_can_go_on(st, solution.newton_iterations, options);
    ++solution.newton_iterations;
    newton_system(st, k, J, rhs);
    const NewtonStepReport step =
        solve_newton_step(J, rhs, dp, newton_step_krylov_tolerance(st.residual, options), options.max_krylov_iterations);
    solution.krylov_iterations += step.krylov_iterations;
    line_search(system, w, k, st, dp, trial);
    std::swap(st, trial);
  }
  solution.residual = st.residual;
  fill_rolling_solution(system, st.p, st.s, st.slip, solution);
  require_finite_rolling_result("exact", solution);
  return solution;
}

}  // namespace

RollingSolution solve_rolling_exact(const ContactPatch& patch, const Creepage& creepage, double mu,
                                    const RollingOptions& options) {
  validate_rolling_input(patch, creepage, mu, options);
  RollingSystem system(patch, options.collocation_offset);
  return solve(system, system.rigid_slip(creepage), mu, options);
}

RollingSolution solve_rolling_exact(const ContactPatch& patch, const StripCreepages& creepages, double mu,
                                    const RollingOptions& options) {
  validate_rolling_input(patch, creepages, mu, options);
  RollingSystem system(patch, options.collocation_offset);
  return solve(system, system.rigid_slip(creepages), mu, options);
}

}  // namespace railcontact
