// Full-adhesion steady-state rolling: K2 (paper Eq 14, 18).
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "elastic/influence_operator.hpp"
#include "elastic/krylov.hpp"
#include "tangential/adhesion_tuning.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/error.hpp"
#include "tangential/steady_rolling_preconditioner.hpp"
#include "tangential/matrix3_eigen.hpp"

namespace railcontact {
namespace {

// D^T for the three unit creepages (Eq 11-12) at the rigid-slip points: 2N x 3.
Eigen::MatrixXd rigid_slip_columns(const ContactElements& elements, double x1_offset_m) {
  const Mesh& mesh = elements.mesh();
  const auto n = static_cast<Eigen::Index>(elements.count());
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(2 * n, 3);
  for (Eigen::Index e = 0; e < n; ++e) {
    const std::size_t k = elements.indices()[e];
    const double x1 = mesh.x1(static_cast<int>(k % mesh.n1)) + x1_offset_m;
    const double x2 = mesh.x2(static_cast<int>(k / mesh.n1));
    w(e, 0) = 1.0;       // xi  -> w1
    w(n + e, 1) = 1.0;   // eta -> w2
    w(e, 2) = -x2;       // phi -> w1 = -phi x2
    w(n + e, 2) = x1;    //        w2 =  phi x1
  }
  return w;
}

// S D: forces and spin moment of piecewise-constant tractions (Eq 13), moment arms at the
// element centres (exact for constant traction per element).
Eigen::MatrixXd force_rows(const ContactElements& elements) {
  const Mesh& mesh = elements.mesh();
  const auto n = static_cast<Eigen::Index>(elements.count());
  const double S = mesh.element_area_m2();
  Eigen::MatrixXd SD = Eigen::MatrixXd::Zero(3, 2 * n);
  for (Eigen::Index e = 0; e < n; ++e) {
    const std::size_t k = elements.indices()[e];
    const double x1 = mesh.x1(static_cast<int>(k % mesh.n1));
    const double x2 = mesh.x2(static_cast<int>(k / mesh.n1));
    SD(0, e) = S;
    SD(1, n + e) = S;
    SD(2, e) = -x2 * S;
    SD(2, n + e) = x1 * S;
  }
  return SD;
}

void require_valid_offset(double alpha, const char* name) {
  require(std::isfinite(alpha) && alpha >= kMinimumCollocationOffset && alpha <= 1.0, [&] {
    return fmt::format("adhesion solver: the collocation offset {} = {:g} must lie in [{:g}, 1] (closer to -1 the "
                       "steady-rolling operator is too ill-conditioned for the Krylov solver)",
                       name, alpha, kMinimumCollocationOffset);
  });
}

// Nothing non-finite is returned. A Krylov solve that fails is reported as not converged before
// this (its residual test catches NaN); a dense LU of R, singular only for alpha = -1 (refused),
// or a Krylov solution passing its residual test cannot give non-finite K2 or tractions with
// valid input: an invariant is broken, kind internal.
// The solution as the solver builds it (Eigen), returned as AdhesionSolution's value types.
struct Work {
  Eigen::Matrix3d creepage_matrix = Eigen::Matrix3d::Zero();
  Eigen::MatrixXd unit_tractions;
  int iterations = 0;
  double relative_residual = 0.0;
};

void require_finite_solution(const Work& s, CreepageMatrixPart part) {
  const bool K2_finite = part == CreepageMatrixPart::full ? s.creepage_matrix.allFinite()
                                                          : s.creepage_matrix.topRows<2>().allFinite();
  if (K2_finite && s.unit_tractions.allFinite()) return;
  throw Error(ErrorKind::internal, fmt::format("adhesion solver: the creepage matrix K2 or the unit tractions are not "
                                               "finite (K2_11 = {:g}, K2_22 = {:g}, K2_23 = {:g}); not returned (a bug: "
                                               "please report it)",
                                               s.creepage_matrix(0, 0), s.creepage_matrix(1, 1), s.creepage_matrix(1, 2)));
}

// GMRES's restart length. Eigen's GMRES allocates and zeroes its Householder basis, 2N x
// (restart + 1) doubles, on every solve: 290 kB with the default 60 on a coarse patch of 300
// elements. Loose solves (nH-FastSim's 3e-3) take 4-12 iterations per right-hand side, so a
// restart of 20 changes no result there; tight solves keep 60 (a restart slows GMRES down).
int restart_for(double tolerance) { return tolerance >= 1e-4 ? 20 : 60; }

// Solves R(alpha) P = W for the given columns of W (the unit creepages), writing into P.
void solve_columns(const ContactElements& elements, const Material& material, double alpha,
                   RigidSlipPoint rigid_slip_point, const std::vector<int>& columns, const AdhesionOptions& options,
                   const AdhesionTuning& tuning, Work& solution) {
  const Mesh& mesh = elements.mesh();
  const auto n = static_cast<Eigen::Index>(elements.count());
  const double slip_offset =
      rigid_slip_point == RigidSlipPoint::collocation ? 0.5 * alpha * mesh.dx1_m : 0.5 * (alpha + 1.0) * mesh.dx1_m;
  const Eigen::MatrixXd W = rigid_slip_columns(elements, slip_offset);
  InfluenceOperator R = make_steady_rolling_operator(mesh, material, alpha);
  if (options.solver == LinearSolver::dense) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(R.dense(elements.indices()));
    for (int j : columns) solution.unit_tractions.col(j) = lu.solve(W.col(j));
    return;
  }
  const MatrixFreeOperator M(2 * n, [&R, &elements, n](const double* x, double* y) {
    R.apply(elements.indices(), {x, static_cast<std::size_t>(2 * n)}, {y, static_cast<std::size_t>(2 * n)});
  });
  const SteadyRollingPreconditioner preconditioner(
      elements, tuning.preconditioner == AdhesionPreconditioner::marching ? 0.0 : tuning.half_laplacian_gamma);
  const ApplyFunction precondition = [&preconditioner](const double* r, double* z) { preconditioner.apply(r, z); };
  KrylovOptions krylov;
  krylov.tolerance = options.tolerance;
  krylov.max_iterations = options.max_iterations;
  krylov.gmres_restart = restart_for(options.tolerance);
  for (int j : columns) {
    const Eigen::VectorXd rhs = W.col(j);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * n);
    const KrylovReport report = solve_krylov(M, precondition, rhs, x, krylov);
    solution.iterations += report.iterations;
    solution.relative_residual = std::max(solution.relative_residual, report.relative_residual);
    if (!report.converged) {
      static const char* const names[] = {"xi", "eta", "phi"};
      throw Error(ErrorKind::not_converged, fmt::format(
          "adhesion solver: GMRES did not converge for unit {} in {} iterations (relative residual {:.2e} > {:.1e})",
          names[j], report.iterations, report.relative_residual, options.tolerance));
    }
    solution.unit_tractions.col(j) = x;
  }
}

