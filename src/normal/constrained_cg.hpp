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
// Only the product A t needs an FFT when the set is unchanged: A p is updated recursively (and
// recomputed after a change of more than kLargestElementUpdate elements, and before convergence is
// accepted after more than kLargestRecursion updates).
#include <cstddef>
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
  double residual = 0.0;   // max complementarity violation / max(A p), from an A p made by FFT
                           // at most kLargestRecursion updates before
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
  // With `product` given (A p of the initial p, to rounding: a time step's start from the last
  // steps' products, wheel_rail/wheelset_solver.cpp) the first product by FFT is left out; it counts
  // as one recursive update of A p. `preconditioner_gamma`: ContactLaplacianPreconditioner's gamma
  // for this solve (its kTimeStepGamma for a time step's predicted start).
  ConstrainedCgReport solve_at_approach(InfluenceOperator& A, std::span<const double> h, double approach_m,
                                        std::span<double> p, double tolerance, int max_iterations,
                                        std::span<const double> product = {},
                                        double preconditioner_gamma = ContactLaplacianPreconditioner::kDefaultGamma);
  // A p of the last solve's p (m), to rounding: the product the iteration ended with.
  [[nodiscard]] std::span<const double> product() const { return u_; }
  // Up to this many elements A p is updated element by element (each mesh.size() multiply-adds)
  // rather than by a product on the whole grid.
  static constexpr std::size_t kLargestElementUpdate = 16;

 private:
  ConstrainedCgReport iterate(InfluenceOperator& A, std::span<const double> h, double pressure_sum,
                              std::optional<double> fixed_approach, std::span<double> p, double tolerance,
                              int max_iterations, std::span<const double> product = {});

  // The steps of one iteration (see the top of this header), on the work vectors below.
  struct ContactSet {
    std::size_t count = 0;  // elements in Ic
    double gap_sum = 0.0;   // sum over Ic of h + A p
  };
  struct GapResidual {
    double violation = 0.0;  // |g| where p > 0, max(0, -g) where p = 0: its largest value
    double u_max = 0.0;      // max(A p)
  };
  struct PressureStep {
    double pressure_sum = 0.0;  // sum p after the step, before the load scaling
    bool set_changed = false;   // an element left or entered Ic
    bool recursive = true;      // A p may follow by recursion (few elements moved)
  };
  // Ic = {p > 0} into contact_mask_ (PK step 1).
  ContactSet mark_contact_set(std::span<const double> p, std::span<const double> h);
  // r = g = h - delta + A p into r_ (PK step 2) and the complementarity violation.
  GapResidual gap_residual(std::span<const double> h, double delta);
  // An empty set with the approach given: p = -r / (4 A(0,0)) where r < 0, and A p recomputed.
  // True when an element entered.
  bool enter_overlap(InfluenceOperator& A, std::span<double> p, double entry_step);
  // Preconditioned residual z = M r into z_, projected on sum z = 0 with the load given (the
  // load is kept by the step); returns G = r.z > 0 (M is positive definite on Ic).
  double preconditioned_residual(std::size_t contact_count, bool load_given);
  // t = z + beta t on Ic, 0 elsewhere (PK step 3).
  void conjugate_direction(double beta);
  // q = A t into q_ (PK step 4) and the step length tau = sum_Ic r t / sum_Ic (q - mean_Ic q) t
  // (PK step 5).
  double step_length(InfluenceOperator& A, std::size_t contact_count, bool load_given);
  // p <- max(0, p - tau t) on Ic (PK step 6) and p <- -entry_step r outside Ic where
  // r < entry_threshold (PK step 7). The elements whose new pressure differs from p - tau t
  // (clamped to zero, or entered) go to moved_ with the difference.
  PressureStep project_pressure(std::span<double> p, double tau, double entry_threshold, double entry_step);
  // p <- p P / sum p (PK step 8), after a restart from the deepest point if sum p is not positive;
  // returns the scale.
  double restore_load(std::span<double> p, double pressure_sum, PressureStep& step) const;
  // A p after the step: with few moved elements by the recursion's (u - tau q) plus their
  // products by the kernel table, times the load scale, instead of a product on the whole grid.
  // True when recomputed on the whole grid (u_ fresh).
  bool update_pressure_product(InfluenceOperator& A, std::span<const double> p, const PressureStep& step,
                               double tau, double scale);

  ContactLaplacianPreconditioner preconditioner_;
  std::vector<double> u_;  // A p
  std::vector<double> r_;  // h + A p - delta
  std::vector<double> z_;  // preconditioned residual
  std::vector<double> t_;  // search direction (0 outside Ic)
  std::vector<double> q_;  // A t
  std::vector<double> contact_mask_;  // 1 on Ic, 0 elsewhere: the sums over Ic as vectorised products
  // Elements whose pressure left the step's p − τ t in the last update, with the difference.
  std::vector<std::pair<std::size_t, double>> moved_;
  // The most recursive updates of A p after which it decides convergence without a product by FFT.
  static constexpr int kLargestRecursion = 64;
};

}  // namespace railcontact::detail
