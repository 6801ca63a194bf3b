// The undeformed distance of a wheelset contact on a mesh in its tangent plane, and the potential
// contact area around the overlap (docs/WHEELSET.md §4).
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "geometry/wheelset_frames.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheelset_geometry.hpp"

namespace railcontact {

namespace {


// Starting guesses for the rail and wheel parameters on the normal line through x2: the reference
// point's parameters moved by x2 along the profiles (X2 runs towards −y_p on the right side and
// +y_p on the left, the profiles' parameters grow with y_p).
struct Guesses {
  double rail_parameter, wheel_parameter;
};
Guesses guesses(const geometry::WheelOnRail& w, const InterpenetrationRegion& region, double x2_m) {
  const double along = w.sign() * x2_m;
  return {w.rail().parameter_at(region.rail_profile_y_m) + along,
          w.wheel().parameter_at(region.wheel_profile_y_m) + along};
}

}  // namespace

double WheelsetTrack::undeformed_distance_m(const WheelsetPosition& position, const InterpenetrationRegion& region,
                                            double x1_m, double x2_m) const {
  validate(position);
  require(std::isfinite(x1_m) && std::isfinite(x2_m), "undeformed distance: x1 and x2 must be finite");
  const geometry::WheelOnRail w(*this, region.side, position);
  Guesses g = guesses(w, region, x2_m);
  const double rail = w.rail_normal_m(region, x2_m, g.rail_parameter);
  double t = rail;
  return w.wheel_normal_m(region, x1_m, x2_m, t, g.wheel_parameter) - rail;
}

std::vector<double> WheelsetTrack::undeformed_distance_m(const WheelsetPosition& position,
                                                         const InterpenetrationRegion& region,
                                                         const Mesh& mesh) const {
  validate(position);
  validate(mesh);
  std::vector<double> strip_x2(static_cast<std::size_t>(mesh.n2));
  for (int i2 = 0; i2 < mesh.n2; ++i2) strip_x2[static_cast<std::size_t>(i2)] = mesh.x2(i2);
  std::vector<double> h(mesh.size());
  geometry::undeformed_distance_on_strips(geometry::WheelOnRail(*this, region.side, position), region, mesh, strip_x2, h);
  return h;
}

namespace geometry {

namespace {

// Extrapolated from the last known points of a strip's march (newest first) to x: the parabola
// through three, the line through two, the value of one.
struct MarchHistory {
  std::array<double, 3> x{}, t{}, u{};
  int known = 0;
  void add(double xi, double ti, double ui) {
    x = {xi, x[0], x[1]};
    t = {ti, t[0], t[1]};
    u = {ui, u[0], u[1]};
    known = std::min(known + 1, 3);
  }
  void extrapolate(double xi, double& t_out, double& u_out) const {
    t_out = 0.0;
    u_out = 0.0;
    for (int j = 0; j < known; ++j) {
      double weight = 1.0;
      for (int m = 0; m < known; ++m)
        if (m != j)
          weight *= (xi - x[static_cast<std::size_t>(m)]) / (x[static_cast<std::size_t>(j)] - x[static_cast<std::size_t>(m)]);
      t_out += weight * t[static_cast<std::size_t>(j)];
      u_out += weight * u[static_cast<std::size_t>(j)];
    }
  }
};

}  // namespace

int round_up_to_granule(int n) {
  int granule = 1;
  while (granule * 16 <= n) granule *= 2;
  return (n + granule - 1) / granule * granule;
}

StripRoots strip_roots(const Mesh& mesh) {
  // The exact root at every `stride`-th element (spacing at most kRootSpacing_m) and at both ends;
  // the elements between, from the quintic through the six nearest roots, agree with the exact
  // distance to 2e-13 m on the tread and 6.2e-11 m on a yawed flange (γ = 1.22 rad; the strip
  // crosses the profile spline's knots), six orders below the overlap of a loaded wheel
  // (WheelsetGeometry.TheUndeformedDistanceIsTheExactOneOnEveryElement). Half as many roots as the
  // cubic through four roots 1 mm apart (1.3e-12 and 1.7e-11 m; 2 mm apart: 2.2e-10 m).
  constexpr double kRootSpacing_m = 2e-3;
  constexpr int kPoints = StripRoots::Interpolated::kPoints;
  const int stride = std::max(1, static_cast<int>(std::floor(kRootSpacing_m / mesh.dx1_m + 1e-9)));
  StripRoots plan;
  plan.middle = std::clamp(static_cast<int>(std::lround(-mesh.x1_first_m / mesh.dx1_m)), 0, mesh.n1 - 1);
  for (std::size_t d = 0; d < 2; ++d) {
    const int direction = d == 0 ? +1 : -1;
    std::vector<int>& m = plan.march[d];
    for (int i1 = plan.middle + direction * stride; i1 >= 0 && i1 < mesh.n1; i1 += direction * stride) m.push_back(i1);
    if (const int end = direction > 0 ? mesh.n1 - 1 : 0; end != plan.middle && (m.empty() || m.back() != end))
      m.push_back(end);
  }
  std::vector<int> roots{plan.middle};
  for (const std::vector<int>& m : plan.march) roots.insert(roots.end(), m.begin(), m.end());
  std::sort(roots.begin(), roots.end());
  // Between roots k and k + 1: the polynomial through the kPoints nearest roots, as many on each
  // side as the strip has (fewer where the strip has fewer roots).
  const auto count = static_cast<int>(roots.size());
  for (int k = 0; k + 1 < count; ++k) {
    const int a = std::max(0, std::min(k - (kPoints / 2 - 1), count - kPoints));
    const int b = std::min(count, a + kPoints);
    for (int i1 = roots[static_cast<std::size_t>(k)] + 1; i1 < roots[static_cast<std::size_t>(k + 1)]; ++i1) {
      StripRoots::Interpolated e;
      e.i1 = i1;
      e.root.fill(roots[static_cast<std::size_t>(b - 1)]);
      for (int j = a; j < b; ++j) {
        const int rj = roots[static_cast<std::size_t>(j)];
        double weight = 1.0;
        for (int m = a; m < b; ++m) {
          const int rm = roots[static_cast<std::size_t>(m)];
          if (m != j) weight *= static_cast<double>(i1 - rm) / static_cast<double>(rj - rm);
        }
        e.root[static_cast<std::size_t>(j - a)] = rj;
        e.weight[static_cast<std::size_t>(j - a)] = weight;
      }
      plan.interpolation.push_back(e);
    }
  }
  return plan;
}

void undeformed_distance_on_strips(const WheelOnRail& w, const InterpenetrationRegion& region, const Mesh& mesh,
                                   const std::vector<double>& strip_x2_m, std::vector<double>& h,
                                   const StripRoots* roots) {
  // Strip by strip; the rail (straight along x) is met at the same t for every x1 of a strip, and
  // each wheel root starts from its neighbours'. The middle of the strip first, then outwards.
  std::optional<StripRoots> made;
  if (roots == nullptr) roots = &made.emplace(strip_roots(mesh));
  const int middle = roots->middle;
  // The strips in the order of the right wheel's x2 (the left wheel's mesh is its mirror image), so
  // that each strip starts from the same neighbour on both wheels.
  const bool right = region.side == WheelSide::right;
  std::optional<Guesses> g;
  // The roots (t, u) of the last two strips solved, at the root columns. From the third strip of a
  // run of strips on, each root starts from their linear extrapolation in x2: the middle root from
  // their middle roots, the others from their shapes along x1 (a root's offset from its strip's
  // middle root, which changes slowly from strip to strip) added to this strip's middle root.
  // Newton's first step then ends most roots, where the march's extrapolation along the strip
  // alone left a second step to many (the counts: docs/WHEELSET.md §8).
  struct StripSolution {
    double x2_m = 0.0;
    std::vector<double> t, u;  // by column i1 (the root columns only)
  };
  StripSolution older, last, now;
  for (StripSolution* k : {&older, &last, &now}) {
    k->t.assign(static_cast<std::size_t>(mesh.n1), 0.0);
    k->u.assign(static_cast<std::size_t>(mesh.n1), 0.0);
  }
  int known_strips = 0;  // consecutive strips solved before this one, up to 2
  for (int k2 = 0; k2 < mesh.n2; ++k2) {
    const int i2 = right ? k2 : mesh.n2 - 1 - k2;
    const double x2 = strip_x2_m[static_cast<std::size_t>(i2)];
    if (std::isnan(x2)) {
      known_strips = 0;
      continue;
    }
    if (!g) g = guesses(w, region, x2);
    const double rail = w.rail_normal_m(region, x2, g->rail_parameter);
    double* strip = h.data() + mesh.index(0, i2);  // i1 runs fastest: the strip is contiguous
    now.x2_m = x2;
    const auto solve = [&](int i1, double t, double u) {
      strip[i1] = w.wheel_normal_m(region, mesh.x1(i1), x2, t, u) - rail;
      now.t[static_cast<std::size_t>(i1)] = t;
      now.u[static_cast<std::size_t>(i1)] = u;
    };
    const double r = known_strips == 2 ? (x2 - last.x2_m) / (last.x2_m - older.x2_m) : 0.0;
    if (known_strips == 2 && std::isfinite(r)) {
      // The middle root from the strips' values there; the others from the strips' shapes (each
      // root's offset from its strip's middle), added to this strip's middle.
      const auto m0 = static_cast<std::size_t>(middle);
      const auto extrapolated = [r](double at_last, double at_older) { return at_last + r * (at_last - at_older); };
      solve(middle, extrapolated(last.t[m0], older.t[m0]), extrapolated(last.u[m0], older.u[m0]));
      for (const std::vector<int>& m : roots->march)
        for (const int i1 : m) {
          const auto k = static_cast<std::size_t>(i1);
          solve(i1, now.t[m0] + extrapolated(last.t[k] - last.t[m0], older.t[k] - older.t[m0]),
                now.u[m0] + extrapolated(last.u[k] - last.u[m0], older.u[k] - older.u[m0]));
        }
    } else {
      // The middle of the strip from the last strip's profile parameter, then outwards: each root
      // from the parabola through the three before it (in x1; third-order accurate).
      solve(middle, rail, g->wheel_parameter);
      for (const std::vector<int>& m : roots->march) {
        MarchHistory history;
        history.add(mesh.x1(middle), now.t[static_cast<std::size_t>(middle)], now.u[static_cast<std::size_t>(middle)]);
        for (const int i1 : m) {
          const double x1 = mesh.x1(i1);
          double t = 0.0, u = 0.0;
          history.extrapolate(x1, t, u);
          solve(i1, t, u);
          history.add(x1, now.t[static_cast<std::size_t>(i1)], now.u[static_cast<std::size_t>(i1)]);
        }
      }
    }
    g->wheel_parameter = now.u[static_cast<std::size_t>(middle)];
    std::swap(older, last);
    std::swap(last, now);
    known_strips = std::min(known_strips + 1, 2);
    for (const StripRoots::Interpolated& e : roots->interpolation) {
      double value = 0.0;
      for (std::size_t j = 0; j < e.root.size(); ++j) value += e.weight[j] * strip[e.root[j]];
      strip[e.i1] = value;
    }
  }
}

}  // namespace geometry

namespace {

// Overlap on normal lines that meet the rail outside the region's own stretch of the rail profile
// belongs to a neighbouring region: those strips are made a gap (1 m, far beyond any approach).
void keep_own_overlap(const geometry::WheelOnRail& w, const InterpenetrationRegion& region, const Mesh& mesh,
                      std::vector<double>& h) {
  if (std::isinf(region.rail_profile_y_lower_bound_m) && std::isinf(region.rail_profile_y_upper_bound_m)) return;
  constexpr double kNotOwned_m = 1.0;
  Guesses g = guesses(w, region, mesh.x2(0));
  for (int i2 = 0; i2 < mesh.n2; ++i2) {
    (void)w.rail_normal_m(region, mesh.x2(i2), g.rail_parameter);
    const double rail_y = w.rail().at(g.rail_parameter).y_m;
    if (rail_y >= region.rail_profile_y_lower_bound_m && rail_y <= region.rail_profile_y_upper_bound_m) continue;
    for (int i1 = 0; i1 < mesh.n1; ++i1) h[mesh.index(i1, i2)] = kNotOwned_m;
  }
}

}  // namespace

TangentPlaneArea WheelsetTrack::potential_contact_area(const WheelsetPosition& position,
                                                       const InterpenetrationRegion& region, double element_size_m,
                                                       int border_elements) const {
  return potential_contact_area(position, region, element_size_m, element_size_m, border_elements);
}

TangentPlaneArea WheelsetTrack::potential_contact_area(const WheelsetPosition& position,
                                                       const InterpenetrationRegion& region, double dx1_m,
                                                       double dx2_m, int border_elements) const {
  for (double d : {dx1_m, dx2_m}) {
    require(std::isfinite(d) && d >= kMinimumTangentPlaneElement_m && d <= 0.01, [&] {
      return fmt::format("potential contact area: the element size {:g} mm must lie in [{:g}, 10] mm", d * 1e3,
                         kMinimumTangentPlaneElement_m * 1e3);
    });
  }
  require(border_elements >= 1 && border_elements <= 100,
          "potential contact area: the border must be 1 to 100 elements wide");
  const geometry::WheelOnRail w(*this, region.side, position);
  const geometry::GrowingArea growing{region, dx1_m, dx2_m, border_elements, "potential contact area",
                                      "in the tangent plane"};
  return geometry::grown_area(growing, [&](const Mesh& mesh, TangentPlaneArea& area) {
    area.h_m = undeformed_distance_m(position, region, mesh);
    keep_own_overlap(w, region, mesh, area.h_m);
  });
}

namespace geometry {

TangentPlaneArea grown_area(const GrowingArea& g, const AreaFiller& fill) {
  const InterpenetrationRegion& region = g.region;
  const int border = g.border_elements;
  // Element centres at integer multiples of the sizes from the reference point.
  int lo1 = static_cast<int>(std::floor(region.x1_min_m / g.dx1_m)) - border;
  int hi1 = static_cast<int>(std::ceil(region.x1_max_m / g.dx1_m)) + border;
  int lo2 = static_cast<int>(std::floor(region.x2_min_m / g.dx2_m)) - border;
  int hi2 = static_cast<int>(std::ceil(region.x2_max_m / g.dx2_m)) + border;
  for (int step = 0;; ++step) {
    // The mesh's size in whole granules (round_up_to_granule). The extra elements go to +x1 and to
    // the gauge side (+x2 on the right wheel, −x2 on the left one, whose X2 points the other way
    // across its rail), so the left wheel stays the mirrored right wheel.
    if (const int extra = round_up_to_granule(hi1 - lo1 + 1) - (hi1 - lo1 + 1); extra > 0) hi1 += extra;
    if (const int extra = round_up_to_granule(hi2 - lo2 + 1) - (hi2 - lo2 + 1); extra > 0)
      (region.side == WheelSide::right ? hi2 : lo2) += region.side == WheelSide::right ? extra : -extra;
    Mesh mesh;
    mesh.n1 = hi1 - lo1 + 1;
    mesh.n2 = hi2 - lo2 + 1;
    mesh.dx1_m = g.dx1_m;
    mesh.dx2_m = g.dx2_m;
    mesh.x1_first_m = lo1 * g.dx1_m;
    mesh.x2_first_m = lo2 * g.dx2_m;
    // Counted in double before anything is allocated (docs/RELIABILITY.md "Resource limits").
    const double elements = static_cast<double>(mesh.n1) * static_cast<double>(mesh.n2);
    require(elements <= kMaximumPotentialAreaElements, [&] {
      return fmt::format("{} {} x {} = {:.3g} elements of {:.3g} x {:.3g} mm {} of the {} wheel; at most {:.3g} elements "
                         "are allowed: use larger elements",
                         kPotentialAreaTooLarge, mesh.n1, mesh.n2, elements, g.dx1_m * 1e3, g.dx2_m * 1e3, g.where,
                         side_name(region.side), kMaximumPotentialAreaElements);
    });
    validate(mesh);
    TangentPlaneArea area;
    area.mesh = mesh;
    area.growth_steps = step;
    fill(mesh, area);
    // Overlap within `border` elements of each edge: the border's rows whole, the first and last
    // `border` columns of the rows between (the interior, most of a large area, is not read).
    bool low1 = false, high1 = false, low2 = false, high2 = false;
    for (int i2 = 0; i2 < mesh.n2; ++i2) {
      const auto scan = [&](int from1, int to1) {
        for (int i1 = from1; i1 < to1; ++i1) {
          if (!(area.h_m[mesh.index(i1, i2)] < 0.0)) continue;
          low1 = low1 || i1 < border;
          high1 = high1 || i1 >= mesh.n1 - border;
          low2 = low2 || i2 < border;
          high2 = high2 || i2 >= mesh.n2 - border;
        }
      };
      if (i2 < border || i2 >= mesh.n2 - border) {
        scan(0, mesh.n1);
      } else {
        scan(0, std::min(border, mesh.n1));
        scan(std::max(border, mesh.n1 - border), mesh.n1);
      }
    }
    if (!(low1 || high1 || low2 || high2)) return area;
    require(step < kMaximumGrowthSteps, [&] {
      return fmt::format("{} of the {} wheel: the overlap still reaches the border of a {} x {} mesh after {} enlargements",
                         g.what, side_name(region.side), mesh.n1, mesh.n2, step);
    });
    const int grow1 = std::max(border, mesh.n1 / 4), grow2 = std::max(border, mesh.n2 / 4);
    if (low1) lo1 -= grow1;
    if (high1) hi1 += grow1;
    if (low2) lo2 -= grow2;
    if (high2) hi2 += grow2;
  }
}

}  // namespace geometry

}  // namespace railcontact
