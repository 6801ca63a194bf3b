#include "tangential/rolling_system.hpp"

#include <algorithm>
#include <cmath>

#include "elastic/krylov.hpp"

namespace railcontact {

RollingSystem::RollingSystem(const ContactPatch& patch, double alpha)
    : patch_(patch),
      count_(patch.elements().count()),
      alpha_(alpha),
      R_(make_steady_rolling_operator(patch.mesh(), patch.material(), alpha)),
      ahead_(count_, 0) {
  // λ = (R's coefficient of the element behind − its own) / 2 depends on the element size and the
  // material only. A patch one element long (a patch that has just appeared on a flank) has no
  // element behind in its own mesh: the coefficients come from a mesh two elements long.
  if (patch.mesh().n1 > 1) {
    lambda1_ = 0.5 * (R_.kernel(0, 0, -1, 0) - R_.kernel(0, 0, 0, 0));
    lambda2_ = 0.5 * (R_.kernel(1, 1, -1, 0) - R_.kernel(1, 1, 0, 0));
  } else {
    Mesh two = patch.mesh();
    two.n1 = 2;
    two.n2 = 1;
    const InfluenceOperator R2 = make_steady_rolling_operator(two, patch.material(), alpha);
    lambda1_ = 0.5 * (R2.kernel(0, 0, -1, 0) - R2.kernel(0, 0, 0, 0));
    lambda2_ = 0.5 * (R2.kernel(1, 1, -1, 0) - R2.kernel(1, 1, 0, 0));
  }
  const auto& idx = patch.elements().indices();
  const auto n1 = static_cast<std::size_t>(patch.mesh().n1);
  for (std::size_t e = 0; e + 1 < count_; ++e)
    ahead_[e] = (idx[e + 1] == idx[e] + 1 && (idx[e] % n1) + 1 < n1) ? 1 : 0;
}

std::vector<double> RollingSystem::rigid_slip(const Creepage& c) const {
  std::vector<double> w(2 * count_);
  const double shift = 0.5 * alpha_ * patch_.mesh().dx1_m;
  for (std::size_t e = 0; e < count_; ++e) {
    const double x1 = patch_.x1(e) + shift;
    const double x2 = patch_.x2(e);
    w[e] = c.xi - c.phi * x2;
    w[count_ + e] = c.eta + c.phi * x1;
  }
  return w;
}

std::vector<double> RollingSystem::rigid_slip(const StripCreepages& creepages) const {
  std::vector<double> w(2 * count_);
  const double shift = 0.5 * alpha_ * patch_.mesh().dx1_m;
  const auto& idx = patch_.elements().indices();
  const auto n1 = static_cast<std::size_t>(patch_.mesh().n1);
  for (std::size_t e = 0; e < count_; ++e) {
    const Creepage& c = creepages[idx[e] / n1];
    w[e] = c.xi;
    w[count_ + e] = c.eta + c.phi * (patch_.x1(e) + shift);
  }
  return w;
}

std::vector<double> RollingSystem::traction_bound(double mu) const {
  std::vector<double> bound(count_);
  for (std::size_t e = 0; e < count_; ++e) bound[e] = mu * patch_.pressure_Pa()[e];
  return bound;
}

void RollingSystem::apply_R(const double* x, double* y) {
  R_.apply(patch_.elements().indices(), {x, 2 * count_}, {y, 2 * count_});
}

TangentialForces RollingSystem::forces(const std::vector<double>& p) const {
  const double S = patch_.mesh().element_area_m2();
  TangentialForces f;
  for (std::size_t e = 0; e < count_; ++e) {
    const double p1 = p[e], p2 = p[count_ + e];
    f.F1_N += S * p1;
    f.F2_N += S * p2;
    f.M3_Nm += S * (patch_.x1(e) * p2 - patch_.x2(e) * p1);
  }
  return f;
}

NewtonMatrix::NewtonMatrix(RollingSystem& system)
    : system_(system), A_(system.count()), B_(system.count()), Rx_(2 * system.count()) {}

void NewtonMatrix::apply(const double* x, double* y) {
  const std::size_t n = system_.count();
  system_.apply_R(x, Rx_.data());
  for (std::size_t e = 0; e < n; ++e) {
    const Block2& a = A_[e];
    const Block2& b = B_[e];
    const double r1 = Rx_[e], r2 = Rx_[n + e], x1 = x[e], x2 = x[n + e];
    y[e] = a[0] * r1 + a[1] * r2 + b[0] * x1 + b[1] * x2;
    y[n + e] = a[2] * r1 + a[3] * r2 + b[2] * x1 + b[3] * x2;
  }
}

void NewtonMatrix::precondition(const double* r, double* z) const {
  // Row e of A R_local + B: A_e Lambda (z_{e+1} - z_e) + B_e z_e = r_e, Lambda = diag(l1, l2).
  const std::size_t n = system_.count();
  const double l1 = system_.lambda1(), l2 = system_.lambda2();
  for (std::size_t e = n; e-- > 0;) {
    const Block2& a = A_[e];
    const Block2& b = B_[e];
    double v1 = r[e], v2 = r[n + e];
    if (system_.ahead_in_contact(e)) {
      const double q1 = l1 * z[e + 1], q2 = l2 * z[n + e + 1];
      v1 -= a[0] * q1 + a[1] * q2;
      v2 -= a[2] * q1 + a[3] * q2;
    }
    // M = B - A Lambda
    const double m11 = b[0] - a[0] * l1, m12 = b[1] - a[1] * l2;
    const double m21 = b[2] - a[2] * l1, m22 = b[3] - a[3] * l2;
    const double det = m11 * m22 - m12 * m21;
    z[e] = (m22 * v1 - m12 * v2) / det;
    z[n + e] = (m11 * v2 - m21 * v1) / det;
  }
}

NewtonStepReport solve_newton_step(NewtonMatrix& J, const std::vector<double>& rhs, std::vector<double>& dx,
                                   double tolerance, int max_iterations) {
  const auto size = static_cast<Eigen::Index>(rhs.size());
  const MatrixFreeOperator M(size, [&J](const double* x, double* y) { J.apply(x, y); });
  const ApplyFunction P = [&J](const double* r, double* z) { J.precondition(r, z); };
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(rhs.data(), size);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(size);
  KrylovOptions options;
  options.tolerance = tolerance;
  options.max_iterations = max_iterations;
  const KrylovReport report = solve_krylov(M, P, b, x, options);
  dx.assign(x.data(), x.data() + size);
  return {report.iterations, report.converged};
}

}  // namespace railcontact

