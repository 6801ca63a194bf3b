#include "elastic/krylov.hpp"

#include <algorithm>
#include <cmath>

namespace railcontact {

KrylovReport solve_krylov(const MatrixFreeOperator& M, const ApplyFunction& preconditioner, const Eigen::VectorXd& b,
                          Eigen::VectorXd& x, const KrylovOptions& options) {
  KrylovReport report;
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    x.setZero();
    report.converged = true;
    return report;
  }
  if (x.size() != b.size()) x = Eigen::VectorXd::Zero(b.size());
  {
    // Right preconditioning, M P y = b - M x0, x = x0 + P y: GMRES then minimises and tests
    // the true residual (Eigen's GMRES preconditions from the left).
    Eigen::VectorXd r0 = b;
    if (!x.isZero(0.0)) {  // a zero start needs no product
      Eigen::VectorXd Mx(b.size());
      M.apply(x.data(), Mx.data());
      r0 -= Mx;
    }
    Eigen::VectorXd work(b.size());
    const MatrixFreeOperator MP(M.rows(), [&](const double* y, double* out) {
      preconditioner(y, work.data());
      M.apply(work.data(), out);
    });
    Eigen::GMRES<MatrixFreeOperator, Eigen::IdentityPreconditioner> solver;  // preconditioned in MP
    solver.setTolerance(options.tolerance * b_norm / std::max(r0.norm(), 1e-300));
    solver.setMaxIterations(options.max_iterations);
    solver.set_restart(options.gmres_restart);
    solver.compute(MP);
    const Eigen::VectorXd y = solver.solve(r0);
    Eigen::VectorXd correction(b.size());
    preconditioner(y.data(), correction.data());
    x += correction;
    report.iterations = static_cast<int>(solver.iterations());
    if (!options.recompute_residual) {
      // GMRES's own residual of M P y = r0 is the true residual b - M x (right preconditioning),
      // up to rounding.
      report.relative_residual = solver.error() * std::max(r0.norm(), 1e-300) / b_norm;
      report.converged = solver.info() == Eigen::Success && std::isfinite(report.relative_residual) &&
                         report.relative_residual <= 10.0 * options.tolerance;
      return report;
    }
  }
  Eigen::VectorXd residual(b.size());
  M.apply(x.data(), residual.data());
  residual = b - residual;
  report.relative_residual = residual.norm() / b_norm;
  // The solvers stop on their own (possibly preconditioned) residual; accept a true residual
  // within a small factor of the requested tolerance.
  report.converged = std::isfinite(report.relative_residual) && report.relative_residual <= 10.0 * options.tolerance;
  return report;
}

}  // namespace railcontact
