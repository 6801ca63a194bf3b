// Polonsky & Keer's constrained conjugate gradients (Wear 231, 1999, §3); see the header.
#include "normal/constrained_cg.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

namespace railcontact::detail {
namespace {

// The work vectors as Eigen arrays: their sums and maxima run vectorised (Eigen's reductions
// keep several partial sums; the order of the additions differs from a plain loop's only in
// rounding).
Eigen::Map<const Eigen::ArrayXd> array(std::span<const double> v) {
  return {v.data(), static_cast<Eigen::Index>(v.size())};
}
Eigen::Map<Eigen::ArrayXd> array(std::vector<double>& v) { return {v.data(), static_cast<Eigen::Index>(v.size())}; }

// The largest of zero and the values, NaN if any is NaN: a breakdown (an overflow in a degenerate
// problem) must reach the convergence test and the caller's check, not be dropped by a maximum.
template <typename Expression>
double largest_or_zero(const Expression& values) {
  const double largest = values.template maxCoeff<Eigen::PropagateNaN>();
  return std::isnan(largest) || largest > 0.0 ? largest : 0.0;
}

}  // namespace

ConstrainedConjugateGradient::ConstrainedConjugateGradient(const Mesh& mesh)
    : preconditioner_(mesh),
      u_(mesh.size()),
      r_(mesh.size()),
      z_(mesh.size()),
      t_(mesh.size()),
      q_(mesh.size()),
      contact_mask_(mesh.size()) {}

ConstrainedCgReport ConstrainedConjugateGradient::solve(InfluenceOperator& A, std::span<const double> h,
                                                        double pressure_sum, std::span<double> p, double tolerance,
                                                        int max_iterations) {
  preconditioner_.set_gamma(ContactLaplacianPreconditioner::kDefaultGamma);
  return iterate(A, h, pressure_sum, std::nullopt, p, tolerance, max_iterations);
}

ConstrainedCgReport ConstrainedConjugateGradient::solve_at_approach(InfluenceOperator& A, std::span<const double> h,
                                                                    double approach_m, std::span<double> p,
                                                                    double tolerance, int max_iterations,
                                                                    std::span<const double> product,
                                                                    double preconditioner_gamma) {
  preconditioner_.set_gamma(preconditioner_gamma);
  return iterate(A, h, 0.0, approach_m, p, tolerance, max_iterations, product);
}

ConstrainedConjugateGradient::ContactSet ConstrainedConjugateGradient::mark_contact_set(std::span<const double> p,
                                                                                        std::span<const double> h) {
  ContactSet set;
  for (std::size_t i = 0; i < p.size(); ++i) contact_mask_[i] = p[i] > 0.0 ? 1.0 : 0.0;
  set.count = static_cast<std::size_t>(array(contact_mask_).sum());  // exact: a sum of ones
  set.gap_sum = (array(contact_mask_) * (array(h) + array(u_))).sum();
  return set;
}

ConstrainedConjugateGradient::GapResidual ConstrainedConjugateGradient::gap_residual(std::span<const double> h,
                                                                                     double delta) {
  // r = h + A p - delta; the violation is |r| on Ic and -r (overlap) outside it.
  const auto mask = array(contact_mask_);
  auto r = array(r_);
  r = array(h) + array(u_) - delta;
  GapResidual gap;
  gap.u_max = largest_or_zero(array(u_));
  gap.violation = largest_or_zero((mask * r.abs()).max((1.0 - mask) * -r));
  return gap;
}

bool ConstrainedConjugateGradient::enter_overlap(InfluenceOperator& A, std::span<double> p, double entry_step) {
  bool entered = false;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (r_[i] < 0.0) {
      p[i] = -entry_step * r_[i];
      entered = true;
    }
  }
  if (entered) A.apply_on_grid(p, u_);
  return entered;
}