// What the adjoint solutions y_i = R^-T (S D)^T e_i of solve_force_rows depend on: the elements'
// indices on their mesh, the mesh's size and element sizes, the material and the solver's settings.
// Not where the patch lies: R is translation invariant and the force rows of S D are the elements'
// areas. K2's rows y_i^T W do depend on the positions (its spin column on the distance from the
// patch's origin, the centre of pressure).
struct AdjointKey {
  int n1 = 0, n2 = 0;
  double dx1_m = 0.0, dx2_m = 0.0;
  std::vector<std::size_t> indices;
  double youngs_modulus_Pa = 0.0, poisson_ratio = 0.0;
  double alpha = 0.0, tolerance = 0.0;
  int max_iterations = 0;
  AdhesionPreconditioner preconditioner = AdhesionPreconditioner::marching;
  double gamma = 0.0;
  bool operator==(const AdjointKey&) const = default;
};

struct AdjointSolutions {
  AdjointKey key;
  std::array<Eigen::VectorXd, 2> y;
  int iterations = 0;
  double relative_residual = 0.0;
};

// The adjoint solutions of the last few patches solved on this thread. A wheelset's time step
// meets the same coarse patch (nH-FastSim's K2 blocks) step after step, and by load at every trial
// height of a step: its K2 rows are then y_i^T W of the remembered y_i, the same numbers as a new
// solve's (the solve is a function of the key alone; test NhFastSim.AMovedPatchGetsTheSameK2AsAFreshSolve),
// without its GMRES (docs/FASTSIM.md "K2 of a patch met before"). Like FFTW's plans, a pure cache:
// nothing a caller sees depends on it but the time.
const AdjointSolutions* remembered_adjoints(const AdjointKey& key, std::vector<AdjointSolutions>& memo) {
  for (auto it = memo.begin(); it != memo.end(); ++it) {
    if (it->key == key) {
      std::rotate(it, it + 1, memo.end());  // most recent last
      return &memo.back();
    }
  }
  return nullptr;
}

