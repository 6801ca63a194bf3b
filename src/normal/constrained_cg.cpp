// Polonsky & Keer's constrained conjugate gradients (Wear 231, 1999, §3); see the header.
#include "normal/constrained_cg.hpp"

#include <algorithm>
#include <cmath>

namespace railcontact::detail {

ConstrainedConjugateGradient::ConstrainedConjugateGradient(const Mesh& mesh)
    : preconditioner_(mesh),
      u_(mesh.size()),
      r_(mesh.size()),
      z_(mesh.size()),
      t_(mesh.size()),
      q_(mesh.size()),
      in_contact_(mesh.size()) {}

ConstrainedCgReport ConstrainedConjugateGradient::solve(InfluenceOperator& A, std::span<const double> h,
                                                        double pressure_sum, std::span<double> p, double tolerance,
                                                        int max_iterations) {
  return iterate(A, h, pressure_sum, std::nullopt, p, tolerance, max_iterations);
}

ConstrainedCgReport ConstrainedConjugateGradient::solve_at_approach(InfluenceOperator& A, std::span<const double> h,
                                                                    double approach_m, std::span<double> p,
                                                                    double tolerance, int max_iterations) {
  return iterate(A, h, 0.0, approach_m, p, tolerance, max_iterations);
}

ConstrainedCgReport ConstrainedConjugateGradient::iterate(InfluenceOperator& A, std::span<const double> h,
                                                          double pressure_sum, std::optional<double> fixed_approach,
                                                          std::span<double> p, double tolerance, int max_iterations) {
  const bool load_given = !fixed_approach.has_value();
  const std::size_t n = p.size();
  // Pressure per unit penetration for elements entering the set: a quarter of the pressure that
  // closes the gap of one element alone, 1 / A33(0, 0). Elements enter in groups, and a group
  // closes a gap with less pressure per element; measured on Hertzian, rough, corner and
  // two-patch cases, factors 0.05 to 1 converge alike, 2 and above can make the set cycle.
  const double entry_step = 0.25 / A.kernel(0, 0, 0, 0);

  A.apply_on_grid(p, u_);
  bool u_fresh = true;      // u_ = A p computed by FFT, not recursively
  bool set_stable = false;  // the last update left the contact set unchanged
  double G_old = 0.0;
  ConstrainedCgReport report;
  int iterations = 0;
  while (true) {
    // delta = mean over Ic of (h + A p): the load multiplier (PK step 1).
    std::size_t contact_count = 0;
    double contact_sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const bool in = p[i] > 0.0;
      in_contact_[i] = in ? 1 : 0;
      if (in) {
        ++contact_count;
        contact_sum += h[i] + u_[i];
      }
    }
    // With the approach given, delta is fixed and the contact set may be empty (no overlap).
    const double delta = load_given ? contact_sum / static_cast<double>(contact_count) : *fixed_approach;
    // Gap residual r = g = h - delta + A p (PK step 2) and the complementarity
    // violation: |g| where p > 0, max(0, -g) where p = 0.
    double violation = 0.0, u_max = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double r = h[i] + u_[i] - delta;
      r_[i] = r;
      u_max = std::max(u_max, u_[i]);
      if (in_contact_[i] != 0) {
        violation = std::max(violation, std::fabs(r));
      } else {
        violation = std::max(violation, -r);
      }
    }
    report.residual = u_max > 0.0 ? violation / u_max : (violation > 0.0 ? 1.0 : 0.0);
    report.approach_m = delta;
    report.iterations = iterations;
    if (set_stable && report.residual <= tolerance) {
      if (u_fresh) {
        report.converged = true;
        break;
      }
      A.apply_on_grid(p, u_);  // accept only on a freshly computed A p
      u_fresh = true;
      continue;
    }
    if (iterations >= max_iterations) {
      if (u_fresh) break;
      A.apply_on_grid(p, u_);  // report the residual of a freshly computed A p
      u_fresh = true;
      continue;
    }
    ++iterations;

    if (contact_count == 0) {
      // Approach given and nothing in contact: the overlap enters (or, without overlap, the
      // empty set is the solution and is accepted at the next check).
      bool entered = false;
      for (std::size_t i = 0; i < n; ++i) {
        if (r_[i] < 0.0) {
          p[i] = -entry_step * r_[i];
          entered = true;
        }
      }
      if (entered) A.apply_on_grid(p, u_);
      u_fresh = true;
      set_stable = !entered;
      continue;
    }