double ConstrainedConjugateGradient::preconditioned_residual(std::size_t contact_count, bool load_given) {
  preconditioner_.apply(contact_mask_, contact_count, r_, z_);
  auto z = array(z_);  // 0 outside Ic
  if (load_given && contact_count > 0) z -= (z.sum() / static_cast<double>(contact_count)) * array(contact_mask_);
  return (array(r_) * z).sum();  // over Ic
}

void ConstrainedConjugateGradient::conjugate_direction(double beta) {
  array(t_) = array(contact_mask_) * (array(z_) + beta * array(t_));
}

double ConstrainedConjugateGradient::step_length(InfluenceOperator& A, std::size_t contact_count, bool load_given) {
  A.apply_on_grid(t_, q_);
  const auto mask = array(contact_mask_);
  const auto t = array(t_);  // 0 outside Ic
  const auto q = array(q_);
  const double q_mean =
      load_given && contact_count > 0 ? (mask * q).sum() / static_cast<double>(contact_count) : 0.0;
  const double numerator = (array(r_) * t).sum();
  const double denominator = ((q - q_mean) * t).sum();
  return denominator > 0.0 ? numerator / denominator : 0.0;
}

ConstrainedConjugateGradient::PressureStep ConstrainedConjugateGradient::project_pressure(std::span<double> p,
                                                                                         double tau,
                                                                                         double entry_threshold,
                                                                                         double entry_step) {
  PressureStep step;
  moved_.clear();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (contact_mask_[i] != 0.0) {
      double pi = p[i] - tau * t_[i];
      if (pi <= 0.0) {
        moved_.push_back({i, -pi});
        pi = 0.0;
        step.set_changed = true;
      }
      p[i] = pi;
    } else if (r_[i] < entry_threshold) {
      p[i] = -entry_step * r_[i];
      moved_.push_back({i, p[i]});
      step.set_changed = true;
    }
    step.pressure_sum += p[i];
  }
  step.recursive = !step.set_changed || moved_.size() <= kLargestElementUpdate;
  return step;
}

double ConstrainedConjugateGradient::restore_load(std::span<double> p, double pressure_sum, PressureStep& step) const {
  if (!(step.pressure_sum > 0.0)) {
    // Cannot happen with a positive step (sum t = 0 on Ic, clamping only adds); restart from the
    // deepest point.
    const auto deepest = static_cast<std::size_t>(std::min_element(r_.begin(), r_.end()) - r_.begin());
    std::fill(p.begin(), p.end(), 0.0);
    p[deepest] = pressure_sum;
    step.pressure_sum = pressure_sum;
    step.set_changed = true;
    step.recursive = false;
  }
  const double scale = pressure_sum / step.pressure_sum;
  for (double& pi : p) pi *= scale;
  return scale;
}

bool ConstrainedConjugateGradient::update_pressure_product(InfluenceOperator& A, std::span<const double> p,
                                                           const PressureStep& step, double tau, double scale) {
  if (!step.recursive) {
    A.apply_on_grid(p, u_);
    return true;
  }
  const std::size_t n = u_.size();
  for (std::size_t i = 0; i < n; ++i) u_[i] -= tau * q_[i];
  for (const auto& [element, difference] : moved_) A.add_element_product(element, difference, u_);
  if (scale != 1.0)
    for (std::size_t i = 0; i < n; ++i) u_[i] *= scale;
  return false;
}

