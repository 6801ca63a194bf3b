// Normal contact solver (METHOD.md §5): input checks, the reusable plan (influence operator and
// workspace), and the solution record. The iteration is in constrained_cg.cpp, the starting
// pressure in initial_pressure.cpp.
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "elastic/influence_operator.hpp"
#include "normal/constrained_cg.hpp"
#include "normal/initial_pressure.hpp"
#include "normal/known_product.hpp"
#include "railcontact/error.hpp"
#include "railcontact/normal.hpp"

namespace railcontact {

struct NormalContactSolver::Plan {
  Plan(const Mesh& m, const Material& material, const NormalOptions& o)
      : mesh(m),
        options(o),
        A(make_normal_operator(m, material)),
        cg(m),
        relative_distance(m.size()),
        work(m.size()) {}
  Mesh mesh;
  NormalOptions options;
  InfluenceOperator A;  // A33 on the whole mesh (zero-padded FFT)
  detail::ConstrainedConjugateGradient cg;
  std::vector<double> relative_distance;  // h - min(h): the iteration works on O(A p) numbers
  std::vector<double> work;
};

namespace {

void validate_options(const NormalOptions& options) {
  require(std::isfinite(options.tolerance) && options.tolerance > 0.0,
          "normal contact: the tolerance must be positive and finite");
  require(options.max_iterations > 0, "normal contact: the iteration limit must be positive");
}

// Checks of the problem data (the mesh first: its size is needed for h).
void validate_problem(const Mesh& mesh, const std::vector<double>& h, double normal_force_N) {
  validate(mesh);
  require(h.size() == mesh.size(), [&] {
    return fmt::format("normal contact: {} undeformed distances given for a mesh of {} elements", h.size(),
                       mesh.size());
  });
  const auto bad = std::find_if(h.begin(), h.end(), [](double value) { return !std::isfinite(value); });
  require(bad == h.end(), [&] {
    return fmt::format("normal contact: the undeformed distance of element {} is not finite",
                       static_cast<std::size_t>(bad - h.begin()));
  });
  validate_normal_force(normal_force_N, "normal contact: the normal force F3");
}

// Every number of a returned solution is finite. The iteration works on finite data (checked
// above), so a non-finite pressure or approach means the conjugate gradients broke down (an
// overflow or a division by a vanishing curvature of the search): the solver did not produce a
// solution, kind not_converged, never a result.
void require_finite_solution(const NormalSolution& s, const std::vector<double>& pressure_Pa) {
  const auto bad = std::find_if(pressure_Pa.begin(), pressure_Pa.end(), [](double p) { return !std::isfinite(p); });
  if (bad == pressure_Pa.end() && std::isfinite(s.approach_m) && std::isfinite(s.residual))
    return;
  throw Error(ErrorKind::not_converged,
              fmt::format("normal contact: the conjugate-gradient iteration broke down after {} iterations (a "
                          "non-finite {}); no solution",
                          s.iterations,
                          bad != pressure_Pa.end() ? fmt::format("pressure at element {}", bad - pressure_Pa.begin())
                                                   : std::string("approach or residual")));
}

bool on_border(const Mesh& mesh, std::size_t k) {
  const auto i1 = static_cast<int>(k % static_cast<std::size_t>(mesh.n1));
  const auto i2 = static_cast<int>(k / static_cast<std::size_t>(mesh.n1));
  return i1 == 0 || i2 == 0 || i1 == mesh.n1 - 1 || i2 == mesh.n2 - 1;
}

// The elements in contact of a solution, whether one lies on the mesh's border, and the sum of
// their pressures (Pa).
double count_contact(const Mesh& mesh, NormalSolution& solution) {
  double sum = 0.0;
  for (std::size_t k = 0; k < mesh.size(); ++k) {
    const double p = solution.pressure_Pa[k];
    if (p > 0.0) {
      sum += p;
      ++solution.elements_in_contact;
      if (on_border(mesh, k)) solution.touches_border = true;
    }
  }
  return sum;
}

}  // namespace

NormalContactSolver::NormalContactSolver(const Mesh& mesh, const Material& material, const NormalOptions& options) {
  validate(mesh);
  validate(material);
  validate_options(options);
  plan_ = std::make_unique<Plan>(mesh, material, options);
}

NormalContactSolver::~NormalContactSolver() = default;
NormalContactSolver::NormalContactSolver(NormalContactSolver&&) noexcept = default;
NormalContactSolver& NormalContactSolver::operator=(NormalContactSolver&&) noexcept = default;

const Mesh& NormalContactSolver::mesh() const { return plan_->mesh; }

NormalSolution NormalContactSolver::solve(const std::vector<double>& h, double normal_force_N) {
  const Mesh& mesh = plan_->mesh;
  validate_problem(mesh, h, normal_force_N);

  // The problem is invariant under h -> h - c, delta -> delta - c: solve with min(h) = 0.
  const double h_min = *std::min_element(h.begin(), h.end());
  std::vector<double>& z = plan_->relative_distance;
  for (std::size_t k = 0; k < h.size(); ++k) z[k] = h[k] - h_min;

  const double S = mesh.element_area_m2();
  const double pressure_sum = normal_force_N / S;  // sum S p3 = F3
  NormalSolution solution;
  solution.pressure_Pa.resize(mesh.size());
  detail::hertz_like_initial_pressure(plan_->A, z, pressure_sum, solution.pressure_Pa, plan_->work);
  const detail::ConstrainedCgReport report = plan_->cg.solve(
      plan_->A, z, pressure_sum, solution.pressure_Pa, plan_->options.tolerance, plan_->options.max_iterations);
  solution.iterations = report.iterations;
  solution.approach_m = report.approach_m + h_min;
  solution.residual = report.residual;
  require_finite_solution(solution, solution.pressure_Pa);

  const double sum = count_contact(mesh, solution);
  if (solution.elements_in_contact == 0)
    throw Error(ErrorKind::no_contact, "normal contact: no contact formed (no element carries pressure)");
  solution.normal_force_N = S * sum;
  solution.converged = report.converged;
  return solution;
}

NormalSolution NormalContactSolver::solve_at_approach(const std::vector<double>& h, double approach_m,
                                                      const std::vector<double>& initial_pressure_Pa) {
  return detail::NormalSolverAccess::solve_at_approach(*this, h, approach_m, initial_pressure_Pa, nullptr, nullptr);
}

namespace detail {

NormalSolution NormalSolverAccess::solve_at_approach(NormalContactSolver& solver, const std::vector<double>& h,
                                                     double approach_m, const std::vector<double>& initial_pressure_Pa,
                                                     const KnownProduct* known, std::vector<double>* final_product_m,
                                                     StartKind start) {
  NormalContactSolver::Plan& plan = *solver.plan_;
  const Mesh& mesh = plan.mesh;
  validate_problem(mesh, h, kMinimumNormalForce_N);
  require(std::isfinite(approach_m) && std::abs(approach_m) < 1.0, [&] {
    return fmt::format("normal contact: the approach {} m must be finite and below 1 m in size", approach_m);
  });
  require(initial_pressure_Pa.empty() || initial_pressure_Pa.size() == mesh.size(), [&] {
    return fmt::format("normal contact: {} initial pressures given for a mesh of {} elements",
                       initial_pressure_Pa.size(), mesh.size());
  });
  NormalSolution solution;
  solution.pressure_Pa.assign(mesh.size(), 0.0);
  for (std::size_t k = 0; k < initial_pressure_Pa.size(); ++k) {
    const double p = initial_pressure_Pa[k];
    require(std::isfinite(p) && p >= 0.0, "normal contact: an initial pressure is negative or not finite");
    // Only where the bodies overlap: elsewhere the old pressure would have to leave the set first.
    solution.pressure_Pa[k] = h[k] < approach_m ? p : 0.0;
  }
  // The start's product from the known one: A p0 = A p_known + A (p0 − p_known), the difference
  // element by element where it is non-zero (few: the prediction's elements floored at zero).
  std::vector<double>& start_product = plan.work;
  bool product_known = known != nullptr && known->pressure_Pa.size() == mesh.size() &&
                       known->displacement_m.size() == mesh.size();
  std::vector<std::size_t> differing;
  for (std::size_t k = 0; k < mesh.size() && product_known; ++k)
    if (solution.pressure_Pa[k] != known->pressure_Pa[k]) {
      differing.push_back(k);
      product_known = differing.size() <= ConstrainedConjugateGradient::kLargestElementUpdate;
    }
  if (product_known) {
    std::copy(known->displacement_m.begin(), known->displacement_m.end(), start_product.begin());
    for (const std::size_t k : differing)
      plan.A.add_element_product(k, solution.pressure_Pa[k] - known->pressure_Pa[k], start_product);
  }
  const ConstrainedCgReport report = plan.cg.solve_at_approach(
      plan.A, h, approach_m, solution.pressure_Pa, plan.options.tolerance, plan.options.max_iterations,
      product_known ? std::span<const double>(start_product.data(), mesh.size()) : std::span<const double>{},
      start == StartKind::time_step_prediction ? ContactLaplacianPreconditioner::kTimeStepGamma
                                               : ContactLaplacianPreconditioner::kDefaultGamma);
  solution.iterations = report.iterations;
  solution.approach_m = approach_m;
  solution.residual = report.residual;
  require_finite_solution(solution, solution.pressure_Pa);
  const double sum = count_contact(mesh, solution);
  solution.normal_force_N = mesh.element_area_m2() * sum;
  solution.converged = report.converged;
  if (final_product_m != nullptr) {
    const std::span<const double> u = plan.cg.product();
    final_product_m->assign(u.begin(), u.end());
  }
  return solution;
}

}  // namespace detail

double NormalContactSolver::complementarity_residual(const std::vector<double>& h, double approach_m,
                                                    const std::vector<double>& pressure_Pa,
                                                    std::vector<double>* displacement_m) {
  const Mesh& mesh = plan_->mesh;
  validate_problem(mesh, h, kMinimumNormalForce_N);
  require(std::isfinite(approach_m), [&] {
    return fmt::format("normal contact: the approach {} m for the residual must be finite", approach_m);
  });
  require(pressure_Pa.size() == mesh.size(), [&] {
    return fmt::format("normal contact: {} pressures given for the residual on a mesh of {} elements",
                       pressure_Pa.size(), mesh.size());
  });
  const auto bad = std::find_if(pressure_Pa.begin(), pressure_Pa.end(),
                                [](double p) { return !std::isfinite(p) || p < 0.0; });
  require(bad == pressure_Pa.end(), [&] {
    return fmt::format("normal contact: the pressure {} Pa of element {} given for the residual must be finite "
                       "and >= 0",
                       *bad, static_cast<std::size_t>(bad - pressure_Pa.begin()));
  });
  std::vector<double>& u = plan_->work;
  plan_->A.apply_on_grid(pressure_Pa, u);
  // As the conjugate gradients define it: |g| where p > 0, max(0, -g) where p = 0, over max A p.
  double violation = 0.0, u_max = 0.0;
  for (std::size_t k = 0; k < mesh.size(); ++k) {
    const double g = h[k] + u[k] - approach_m;
    u_max = std::max(u_max, u[k]);
    violation = std::max(violation, pressure_Pa[k] > 0.0 ? std::fabs(g) : -g);
  }
  if (displacement_m != nullptr) displacement_m->assign(u.begin(), u.begin() + static_cast<std::ptrdiff_t>(mesh.size()));
  return u_max > 0.0 ? violation / u_max : (violation > 0.0 ? 1.0 : 0.0);
}

NormalSolution solve_normal_contact_at_approach(const Mesh& mesh, const std::vector<double>& undeformed_distance_m,
                                                double approach_m, const Material& material,
                                                const NormalOptions& options) {
  validate_problem(mesh, undeformed_distance_m, kMinimumNormalForce_N);
  NormalContactSolver solver(mesh, material, options);
  return solver.solve_at_approach(undeformed_distance_m, approach_m);
}

NormalSolution solve_normal_contact(const Mesh& mesh, const std::vector<double>& undeformed_distance_m,
                                    double normal_force_N, const Material& material, const NormalOptions& options) {
  validate_problem(mesh, undeformed_distance_m, normal_force_N);  // before building the operator
  NormalContactSolver solver(mesh, material, options);
  return solver.solve(undeformed_distance_m, normal_force_N);
}

}  // namespace railcontact