std::vector<AdjointSolutions>& remembered_adjoints_of_this_thread() {
  thread_local std::vector<AdjointSolutions> memo;
  return memo;
}

// Rows 1 and 2 of K2 by adjoint solves: K2(i, :) = (R^-T (S D)^T e_i)^T W.
void solve_force_rows(const ContactElements& elements, const Material& material, const AdhesionOptions& options,
                      const AdhesionTuning& tuning, Work& solution) {
  const Mesh& mesh = elements.mesh();
  const auto n = static_cast<Eigen::Index>(elements.count());
  const double alpha = options.collocation_offset;
  const double slip_offset = options.rigid_slip_point == RigidSlipPoint::collocation ? 0.5 * alpha * mesh.dx1_m
                                                                                      : 0.5 * (alpha + 1.0) * mesh.dx1_m;
  const Eigen::MatrixXd W = rigid_slip_columns(elements, slip_offset);
  solution.creepage_matrix.setConstant(std::numeric_limits<double>::quiet_NaN());
  if (options.solver == LinearSolver::dense) {
    const Eigen::MatrixXd SD = force_rows(elements);
    InfluenceOperator R = make_steady_rolling_operator(mesh, material, alpha);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(R.dense(elements.indices()).transpose());
    for (int i = 0; i < 2; ++i) solution.creepage_matrix.row(i) = (lu.solve(SD.row(i).transpose())).transpose() * W;
    return;
  }
  // A patch met before: its rows from the remembered adjoint solutions, before the operator and
  // the preconditioner are made.
  // nH-FastSim's coarse patches have 250-1000 elements; the memo stays below 1.2 MB a thread.
  constexpr std::size_t kRememberedPatches = 8;
  constexpr std::size_t kLargestRememberedPatch = 4096;  // elements
  std::vector<AdjointSolutions>& memo = remembered_adjoints_of_this_thread();
  AdjointKey key{mesh.n1,
                 mesh.n2,
                 mesh.dx1_m,
                 mesh.dx2_m,
                 elements.indices(),
                 material.youngs_modulus_Pa,
                 material.poisson_ratio,
                 alpha,
                 options.tolerance,
                 options.max_iterations,
                 tuning.preconditioner,
                 tuning.half_laplacian_gamma};
  if (const AdjointSolutions* known = remembered_adjoints(key, memo)) {
    for (int i = 0; i < 2; ++i) solution.creepage_matrix.row(i) = known->y[static_cast<std::size_t>(i)].transpose() * W;
    solution.iterations += known->iterations;
    solution.relative_residual = std::max(solution.relative_residual, known->relative_residual);
    return;
  }
  const Eigen::MatrixXd SD = force_rows(elements);
  InfluenceOperator R = make_steady_rolling_operator(mesh, material, alpha);
  const MatrixFreeOperator M(2 * n, [&R, &elements, n](const double* x, double* y) {
    R.apply_transpose(elements.indices(), {x, static_cast<std::size_t>(2 * n)}, {y, static_cast<std::size_t>(2 * n)});
  });
  const SteadyRollingPreconditioner preconditioner(
      elements, tuning.preconditioner == AdhesionPreconditioner::marching ? 0.0 : tuning.half_laplacian_gamma);
  const ApplyFunction precondition = [&preconditioner](const double* r, double* z) {
    preconditioner.apply_transpose(r, z);
  };
  AdjointSolutions solved;
  KrylovOptions krylov;
  krylov.tolerance = options.tolerance;
  krylov.max_iterations = options.max_iterations;
  // nH-FastSim's loose tolerance (3e-3): GMRES's residual estimate is exact to far better than
  // that; its recomputation would be one more product per row (~10 % of K2 on a coarse patch).
  krylov.recompute_residual = options.tolerance < 1e-6;
  krylov.gmres_restart = restart_for(options.tolerance);
  for (int i = 0; i < 2; ++i) {
    const Eigen::VectorXd rhs = SD.row(i).transpose();
    Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
    const KrylovReport report = solve_krylov(M, precondition, rhs, y, krylov);
    solution.iterations += report.iterations;
    solution.relative_residual = std::max(solution.relative_residual, report.relative_residual);
    if (!report.converged)
      throw Error(ErrorKind::not_converged, fmt::format("adhesion solver: GMRES did not converge for the adjoint of F{} in {} iterations "
                              "(relative residual {:.2e} > {:.1e})",
                              i + 1, report.iterations, report.relative_residual, options.tolerance));
    solution.creepage_matrix.row(i) = y.transpose() * W;
    solved.iterations += report.iterations;
    solved.relative_residual = std::max(solved.relative_residual, report.relative_residual);
    solved.y[static_cast<std::size_t>(i)] = std::move(y);
  }
  if (elements.count() > kLargestRememberedPatch) return;
  solved.key = std::move(key);
  if (memo.size() == kRememberedPatches) memo.erase(memo.begin());
  memo.push_back(std::move(solved));
}

}  // namespace