    // Preconditioned residual z = M r, projected on sum z = 0 (the load is kept by the step);
    // G = r.z > 0 as M is positive definite on Ic.
    preconditioner_.apply(in_contact_, contact_count, r_, z_);
    double z_sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) z_sum += z_[i];  // z = 0 outside Ic
    const double z_mean = load_given && contact_count > 0 ? z_sum / static_cast<double>(contact_count) : 0.0;
    double G = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (in_contact_[i] != 0) {
        z_[i] -= z_mean;
        G += r_[i] * z_[i];
      }
    }
    // Conjugate direction on Ic (PK step 3), restarted after every change of the contact set.
    const double beta = (set_stable && G_old > 0.0) ? G / G_old : 0.0;
    for (std::size_t i = 0; i < n; ++i) t_[i] = in_contact_[i] != 0 ? z_[i] + beta * t_[i] : 0.0;
    G_old = G;

    // q = A t with its mean over Ic removed (PK step 4) and the step length (PK step 5).
    A.apply_on_grid(t_, q_);
    double q_sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) q_sum += in_contact_[i] != 0 ? q_[i] : 0.0;
    const double q_mean = load_given && contact_count > 0 ? q_sum / static_cast<double>(contact_count) : 0.0;
    double numerator = 0.0, denominator = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (in_contact_[i] != 0) {
        numerator += r_[i] * t_[i];
        denominator += (q_[i] - q_mean) * t_[i];
      }
    }
    const double tau = denominator > 0.0 ? numerator / denominator : 0.0;

    // Pressure update, projection on p >= 0 (PK step 6) and overlap entering the set (step 7).
    // Elements outside Ic enter only when their penetration exceeds half the tolerance, so that
    // rounding noise cannot keep the set changing.
    // The elements whose new pressure differs from the step p − τ t (clamped to zero, or entered)
    // are kept with the difference: when they are few, A p follows from the recursion's
    // u − τ q plus their products by the kernel table, instead of a product on the whole grid.
    const double entry_threshold = -0.5 * tolerance * u_max;
    bool changed = false;
    moved_.clear();
    double p_sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (in_contact_[i] != 0) {
        double pi = p[i] - tau * t_[i];
        if (pi <= 0.0) {
          moved_.push_back({i, -pi});
          pi = 0.0;
          changed = true;
        }
        p[i] = pi;
      } else if (r_[i] < entry_threshold) {
        p[i] = -entry_step * r_[i];
        moved_.push_back({i, p[i]});
        changed = true;
      }
      p_sum += p[i];
    }
    bool recursive = !changed || moved_.size() <= kLargestElementUpdate;
    const auto follow = [&](double scale) {
      for (std::size_t i = 0; i < n; ++i) u_[i] -= tau * q_[i];
      for (const auto& [element, difference] : moved_) A.add_element_product(element, difference, u_);
      if (scale != 1.0)
        for (std::size_t i = 0; i < n; ++i) u_[i] *= scale;
      u_fresh = false;
    };
    if (!load_given) {
      // Approach given: no load constraint to restore (an empty set is a valid state).
      if (recursive) {
        follow(1.0);
      } else {
        A.apply_on_grid(p, u_);
        u_fresh = true;
      }
      set_stable = !changed;
      continue;
    }
    if (!(p_sum > 0.0)) {
      // Cannot happen with a positive step (sum t = 0 on Ic, clamping only adds); restart from the
      // deepest point.
      const auto deepest = static_cast<std::size_t>(std::min_element(r_.begin(), r_.end()) - r_.begin());
      std::fill(p.begin(), p.end(), 0.0);
      p[deepest] = pressure_sum;
      p_sum = pressure_sum;
      changed = true;
      recursive = false;
    }
    // Load (PK step 8): sum p = P.
    const double scale = pressure_sum / p_sum;
    for (std::size_t i = 0; i < n; ++i) p[i] *= scale;

    if (recursive) {
      follow(scale);
    } else {
      A.apply_on_grid(p, u_);
      u_fresh = true;
    }
    set_stable = !changed;
  }
  return report;
}

}  // namespace railcontact::detail
