// The Krylov wrapper: GMRES's own residual estimate (used at loose tolerances instead of one more
// product) against the recomputed true residual, and non-convergence reported either way.
#include <gtest/gtest.h>

#include "elastic/influence_operator.hpp"
#include "elastic/krylov.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "tangential/steady_rolling_preconditioner.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};

struct AdjointProblem {
  ContactElements elements = elliptical_contact(6e-3, 4e-3, 24);
  InfluenceOperator R = make_steady_rolling_operator(elements.mesh(), kSteel, 0.0);
  SteadyRollingPreconditioner preconditioner{elements, 1.5};
  Eigen::Index n = static_cast<Eigen::Index>(elements.count());

  KrylovReport solve(const KrylovOptions& options) {
    const MatrixFreeOperator M(2 * n, [this](const double* x, double* y) {
      R.apply_transpose(elements.indices(), {x, static_cast<std::size_t>(2 * n)}, {y, static_cast<std::size_t>(2 * n)});
    });
    const ApplyFunction precondition = [this](const double* r, double* z) { preconditioner.apply_transpose(r, z); };
    Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * n);
    b.head(n).setOnes();  // the F1 row's adjoint right-hand side (up to the element area)
    Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * n);
    return solve_krylov(M, precondition, b, x, options);
  }
};

TEST(Krylov, GmresResidualEstimateEqualsTheTrueResidual) {
  AdjointProblem problem;
  for (double tolerance : {1e-3, 1e-6}) {
    KrylovOptions estimated;
    estimated.tolerance = tolerance;
    estimated.recompute_residual = false;
    KrylovOptions recomputed = estimated;
    recomputed.recompute_residual = true;
    const KrylovReport a = problem.solve(estimated);
    const KrylovReport b = problem.solve(recomputed);
    ASSERT_TRUE(a.converged && b.converged);
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_LE(a.relative_residual, tolerance);
    EXPECT_NEAR(a.relative_residual, b.relative_residual, 1e-6 * b.relative_residual) << tolerance;
  }
}

TEST(Krylov, ReportsNonConvergenceWithTheEstimatedResidual) {
  AdjointProblem problem;
  KrylovOptions options;
  options.tolerance = 1e-3;
  options.max_iterations = 2;
  options.recompute_residual = false;
  const KrylovReport report = problem.solve(options);
  EXPECT_FALSE(report.converged);
  EXPECT_GT(report.relative_residual, 1e-2);
  // Through the public API: K2's force rows at nH-FastSim's tolerance (estimated residual) throw.
  AdhesionOptions adhesion;
  adhesion.part = CreepageMatrixPart::force_rows;
  adhesion.tolerance = 1e-3;
  adhesion.max_iterations = 2;
  EXPECT_THROW(solve_full_adhesion(problem.elements, kSteel, adhesion), Error);
}

}  // namespace
}  // namespace railcontact
