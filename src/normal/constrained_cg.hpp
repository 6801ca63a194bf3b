#pragma once
// Polonsky & Keer's constrained conjugate gradients (Wear 231, 1999, 206-219, §3) for the
// normal contact problem with prescribed load on a regular mesh (METHOD.md §5):
//   minimise  1/2 p.A p + h.p   subject to  p >= 0,  sum p = P  (P = F3 / S),
// whose optimality conditions are those of include/railcontact/normal.hpp with delta the
// multiplier of the load constraint: g = h - delta + A p >= 0, p >= 0, p g = 0.
//
// One iteration on the contact set Ic = {p > 0} (PK's steps, our sign convention, with a
// preconditioner M ~ A^-1 on Ic added to PK's plain conjugate gradients):
//   delta = mean_Ic(h + A p),  r = h + A p - delta         (gap residual, zero mean on Ic)
//   z = M r - mean_Ic(M r)                                 (preconditioned, kept in sum z = 0)
//   t = z + beta t on Ic, 0 elsewhere; beta = G/G_old, G = sum_Ic r z, beta = 0 after a set change
//   q = A t - mean_Ic(A t);  tau = sum_Ic r t / sum_Ic q t
//   p <- max(0, p - tau t) on Ic;  p <- -r / (4 A(0,0)) where p = 0 and r < 0 (overlap enters)
//   p <- p P / sum p                                       (load)
// PK's entering pressure -tau r assumes t ~ r; with M it is replaced by a quarter of the pressure
// that closes the gap of a single element, -r / A33(0,0) (see the .cpp).
// Only the product A t needs an FFT when the set is unchanged: A p is updated recursively and
// recomputed after a set change and before convergence is accepted.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "elastic/influence_operator.hpp"
#include "normal/contact_laplacian_preconditioner.hpp"

namespace railcontact::detail {

struct ConstrainedCgReport {
  int iterations = 0;
  bool converged = false;
  double residual = 0.0;   // max complementarity violation / max(A p), from a fresh A p
  double approach_m = 0.0;  // delta = mean_Ic(h + A p)
};

class ConstrainedConjugateGradient {
 public:
  explicit ConstrainedConjugateGradient(const Mesh& mesh);

  // A: the normal operator on the whole grid; h: undeformed distance per element; pressure_sum:
  // the prescribed sum of p (F3 / S, Pa); p: initial guess (>= 0, not all zero) in, solution out.
  ConstrainedCgReport solve(InfluenceOperator& A, std::span<const double> h, double pressure_sum, std::span<double> p,
                            double tolerance, int max_iterations);
  // The same problem with the approach delta prescribed instead of the load (PK's displacement-
  // driven variant): minimise 1/2 p.A p + (h - delta).p subject to p >= 0, i.e. the steps above
  // without the means over Ic and without the load scaling. p: initial guess (>= 0, may be zero).
  ConstrainedCgReport solve_at_approach(InfluenceOperator& A, std::span<const double> h, double approach_m,
                                        std::span<double> p, double tolerance, int max_iterations);

 private:
  ConstrainedCgReport iterate(InfluenceOperator& A, std::span<const double> h, double pressure_sum,
                              std::optional<double> fixed_approach, std::span<double> p, double tolerance,
                              int max_iterations);
  ContactLaplacianPreconditioner preconditioner_;
  std::vector<double> u_;  // A p
  std::vector<double> r_;  // h + A p - delta
  std::vector<double> z_;  // preconditioned residual
  std::vector<double> t_;  // search direction (0 outside Ic)
  std::vector<double> q_;  // A t
  std::vector<std::uint8_t> in_contact_;
  // Elements whose pressure left the step's p − τ t in the last update, with the difference.
  std::vector<std::pair<std::size_t, double>> moved_;
  // Up to this many such elements A p is updated element by element (each mesh.size()
  // multiply-adds) rather than by a product on the whole grid.
  static constexpr std::size_t kLargestElementUpdate = 16;
};

}  // namespace railcontact::detail
