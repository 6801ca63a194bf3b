// Choice of the potential contact area of a wheel–rail contact (docs/GEOMETRY.md §6): a regular
// mesh around the region where the undeformed distance h is below margin × approach, with a
// border of a few elements, grown until that region no longer reaches into the border.
//
// Since the wheel only rises away from x1 = 0 (h(x1, x2) >= h(0, x2)), the lateral extent of the
// region is that of {x2 : h(0, x2) < level}; it is found by a scan over the whole reach of the
// profiles, so a second interpenetration region (near a two-point contact) is included too.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "geometry/tangent_section.hpp"
#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

namespace {

// Point between `inside` (h < level) and `outside` (h >= level) where h crosses level.
double crossing(const std::function<double(double)>& h, double level, double inside, double outside) {
  for (int k = 0; k < 50 && std::abs(outside - inside) > 1e-9; ++k) {
    const double mid = 0.5 * (inside + outside);
    (h(mid) < level ? inside : outside) = mid;
  }
  return 0.5 * (inside + outside);
}

// Distance along +x1 (h even in x1) at which h(x1, 0) reaches level.
double x1_reach(const std::function<double(double)>& h, double level, double first_step) {
  double inside = 0.0, outside = first_step, step = first_step;
  while (h(outside) < level) {
    inside = outside;
    step *= 1.5;
    outside += step;
    require(outside < 0.2, [&] {
      return fmt::format("potential contact area: h stays below {:.3g} mm along X1 over more than 200 mm", level * 1e3);
    });
  }
  return crossing(h, level, inside, outside);
}

struct Interval {
  double lo, hi;
};

// "1.5 GiB", "37 MiB": a number of bytes for a message.
std::string bytes_text(double bytes) {
  if (bytes >= 0.95 * 1024.0 * 1024.0 * 1024.0) return fmt::format("{:.3g} GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return fmt::format("{:.3g} MiB", bytes / (1024.0 * 1024.0));
}

// Refuses a mesh of n1 x n2 elements (counted in double: no int overflow) beyond
// kMaximumPotentialAreaElements, with the memory it would need, before anything is allocated.
void check_area_size(double n1, double n2, double dx1_m, double dx2_m) {
  const double elements = n1 * n2;
  if (elements <= kMaximumPotentialAreaElements) return;
  throw Error(fmt::format(
      "{} {:.0f} x {:.0f} = {:.3g} elements of {:.3g} x {:.3g} mm would need about {} for the normal solve (about {:g} "
      "bytes per element); at most {:.3g} elements ({}) are allowed: use larger elements (fewer elements in contact)",
      kPotentialAreaTooLarge, n1, n2, elements, dx1_m * 1e3, dx2_m * 1e3,
      bytes_text(elements * kNormalSolveBytesPerElement), kNormalSolveBytesPerElement, kMaximumPotentialAreaElements,
      bytes_text(kMaximumPotentialAreaElements * kNormalSolveBytesPerElement)));
}

// The options' ranges and a positive approach (Error naming the option otherwise).
void check_potential_area_input(double approach_m, const PotentialAreaOptions& options) {
  require(std::isfinite(approach_m) && approach_m > 0.0, "potential contact area: the approach must be positive");
  require(std::isfinite(options.margin_factor) && options.margin_factor >= 1.0,
          "potential contact area: the margin factor must be at least 1");
  require(options.elements_across >= 2, "potential contact area: at least 2 elements across are needed");
  require(options.border_elements >= 1, "potential contact area: the border must be at least 1 element");
  require(options.max_growth_steps >= 0, "potential contact area: max_growth_steps must be non-negative");
  require(std::isfinite(options.dx1_m) && std::isfinite(options.dx2_m) && options.dx1_m >= 0.0 && options.dx2_m >= 0.0,
          "potential contact area: element sizes must be non-negative");

}

// Along x2 through the contact point: the interpenetration region h(0, x2) < approach (it sets the
// element width) and the margin region h(0, x2) < level (every x2 of it is covered), from a scan of
// h over the reach of the profiles at 0.05 mm and root finds at their ends.
struct LateralExtent {
  Interval patch, margin;
};
LateralExtent lateral_extent(const geometry::TangentPlaneSection& section, double approach_m, double level) {
  const std::function<double(double)> h_x2 = [&](double x2) { return section.undeformed_distance_m(0.0, x2); };
  // Lateral scan of h(0, x2) over the reach of the profiles.
  const double reach_lo = section.x2_min_m(), reach_hi = section.x2_max_m();
  require(reach_lo < 0.0 && reach_hi > 0.0, "potential contact area: the contact point lies at the edge of a profile");
  const int n_lo = static_cast<int>(std::ceil(-reach_lo / 0.05e-3));
  const int n_hi = static_cast<int>(std::ceil(reach_hi / 0.05e-3));
  const double step_lo = -reach_lo / n_lo * (1.0 - 1e-9), step_hi = reach_hi / n_hi * (1.0 - 1e-9);
  std::vector<double> xs, hs;
  for (int k = -n_lo; k <= n_hi; ++k) {
    xs.push_back(k < 0 ? k * step_lo : k * step_hi);
    hs.push_back(h_x2(xs.back()));
  }
  const auto k0 = static_cast<std::size_t>(n_lo);  // x2 = 0
  // The interpenetration region around the contact (h < approach) sets the element width ...
  std::size_t a = k0, b = k0;
  while (a > 0 && hs[a - 1] < approach_m) --a;
  while (b + 1 < xs.size() && hs[b + 1] < approach_m) ++b;
  require(a > 0 && b + 1 < xs.size(),
          "potential contact area: the interpenetration region reaches beyond the profiles; reduce the approach");
  const Interval patch{crossing(h_x2, approach_m, xs[a], xs[a - 1]), crossing(h_x2, approach_m, xs[b], xs[b + 1])};
  // ... and every x2 with h(0, x2) < level is covered.
  std::size_t first = k0, last = k0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    if (hs[k] < level) {
      first = std::min(first, k);
      last = std::max(last, k);
    }
  }
  require(first > 0 && last + 1 < xs.size(), [&] {
    return fmt::format(
        "potential contact area: the region h < {:.3g} mm reaches beyond the profiles; reduce the approach",
        level * 1e3);
  });
  const Interval margin2{crossing(h_x2, level, xs[first], xs[first - 1]), crossing(h_x2, level, xs[last], xs[last + 1])};
  return {patch, margin2};

}

// A potential area's mesh as it grows: n1_lo elements below x1 = 0 and n1_hi above, n2_lo and n2_hi
// on either side of x2_centre.
struct GrowingMesh {
  double dx1 = 0.0, dx2 = 0.0, x2_centre = 0.0;
  int n1_lo = 0, n1_hi = 0, n2_lo = 0, n2_hi = 0;
  [[nodiscard]] Mesh mesh() const {
    check_area_size(static_cast<double>(n1_lo) + n1_hi, static_cast<double>(n2_lo) + n2_hi, dx1, dx2);
    Mesh m;
    m.n1 = n1_lo + n1_hi;
    m.n2 = n2_lo + n2_hi;
    m.dx1_m = dx1;
    m.dx2_m = dx2;
    m.x1_first_m = -(n1_lo - 0.5) * dx1;
    m.x2_first_m = x2_centre - (n2_lo - 0.5) * dx2;
    validate(m);
    return m;
  }
};

// The mesh grown on each side where the margin region h < level reaches the border ring, until it
// does not (at most options.max_growth_steps times): the potential area and h on it.
PotentialContactArea area_holding_the_margin(const WheelRailPair& pair, const WheelRailContactPoint& contact,
                                             double level, GrowingMesh grown, const PotentialAreaOptions& options) {
  const int border = options.border_elements;
  for (int step = 0;; ++step) {
    const Mesh mesh = grown.mesh();
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
      return PotentialContactArea{mesh, std::move(h), step};
    }
    require(step < options.max_growth_steps, [&] {
      return fmt::format(
          "potential contact area: the region h < {:.3g} mm still reaches the border after {} "
          "enlargements ({} x {} elements)",
          level * 1e3, step, mesh.n1, mesh.n2);
    });
    const int grow1 = std::max(border, mesh.n1 / 4);
    const int grow2 = std::max(border, mesh.n2 / 4);
    if (low1) grown.n1_lo += grow1;
    if (high1) grown.n1_hi += grow1;
    if (low2) grown.n2_lo += grow2;
    if (high2) grown.n2_hi += grow2;
  }
}

}  // namespace