void forget_remembered_adjoints() { remembered_adjoints_of_this_thread().clear(); }

AdhesionSolution solve_full_adhesion(const ContactElements& elements, const Material& material,
                                     const AdhesionOptions& options) {
  return solve_full_adhesion(elements, material, options, AdhesionTuning{});
}

AdhesionSolution solve_full_adhesion(const ContactElements& elements, const Material& material,
                                     const AdhesionOptions& options, const AdhesionTuning& tuning) {
  validate(material);
  validate(elements.mesh());
  require(elements.count() > 0, "adhesion solver: no elements in contact");
  require_valid_offset(options.collocation_offset, "alpha");
  const double spin_alpha = options.spin_collocation_offset.value_or(options.collocation_offset);
  require_valid_offset(spin_alpha, "alpha of the spin column");
  require(std::isfinite(tuning.half_laplacian_gamma) && tuning.half_laplacian_gamma > 0.0,
          "adhesion solver: the preconditioner's gamma must be positive and finite");
  if (options.solver == LinearSolver::krylov) {
    require(std::isfinite(options.tolerance) && options.tolerance > 0 && options.tolerance <= 1e-2, [&] {
      return fmt::format("adhesion solver: the Krylov tolerance = {:g} must lie in (0, 0.01]", options.tolerance);
    });
    require(options.max_iterations > 0, [&] {
      return fmt::format("adhesion solver: the Krylov iteration limit max_iterations = {} must be positive",
                         options.max_iterations);
    });
  } else {
    // The dense matrix and its LU take 2 (2N)^2 doubles (9 GB at N = 12000) and O(N^3) time.
    require(elements.count() <= 12000, [&] {
      return "adhesion solver: " + std::to_string(elements.count()) +
             " elements are too many for the dense solver (at most 12000: it would not fit "
             "in memory); use the Krylov solver";
    });
  }
  const auto n = static_cast<Eigen::Index>(elements.count());
  Work work;
  if (options.part == CreepageMatrixPart::force_rows) {
    require(spin_alpha == options.collocation_offset,
            "adhesion solver: the force rows of K2 need one collocation offset for all creepages");
    solve_force_rows(elements, material, options, tuning, work);
  } else {
    work.unit_tractions.resize(2 * n, 3);
    if (spin_alpha == options.collocation_offset) {
      solve_columns(elements, material, spin_alpha, options.rigid_slip_point, {0, 1, 2}, options, tuning, work);
    } else {
      solve_columns(elements, material, options.collocation_offset, options.rigid_slip_point, {0, 1}, options, tuning,
                    work);
      solve_columns(elements, material, spin_alpha, options.rigid_slip_point, {2}, options, tuning, work);
    }
    work.creepage_matrix = force_rows(elements) * work.unit_tractions;
  }
  require_finite_solution(work, options.part);
  AdhesionSolution solution;
  solution.creepage_matrix = detail::to_matrix3(work.creepage_matrix);
  solution.unit_tractions.rows = static_cast<std::size_t>(work.unit_tractions.rows());
  solution.unit_tractions.values.assign(work.unit_tractions.data(),
                                        work.unit_tractions.data() + work.unit_tractions.size());  // column-major
  solution.iterations = work.iterations;
  solution.relative_residual = work.relative_residual;
  return solution;
}

CreepageCoefficients creepage_coefficients(const Matrix3& K2, double G, double c) {
  require(G > 0 && c > 0, "creepage coefficients: G and c must be positive");
  return {-K2(0, 0) / (G * c * c), -K2(1, 1) / (G * c * c), -K2(1, 2) / (G * c * c * c),
          -K2(2, 2) / (G * c * c * c * c)};
}

}  // namespace railcontact