ConstrainedCgReport ConstrainedConjugateGradient::iterate(InfluenceOperator& A, std::span<const double> h,
                                                          double pressure_sum, std::optional<double> fixed_approach,
                                                          std::span<double> p, double tolerance, int max_iterations,
                                                          std::span<const double> product) {
  const bool load_given = !fixed_approach.has_value();
  // Pressure per unit penetration for elements entering the set: a quarter of the pressure that
  // closes the gap of one element alone, 1 / A33(0, 0). Elements enter in groups, and a group
  // closes a gap with less pressure per element; measured on Hertzian, rough, corner and
  // two-patch cases, factors 0.05 to 1 converge alike, 2 and above can make the set cycle.
  const double entry_step = 0.25 / A.kernel(0, 0, 0, 0);

  int recursive_updates = 0;  // updates of u_ = A p by recursion since its last product by FFT
  if (product.size() == u_.size()) {
    std::copy(product.begin(), product.end(), u_.begin());
    recursive_updates = 1;
  } else {
    A.apply_on_grid(p, u_);
  }
  bool set_stable = false;    // the last update left the contact set unchanged
  double G_old = 0.0;
  ConstrainedCgReport report;
  int iterations = 0;
  while (true) {
    // PK step 1: the contact set Ic and the load multiplier delta = mean over Ic of (h + A p).
    // With the approach given, delta is fixed and the contact set may be empty (no overlap).
    const ContactSet set = mark_contact_set(p, h);
    const double delta = load_given ? set.gap_sum / static_cast<double>(set.count) : *fixed_approach;
    // PK step 2: the gap residual r and the complementarity violation, relative to max(A p).
    const GapResidual gap = gap_residual(h, delta);
    report.residual = gap.u_max > 0.0 ? gap.violation / gap.u_max : (gap.violation > 0.0 ? 1.0 : 0.0);
    report.approach_m = delta;
    report.iterations = iterations;

    // Convergence check: accepted only on an unchanged set and an A p made by FFT at most
    // kLargestRecursion updates ago (and the residual at the iteration limit reported from one
    // made by FFT). The recursion is exact but for rounding, some 1e-16 of max(A p) per update,
    // eleven orders below the tolerances in use; a product by FFT to confirm it cost a sixth of a
    // wheelset time step's normal solves (docs/NORMAL.md "Convergence").
    const bool converged = set_stable && report.residual <= tolerance;
    const bool product_trusted = converged ? recursive_updates <= kLargestRecursion : recursive_updates == 0;
    if (converged || iterations >= max_iterations) {
      if (product_trusted) {
        report.converged = converged;
        break;
      }
      A.apply_on_grid(p, u_);
      recursive_updates = 0;
      continue;
    }
    ++iterations;

    if (set.count == 0) {
      // Approach given and nothing in contact: the overlap enters (or, without overlap, the
      // empty set is the solution and is accepted at the next check).
      set_stable = !enter_overlap(A, p, entry_step);
      recursive_updates = 0;
      continue;
    }

    // PK step 3: the conjugate direction from the preconditioned residual, restarted after every
    // change of the contact set.
    const double G = preconditioned_residual(set.count, load_given);
    const double beta = (set_stable && G_old > 0.0) ? G / G_old : 0.0;
    conjugate_direction(beta);
    G_old = G;
    // PK steps 4–5: q = A t and the step length tau.
    const double tau = step_length(A, set.count, load_given);
    if (!std::isfinite(G) || !std::isfinite(tau)) {
      // A breakdown (an overflow in a degenerate problem): no solution; the caller reports it.
      report.residual = std::numeric_limits<double>::quiet_NaN();
      report.converged = false;
      report.iterations = iterations;
      break;
    }
    // PK steps 6–7: the projected pressure update and the overlap entering the set. Elements
    // outside Ic enter only when their penetration exceeds half the tolerance, so that rounding
    // noise cannot keep the set changing.
    PressureStep step = project_pressure(p, tau, -0.5 * tolerance * gap.u_max, entry_step);
    // PK step 8: sum p = P. With the approach given there is no load constraint to restore (an
    // empty set is a valid state).
    const double scale = load_given ? restore_load(p, pressure_sum, step) : 1.0;
    recursive_updates = update_pressure_product(A, p, step, tau, scale) ? 0 : recursive_updates + 1;
    set_stable = !step.set_changed;
  }
  return report;
}

}  // namespace railcontact::detail