PotentialContactArea potential_contact_area(const WheelRailPair& pair, const WheelRailContactPoint& contact,
                                            double approach_m, const PotentialAreaOptions& options) {
  check_potential_area_input(approach_m, options);
  const geometry::TangentPlaneSection section(pair, contact);
  const double level = options.margin_factor * approach_m;
  const std::function<double(double)> h_x1 = [&](double x1) { return section.undeformed_distance_m(x1, 0.0); };
  const LateralExtent lateral = lateral_extent(section, approach_m, level);
  const Interval& patch = lateral.patch;
  const Interval& margin2 = lateral.margin;
  const double first_step1 = 0.1 * std::sqrt(approach_m / std::max(contact.A_per_m, 1e-6));
  const double a1 = x1_reach(h_x1, approach_m, first_step1);
  const double m1 = x1_reach(h_x1, level, first_step1);
  const double dx1 = options.dx1_m > 0.0 ? options.dx1_m : 2.0 * a1 / options.elements_across;
  const double dx2 = options.dx2_m > 0.0 ? options.dx2_m : (patch.hi - patch.lo) / options.elements_across;

  require(std::isfinite(dx1) && std::isfinite(dx2) && dx1 > 0.0 && dx2 > 0.0, [&] {
    return fmt::format("potential contact area: the element sizes must be positive and finite (got {} x {} m)", dx1, dx2);
  });
  const int border = options.border_elements;
  const double x2_centre = 0.5 * (margin2.lo + margin2.hi);
  // The counts in double first: tiny elements must be refused, not overflow an int.
  const double n1_half = std::ceil(m1 / dx1) + border;
  const double n2_low = std::ceil((x2_centre - margin2.lo) / dx2) + border;
  const double n2_high = std::ceil((margin2.hi - x2_centre) / dx2) + border;
  check_area_size(2.0 * n1_half, n2_low + n2_high, dx1, dx2);
  const GrowingMesh start{dx1,
                          dx2,
                          x2_centre,
                          static_cast<int>(n1_half),
                          static_cast<int>(n1_half),
                          static_cast<int>(n2_low),
                          static_cast<int>(n2_high)};
  return area_holding_the_margin(pair, contact, level, start, options);
}

}  // namespace railcontact
