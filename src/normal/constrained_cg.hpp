#pragma once
// Polonsky & Keer's constrained conjugate gradients (Wear 231, 1999, 206-219, §3) for the
// normal contact problem with prescribed load on a regular mesh (METHOD.md §5):
//   minimise  1/2 p.A p + h.p   subject to  p >= 0,  sum p = P  (P = F3 / S),
// whose optimality conditions are those of include/railcontact/normal.hpp with delta the
// multiplier of the load constraint: g = h - delta + A p >= 0, p >= 0, p g = 0.
//
// One iteration on the contact set Ic = {p > 0} (PK's steps, our sign convention):
//   delta = mean_Ic(h + A p),  r = h + A p - delta         (gap residual, zero mean on Ic)
//   t = r + beta t on Ic, 0 elsewhere; beta = G/G_old, G = sum_Ic r^2, beta = 0 after a set change
//   q = A t - mean_Ic(A t);  tau = sum_Ic r t / sum_Ic q t
//   p <- max(0, p - tau t) on Ic;  p <- -tau r where p = 0 and r < 0 (overlap enters the set)
//   p <- p P / sum p                                       (load)
// Only the product A t needs an FFT when the set is unchanged: A p is updated recursively and
// recomputed after a set change and before convergence is accepted.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "elastic/influence_operator.hpp"

namespace railcontact::detail {

struct ConstrainedCgReport {
  int iterations = 0;
  bool converged = false;
  double residual = 0.0;   // max complementarity violation / max(A p), from a fresh A p
  double approach_m = 0.0;  // delta = mean_Ic(h + A p)
};

class ConstrainedConjugateGradient {
 public:
  explicit ConstrainedConjugateGradient(std::size_t grid_size);

  // A: the normal operator on the whole grid; h: undeformed distance per element; pressure_sum:
  // the prescribed sum of p (F3 / S, Pa); p: initial guess (>= 0, not all zero) in, solution out.
  ConstrainedCgReport solve(InfluenceOperator& A, std::span<const double> h, double pressure_sum, std::span<double> p,
                            double tolerance, int max_iterations);

 private:
  std::vector<double> u_;  // A p
  std::vector<double> r_;  // h + A p - delta
  std::vector<double> t_;  // search direction (0 outside Ic)
  std::vector<double> q_;  // A t
  std::vector<std::uint8_t> in_contact_;
};

}  // namespace railcontact::detail
