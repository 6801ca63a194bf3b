// Choice of the potential contact area of a wheel–rail contact (docs/GEOMETRY.md §6): a regular
// mesh around the region where the undeformed distance h is below margin × approach, with a
// border of a few elements, grown until that region no longer reaches into the border.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {

namespace {

// Distance from 0 along direction `sign` (±1) of the first point where h(t) reaches `level`,
// for h(0) < level: stepping outwards, then bisection. max_distance bounds the search.
double reach(const std::function<double(double)>& h, double level, double sign, double first_step, double max_distance) {
  double inside = 0.0;
  double step = first_step;
  double outside = step;
  while (h(sign * outside) < level) {
    inside = outside;
    step *= 1.5;
    outside += step;
    require(outside < max_distance,
            fmt::format("potential contact area: h stays below {:.3g} mm over more than {:.1f} mm", level * 1e3,
                        max_distance * 1e3));
  }
  for (int k = 0; k < 60 && outside - inside > 1e-4 * first_step; ++k) {
    const double mid = 0.5 * (inside + outside);
    if (h(sign * mid) < level) {
      inside = mid;
    } else {
      outside = mid;
    }
  }
  return 0.5 * (inside + outside);
}

}  // namespace

PotentialContactArea potential_contact_area(const WheelRailPair& pair, const WheelRailContactPoint& contact,
                                            double approach_m, const PotentialAreaOptions& options) {
  require(std::isfinite(approach_m) && approach_m > 0.0, "potential contact area: the approach must be positive");
  require(std::isfinite(options.margin_factor) && options.margin_factor >= 1.0,
          "potential contact area: the margin factor must be at least 1");
  require(options.elements_across >= 2, "potential contact area: at least 2 elements across are needed");
  require(options.border_elements >= 1, "potential contact area: the border must be at least 1 element");
  require(options.max_growth_steps >= 0, "potential contact area: max_growth_steps must be non-negative");
  require(std::isfinite(options.dx1_m) && std::isfinite(options.dx2_m) && options.dx1_m >= 0.0 && options.dx2_m >= 0.0,
          "potential contact area: element sizes must be non-negative");

  const double level = options.margin_factor * approach_m;
  const auto h_x1 = [&](double x1) { return pair.undeformed_distance(contact, x1, 0.0); };
  const auto h_x2 = [&](double x2) { return pair.undeformed_distance(contact, 0.0, x2); };
  // First steps from the quadratic form h ≈ A x1² + B x2².
  const double step1 = 0.1 * std::sqrt(approach_m / std::max(contact.A_per_m, 1e-6));
  const double step2 = 0.1 * std::sqrt(approach_m / std::max(std::abs(contact.B_per_m), 1e-2));
  const double max_distance = 0.2;

  // Interpenetration region (h < approach) for the element sizes.
  const double a1 = reach(h_x1, approach_m, 1.0, step1, max_distance);
  const double b2 = reach(h_x2, approach_m, 1.0, step2, max_distance) + reach(h_x2, approach_m, -1.0, step2, max_distance);
  const double dx1 = options.dx1_m > 0.0 ? options.dx1_m : 2.0 * a1 / options.elements_across;
  const double dx2 = options.dx2_m > 0.0 ? options.dx2_m : b2 / options.elements_across;

  // Margin region, plus the border.
  const int border = options.border_elements;
  const double m1 = reach(h_x1, level, 1.0, step1, max_distance);
  const double m2_hi = reach(h_x2, level, 1.0, step2, max_distance);
  const double m2_lo = -reach(h_x2, level, -1.0, step2, max_distance);
  int n1_lo = static_cast<int>(std::ceil(m1 / dx1)) + border;  // elements on each side of x1 = 0
  int n1_hi = n1_lo;
  const double x2_centre = 0.5 * (m2_lo + m2_hi);
  int n2_lo = static_cast<int>(std::ceil((x2_centre - m2_lo) / dx2)) + border;
  int n2_hi = static_cast<int>(std::ceil((m2_hi - x2_centre) / dx2)) + border;

  PotentialContactArea area;
  for (int step = 0;; ++step) {
    Mesh mesh;
    mesh.n1 = n1_lo + n1_hi;
    mesh.n2 = n2_lo + n2_hi;
    mesh.dx1_m = dx1;
    mesh.dx2_m = dx2;
    mesh.x1_first_m = -(n1_lo - 0.5) * dx1;
    mesh.x2_first_m = x2_centre - (n2_lo - 0.5) * dx2;
    validate(mesh);
    std::vector<double> h = pair.undeformed_distance(contact, mesh);

    // Does the margin region reach into the border ring? Then grow that side.
    bool low1 = false, high1 = false, low2 = false, high2 = false;
    for (int i2 = 0; i2 < mesh.n2; ++i2) {
      for (int i1 = 0; i1 < mesh.n1; ++i1) {
        if (!(h[mesh.index(i1, i2)] < level)) continue;
        low1 = low1 || i1 < border;
        high1 = high1 || i1 >= mesh.n1 - border;
        low2 = low2 || i2 < border;
        high2 = high2 || i2 >= mesh.n2 - border;
      }
    }
    if (!(low1 || high1 || low2 || high2)) {
      area.mesh = mesh;
      area.h_m = std::move(h);
      area.growth_steps = step;
      return area;
    }
    require(step < options.max_growth_steps,
            fmt::format("potential contact area: the region h < {:.3g} mm still reaches the border after {} enlargements "
                        "({} x {} elements)",
                        level * 1e3, step, mesh.n1, mesh.n2));
    const int grow1 = std::max(border, mesh.n1 / 4);
    const int grow2 = std::max(border, mesh.n2 / 4);
    if (low1) n1_lo += grow1;
    if (high1) n1_hi += grow1;
    if (low2) n2_lo += grow2;
    if (high2) n2_hi += grow2;
  }
}

}  // namespace railcontact