#include <fmt/format.h>

#include "railcontact/error.hpp"

namespace railcontact {

void validate(const RollingOptions& o) {
  require(std::isfinite(o.collocation_offset) && o.collocation_offset >= kMinimumCollocationOffset &&
              o.collocation_offset <= 1.0,
          [&] {
            return fmt::format("rolling solver: the collocation offset alpha = {:g} must lie in [{:g}, 1] (closer to -1 "
                               "the steady-rolling operator is too ill-conditioned for the Krylov solver)",
                               o.collocation_offset, kMinimumCollocationOffset);
          });
  require(std::isfinite(o.tolerance) && o.tolerance > 0.0 && o.tolerance <= kMaximumRollingTolerance, [&] {
    return fmt::format("rolling solver: tolerance = {:g} must lie in (0, {:g}] (relative to mu max p3)", o.tolerance,
                       kMaximumRollingTolerance);
  });
  require(std::isfinite(o.krylov_tolerance) && o.krylov_tolerance > 0.0 && o.krylov_tolerance <= 0.5, [&] {
    return fmt::format("rolling solver: krylov_tolerance = {:g} must lie in (0, 0.5]", o.krylov_tolerance);
  });
  require(o.max_newton_iterations > 0, [&] {
    return fmt::format("rolling solver: max_newton_iterations = {} must be positive", o.max_newton_iterations);
  });
  require(o.max_krylov_iterations > 0, [&] {
    return fmt::format("rolling solver: max_krylov_iterations = {} must be positive", o.max_krylov_iterations);
  });
  require(std::isfinite(o.regularisation) && o.regularisation >= kMinimumRegularisation &&
              o.regularisation <= kMaximumRegularisation,
          [&] {
            return fmt::format("rolling solver: regularisation = {:g} must lie in [{:g}, {:g}] (a slip per unit rolling "
                               "speed; the paper uses 1e-08)",
                               o.regularisation, kMinimumRegularisation, kMaximumRegularisation);
          });
}

void validate_rolling_input(const ContactPatch& patch, const Creepage& c, double mu, const RollingOptions& o) {
  require(patch.elements().count() > 0, "rolling solver: the patch has no element in contact");
  require(std::isfinite(mu) && mu > 0,
          [&] { return fmt::format("rolling solver: the friction coefficient mu = {:g} must be positive and finite", mu); });
  require(std::isfinite(c.xi) && std::isfinite(c.eta) && std::isfinite(c.phi), [&] {
    return fmt::format("rolling solver: the creepages xi = {:g}, eta = {:g}, phi = {:g} 1/m must be finite", c.xi,
                       c.eta, c.phi);
  });
  validate(o);
}

void validate_rolling_input(const ContactPatch& patch, const StripCreepages& creepages, double mu,
                            const RollingOptions& o) {
  require(creepages.size() == static_cast<std::size_t>(patch.mesh().n2), [&] {
    return fmt::format("rolling solver: {} strip creepages for a patch of {} strips (mesh columns)", creepages.size(),
                       patch.mesh().n2);
  });
  for (const Creepage& c : creepages) validate_rolling_input(patch, c, mu, o);
  if (creepages.empty()) validate_rolling_input(patch, Creepage{}, mu, o);
}

void require_finite_rolling_result(const char* solver, const RollingSolution& s) {
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (std::isfinite(s.forces.F1_N) && std::isfinite(s.forces.F2_N) && std::isfinite(s.forces.M3_Nm) &&
      std::isfinite(s.residual) && finite(s.p1_Pa) && finite(s.p2_Pa) && finite(s.s1) && finite(s.s2))
    return;
  throw Error(ErrorKind::internal,
              fmt::format("{} rolling solver: a converged solution holds non-finite numbers (F1 = {:g}, F2 = {:g}, M3 = "
                          "{:g}, residual {:g}); not returned (a bug: please report it)",
                          solver, s.forces.F1_N, s.forces.F2_N, s.forces.M3_Nm, s.residual));
}

void fill_rolling_solution(const RollingSystem& system, const std::vector<double>& p, const std::vector<double>& s,
                           const std::vector<std::uint8_t>& slip, RollingSolution& solution) {
  const std::size_t n = system.count();
  solution.p1_Pa.assign(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(n));
  solution.p2_Pa.assign(p.begin() + static_cast<std::ptrdiff_t>(n), p.end());
  solution.s1.assign(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(n));
  solution.s2.assign(s.begin() + static_cast<std::ptrdiff_t>(n), s.end());
  solution.slip = slip;
  std::size_t sticking = 0;
  for (std::uint8_t flag : slip) sticking += flag == 0 ? 1 : 0;
  solution.adhesion_fraction = n > 0 ? static_cast<double>(sticking) / static_cast<double>(n) : 0.0;
  solution.forces = system.forces(p);
}

}  // namespace railcontact
