#pragma once
// Shared pieces of the Newton solvers of steady rolling with friction (docs/ROLLING.md):
// the steady-rolling operator R on the patch, the rigid slip, the forces, and the Newton
// linear operator J = A R + B (2 x 2 blocks A_e, B_e per element) with its preconditioner.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "elastic/influence_operator.hpp"
#include "railcontact/contact_patch.hpp"

namespace railcontact {

using Block2 = std::array<double, 4>;  // row-major 2 x 2: {a11, a12, a21, a22}

class RollingSystem {
 public:
  RollingSystem(const ContactPatch& patch, double alpha);

  [[nodiscard]] std::size_t count() const { return count_; }
  [[nodiscard]] const ContactPatch& patch() const { return patch_; }
  // Local (FastSim) part of R along a strip: R ~ lambda_k (shift_ahead - I), k = 1, 2.
  [[nodiscard]] double lambda1() const { return lambda1_; }
  [[nodiscard]] double lambda2() const { return lambda2_; }
  // Element e's neighbour ahead (towards the leading edge) is in contact: it is e + 1.
  [[nodiscard]] bool ahead_in_contact(std::size_t e) const { return ahead_[e] != 0; }

  // Rigid slip w = (xi - phi x2, eta + phi x1) at the collocation points, [w1; w2].
  [[nodiscard]] std::vector<double> rigid_slip(const Creepage& creepage) const;
  // The same from each strip's creepages (StripCreepages, one per mesh column).
  [[nodiscard]] std::vector<double> rigid_slip(const StripCreepages& creepages) const;
  // Traction bound g = mu p3 per element.
  [[nodiscard]] std::vector<double> traction_bound(double mu) const;
  // y = R x (FFT), vectors [c1 on elements; c2 on elements].
  void apply_R(const double* x, double* y);
  // (F1, F2, M3) = S D p (Eq 13).
  [[nodiscard]] TangentialForces forces(const std::vector<double>& p) const;

 private:
  const ContactPatch& patch_;
  std::size_t count_;
  double alpha_;
  InfluenceOperator R_;
  double lambda1_, lambda2_;
  std::vector<std::uint8_t> ahead_;
};

// The Newton matrix J x = A (R x) + B x of one Newton step, and its preconditioner: the exact
// inverse of A R_local + B, R_local the FastSim part of R, solved by marching each strip run
// from the leading edge with one 2 x 2 solve per element (O(N)).
class NewtonMatrix {
 public:
  explicit NewtonMatrix(RollingSystem& system);
  std::vector<Block2>& A() { return A_; }
  std::vector<Block2>& B() { return B_; }
  void apply(const double* x, double* y);
  void precondition(const double* r, double* z) const;

 private:
  RollingSystem& system_;
  std::vector<Block2> A_, B_;
  std::vector<double> Rx_;
};

struct NewtonStepReport {
  int krylov_iterations = 0;
  bool converged = false;
};

// Solves J dx = rhs with preconditioned GMRES.
NewtonStepReport solve_newton_step(NewtonMatrix& J, const std::vector<double>& rhs, std::vector<double>& dx,
                                   double tolerance, int max_iterations);

}  // namespace railcontact

#include "railcontact/tangential.hpp"

namespace railcontact {

// Throws railcontact::Error on non-physical input (mu, creepage, options).
void validate_rolling_input(const ContactPatch& patch, const Creepage& creepage, double mu,
                            const RollingOptions& options);
void validate_rolling_input(const ContactPatch& patch, const StripCreepages& creepages, double mu,
                            const RollingOptions& options);

// The larger of a and b, NaN if either is NaN (std::max(a, NaN) returns a: a residual taken with
// it would hide a NaN element and report convergence).
inline double max_or_nan(double a, double b) { return (b > a || std::isnan(b)) ? b : a; }

// Throws Error(internal) naming the solver ("exact", "regularised") if a converged solution holds a
// non-finite force, traction, slip or residual: its residual test covers every element (NaN
// propagating), so with finite input this cannot happen without a bug.
void require_finite_rolling_result(const char* solver, const RollingSolution& solution);

// Fills tractions, slip, flags, forces and the adhesion fraction of a solution.
void fill_rolling_solution(const RollingSystem& system, const std::vector<double>& p, const std::vector<double>& s,
                           const std::vector<std::uint8_t>& slip, RollingSolution& solution);

}  // namespace railcontact
