// The smooth representation of a profile: a penalised least-squares cubic B-spline curve
// in chord-length parameter s, with the exact integral penalty of a smoothing spline on the
// m-th derivative (Reinsch 1967; de Boor, A Practical Guide to Splines, ch. XIV; on a uniform
// knot grid as in the P-splines of Eilers & Marx 1996). Basis functions and curve evaluation come from Eigen's
// Splines module (unsupported/Eigen/Splines); the banded normal equations are solved with
// Eigen's sparse Cholesky (SimplicialLDLT). See docs/GEOMETRY.md §5. The assembly of the penalised
// normal equations is our own: no Debian library fits this criterion (docs/DEPENDENCIES.md,
// "Numerical routines: library or our own").
//
//   minimise  sum_i w_i |C(s_i) - P_i|^2 + L^(2m) ∫ |C^(m)(s)|^2 ds,   w_i = arc length per point.
#include <fmt/core.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <cstddef>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>
#include <unsupported/Eigen/Splines>

#include "geometry/root_finding.hpp"
#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

using Curve = Eigen::Spline<double, 2, 3>;

struct SmoothProfile::Impl {
  double s_begin_m = 0.0;
  double s_end_m = 0.0;
  // The fitted curve, piecewise: on knot interval k, [k h, (k + 1) h] (the last one ends at s_end),
  // y and z and their first three derivatives at the interval's midpoint, so that evaluation is a
  // cubic polynomial (the curve is a cubic on each interval; its Taylor expansion is exact).
  // Eigen's Spline evaluates through the B-spline basis derivatives on every call, which was 27 %
  // of a wheelset time step (docs/DEPENDENCIES.md "Numerical routines: library or our own").
  struct Interval {
    double middle_m;
    std::array<double, 4> y, z;  // value, d/ds, d2/ds2, d3/ds3 at the middle
  };
  double knot_spacing_m = 0.0;
  double knots_per_m = 0.0;  // 1 / knot_spacing_m: interval_at multiplies (its rounding is corrected there)
  std::vector<Interval> intervals;
  [[nodiscard]] const Interval& interval_at(double s) const;
  [[nodiscard]] double y_at(double s) const;
  // Samples of y(s) with their running maximum, for inverting y(s) (graph form).
  std::vector<double> table_s_m;
  std::vector<double> table_y_max_m;
  // Where to search that table: bucket b of equal widths in y from table_y_max_m.front() holds
  // the first sample whose y_max reaches the bucket's lower end, the last entry the table's size
  // (parameter_at then searches a few samples instead of the whole table).
  std::vector<std::size_t> bucket_first_sample;
  double buckets_per_m = 0.0;
  std::string source;
  ProfileKind kind = ProfileKind::unknown;
};

namespace {

// A cubic and its first two derivatives at offset t from the point of its Taylor coefficients
// c = (value, first, second, third derivative).
struct CubicValue {
  double value, first, second;
};
CubicValue cubic_at(const std::array<double, 4>& c, double t) {
  return {c[0] + t * (c[1] + t * (0.5 * c[2] + t * (c[3] / 6.0))), c[1] + t * (c[2] + t * (0.5 * c[3])),
          c[2] + t * c[3]};
}

}  // namespace

const SmoothProfile::Impl::Interval& SmoothProfile::Impl::interval_at(double s) const {
  const auto last = static_cast<std::ptrdiff_t>(intervals.size()) - 1;
  auto k = std::clamp(static_cast<std::ptrdiff_t>(std::floor(s * knots_per_m)), std::ptrdiff_t{0}, last);
  // Rounding of s / h at a knot: the interval whose knots bracket s (its lower knot belongs to it).
  const auto lower_knot = [this](std::ptrdiff_t j) { return static_cast<double>(j) * knot_spacing_m; };
  if (k > 0 && s < lower_knot(k)) --k;
  if (k < last && s >= lower_knot(k + 1)) ++k;
  return intervals[static_cast<std::size_t>(k)];
}

double SmoothProfile::Impl::y_at(double s) const {
  const Interval& i = interval_at(s);
  return cubic_at(i.y, s - i.middle_m).value;
}

namespace {

constexpr int kDegree = 3;
constexpr int kMaximumKnotIntervals = 200000;

std::string name_of(const Profile& profile) {
  return profile.source.empty() ? std::string("(unnamed)") : profile.source;
}

void validate(const SmoothingOptions& options) {
  require(std::isfinite(options.smoothing_length_m) && options.smoothing_length_m >= 0.0,
          "smoothing: the smoothing length must be non-negative");
  require(std::isfinite(options.knot_spacing_m) && options.knot_spacing_m > 0.0,
          "smoothing: the knot spacing must be positive");
  require(options.penalty_derivative >= 1 && options.penalty_derivative <= kDegree,
          "smoothing: the penalised derivative must be of order 1, 2 or 3");
}

// The profile's points with their chord length s from the first.
struct ChordPoints {
  std::vector<double> y, z, s;
};

// Points ordered so that y grows along the curve; coincident points dropped.
ChordPoints chord_length_points(const Profile& profile) {
  std::vector<double> py = profile.y_m, pz = profile.z_m;
  if (py.front() > py.back()) {
    std::reverse(py.begin(), py.end());
    std::reverse(pz.begin(), pz.end());
  }
  ChordPoints points{{py.front()}, {pz.front()}, {0.0}};
  std::vector<double>& y = points.y;
  std::vector<double>& z = points.z;
  std::vector<double>& s = points.s;
  for (std::size_t i = 1; i < py.size(); ++i) {
    const double ds = std::hypot(py[i] - y.back(), pz[i] - z.back());
    if (ds <= 1e-12) continue;
    y.push_back(py[i]);
    z.push_back(pz[i]);
    s.push_back(s.back() + ds);
  }
  require(s.size() >= 4, [&] { return fmt::format("profile {}: fewer than 4 distinct points", name_of(profile)); });
  return points;
}

// Clamped uniform knot vector on [0, length]: `intervals` knot intervals h long, and
// intervals + 3 control points.
struct KnotGrid {
  int intervals = 0;
  double h = 0.0;
  Curve::KnotVectorType knots;
  [[nodiscard]] int control_points() const { return intervals + kDegree; }
};

// The number of knot intervals is computed in double and bounded before it becomes an int
// (memory grows with it: about 1 kB per interval).
KnotGrid clamped_knot_grid(const Profile& profile, double length, double knot_spacing_m) {
  const double wanted_intervals = std::ceil(length / knot_spacing_m);
  require(wanted_intervals <= kMaximumKnotIntervals, [&] {
    return fmt::format(
        "profile {}: a curve {:.4g} mm long with knots every {:.4g} mm needs {:.4g} knot intervals; at most {} "
        "(increase the knot spacing)",
        name_of(profile), length * 1e3, knot_spacing_m * 1e3, wanted_intervals, kMaximumKnotIntervals);
  });
  KnotGrid grid;
  grid.intervals = std::max(4, static_cast<int>(wanted_intervals));
  const int intervals = grid.intervals;
  grid.h = length / intervals;
  grid.knots.resize(intervals + 2 * kDegree + 1);
  for (int j = 0; j < grid.knots.size(); ++j) {
    const int b = std::clamp(j - kDegree, 0, intervals);
    grid.knots(j) = b == intervals ? length : b * grid.h;
  }
  return grid;
}

// Normal equations (B' W B + L^(2m) P) c = B' W p, with two right-hand sides (y, z): the matrix
// as entries summed on assembly.
struct NormalEquations {
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixX2d rhs;
};

// The least-squares part B' W B and B' W p, w_i = arc length per point.
void add_data_terms(const ChordPoints& points, const KnotGrid& grid, NormalEquations& equations) {
  const std::vector<double>& y = points.y;
  const std::vector<double>& z = points.z;
  const std::vector<double>& s = points.s;
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double w = 0.5 * (s[std::min(i + 1, n - 1)] - s[i == 0 ? 0 : i - 1]);
    const auto span = Curve::Span(s[i], kDegree, grid.knots);
    const auto basis = Curve::BasisFunctions(s[i], kDegree, grid.knots);
    for (int a = 0; a <= kDegree; ++a) {
      const auto ia = static_cast<int>(span) - kDegree + a;
      equations.rhs(ia, 0) += w * basis(a) * y[i];
      equations.rhs(ia, 1) += w * basis(a) * z[i];
      for (int b = 0; b <= kDegree; ++b) {
        equations.triplets.emplace_back(ia, static_cast<int>(span) - kDegree + b, w * basis(a) * basis(b));
      }
    }
  }
}

// Penalty L^(2m) ∫ |C^(m)|^2 ds (lambda = L^(2m)), integrated exactly on every knot interval by
// 2-point Gauss quadrature (C^(m) is a polynomial of degree 3 - m there).
void add_penalty(const KnotGrid& grid, int m, double lambda, NormalEquations& equations) {
  const double gauss = 0.5 / std::sqrt(3.0);
  const double h = grid.h;
  for (int k = 0; k < grid.intervals; ++k) {
    for (const double offset : {0.5 - gauss, 0.5 + gauss}) {
      const double u = (k + offset) * h;
      const auto span = Curve::Span(u, kDegree, grid.knots);
      const auto derivatives = Curve::BasisFunctionDerivatives(u, m, kDegree, grid.knots);
      for (int a = 0; a <= kDegree; ++a) {
        for (int b = 0; b <= kDegree; ++b) {
          equations.triplets.emplace_back(static_cast<int>(span) - kDegree + a, static_cast<int>(span) - kDegree + b,
                                          lambda * 0.5 * h * derivatives(m, a) * derivatives(m, b));
        }
      }
    }
  }
}

// The control points of the penalised least-squares curve (one column per coordinate).
Eigen::MatrixX2d fitted_coefficients(const Profile& profile, const ChordPoints& points, const KnotGrid& grid,
                                     const SmoothingOptions& options) {
  const std::size_t n = points.s.size();
  const int n_ctrl = grid.control_points();
  NormalEquations equations;
  equations.triplets.reserve(static_cast<std::size_t>(16) * (n + static_cast<std::size_t>(grid.intervals)));
  equations.rhs = Eigen::MatrixX2d::Zero(n_ctrl, 2);
  add_data_terms(points, grid, equations);
  const int m = options.penalty_derivative;
  const double lambda = std::pow(options.smoothing_length_m, 2 * m);
  if (lambda > 0.0) add_penalty(grid, m, lambda, equations);

  Eigen::SparseMatrix<double> normal(n_ctrl, n_ctrl);
  normal.setFromTriplets(equations.triplets.begin(), equations.triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  require(solver.info() == Eigen::Success, [&] {
    return fmt::format(
        "profile {}: the smoothing spline system is singular (too few points for the knot "
        "spacing; increase the smoothing length)",
        name_of(profile));
  });
  Eigen::MatrixX2d coefficients = solver.solve(equations.rhs);
  require(solver.info() == Eigen::Success && coefficients.allFinite(),
          [&] { return fmt::format("profile {}: the smoothing spline could not be computed", name_of(profile)); });
  return coefficients;
}

// The impl's intervals and its table of y's running maximum from the fitted curve on its knot
// vector (s_end_m set).
void tabulate(const Curve& curve, const Curve::KnotVectorType& knots, int interval_count, SmoothProfile::Impl& impl) {
  // The Taylor coefficients at every knot interval's middle.
  impl.intervals.resize(static_cast<std::size_t>(interval_count));
  for (int k = 0; k < interval_count; ++k) {
    const double lower = knots(k + kDegree), upper = knots(k + kDegree + 1);
    SmoothProfile::Impl::Interval& interval = impl.intervals[static_cast<std::size_t>(k)];
    interval.middle_m = 0.5 * (lower + upper);
    const auto d = curve.derivatives<kDegree>(interval.middle_m);
    for (int order = 0; order <= kDegree; ++order) {
      interval.y[static_cast<std::size_t>(order)] = d(0, order);
      interval.z[static_cast<std::size_t>(order)] = d(1, order);
    }
  }
  // The running maximum of y on four samples per interval.
  const double length = impl.s_end_m;
  const int samples = 4 * interval_count;
  impl.table_s_m.resize(static_cast<std::size_t>(samples) + 1);
  impl.table_y_max_m.resize(static_cast<std::size_t>(samples) + 1);
  double y_max = -std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    const double sk = k == samples ? length : k * (length / samples);
    y_max = std::max(y_max, impl.y_at(sk));
    impl.table_s_m[static_cast<std::size_t>(k)] = sk;
    impl.table_y_max_m[static_cast<std::size_t>(k)] = y_max;
  }
  const std::vector<double>& ys = impl.table_y_max_m;
  const double y_range = ys.back() - ys.front();
  const auto buckets = static_cast<std::size_t>(samples);
  impl.buckets_per_m = y_range > 0.0 ? static_cast<double>(buckets) / y_range : 0.0;
  impl.bucket_first_sample.resize(buckets + 1);
  for (std::size_t b = 0; b < buckets; ++b) {
    const double lower_end = ys.front() + static_cast<double>(b) * (y_range / static_cast<double>(buckets));
    impl.bucket_first_sample[b] = static_cast<std::size_t>(std::lower_bound(ys.begin(), ys.end(), lower_end) - ys.begin());
  }
  impl.bucket_first_sample[buckets] = ys.size();
}

}  // namespace

SmoothProfile::SmoothProfile(const Profile& profile, const SmoothingOptions& options) {
  validate(profile);
  validate(options);
  const ChordPoints points = chord_length_points(profile);
  const double length = points.s.back();
  const KnotGrid grid = clamped_knot_grid(profile, length, options.knot_spacing_m);
  const Eigen::MatrixX2d coefficients = fitted_coefficients(profile, points, grid, options);

  auto impl = std::make_shared<Impl>();
  impl->s_begin_m = 0.0;
  impl->s_end_m = length;
  impl->source = profile.source;
  impl->kind = profile.kind;
  impl->knot_spacing_m = grid.h;
  impl->knots_per_m = 1.0 / grid.h;
  tabulate(Curve(grid.knots, coefficients.transpose()), grid.knots, grid.intervals, *impl);
  impl_ = std::move(impl);
}

const SmoothProfile::Impl& SmoothProfile::impl() const {
  require(impl_ != nullptr, "smooth profile: used before construction");
  return *impl_;
}

const std::string& SmoothProfile::source() const { return impl().source; }
ProfileKind SmoothProfile::kind() const { return impl().kind; }
double SmoothProfile::s_begin_m() const { return impl().s_begin_m; }
double SmoothProfile::s_end_m() const { return impl().s_end_m; }

ProfileCurvePoint SmoothProfile::at(double s_m) const {
  const Impl& im = impl();
  const double s = std::clamp(s_m, im.s_begin_m, im.s_end_m);
  const Impl::Interval& interval = im.interval_at(s);
  const CubicValue y = cubic_at(interval.y, s - interval.middle_m);
  const CubicValue z = cubic_at(interval.z, s - interval.middle_m);
  ProfileCurvePoint p;
  p.s_m = s;
  p.y_m = y.value;
  p.z_m = z.value;
  p.dy_ds = y.first;
  p.dz_ds = z.first;
  p.d2y_ds2_per_m = y.second;
  p.d2z_ds2_per_m = z.second;
  return p;
}

double SmoothProfile::curvature_at(double s_m) const {
  const ProfileCurvePoint p = at(s_m);
  const double speed2 = p.dy_ds * p.dy_ds + p.dz_ds * p.dz_ds;
  return (p.dy_ds * p.d2z_ds2_per_m - p.dz_ds * p.d2y_ds2_per_m) / (speed2 * std::sqrt(speed2));
}

double SmoothProfile::y_min_m() const { return impl().table_y_max_m.front(); }
double SmoothProfile::y_max_m() const { return impl().table_y_max_m.back(); }

double SmoothProfile::parameter_at(double y_m) const {
  const Impl& im = impl();
  const auto& ys = im.table_y_max_m;
  const double tolerance = 1e-12;
  require(y_m >= ys.front() - tolerance && y_m <= ys.back() + tolerance, [&] {
    return fmt::format("profile {}: y = {:.6f} mm lies outside the profile [{:.6f}, {:.6f}] mm", im.source, y_m * 1e3,
                       ys.front() * 1e3, ys.back() * 1e3);
  });
  // The first sample with y_max >= y_m: searched within y_m's bucket when the bucket brackets it
  // (always, but where rounding puts y_m in a neighbouring bucket), else in the whole table.
  auto first = ys.begin(), last = ys.end();
  if (im.buckets_per_m > 0.0) {
    const auto buckets = static_cast<double>(im.bucket_first_sample.size() - 1);
    const auto b = static_cast<std::size_t>(std::clamp(std::floor((y_m - ys.front()) * im.buckets_per_m), 0.0, buckets - 1.0));
    const std::size_t lo = im.bucket_first_sample[b], hi = im.bucket_first_sample[b + 1];
    if ((lo == 0 || ys[lo - 1] < y_m) && (hi == ys.size() || ys[hi] >= y_m)) {
      first = ys.begin() + static_cast<std::ptrdiff_t>(lo);
      last = ys.begin() + static_cast<std::ptrdiff_t>(hi);
    }
  }
  const auto it = std::lower_bound(first, last, y_m);
  if (it == ys.begin()) return im.table_s_m.front();
  if (it == ys.end()) return im.table_s_m.back();
  const auto j = static_cast<std::size_t>(it - ys.begin());
  const double lo = im.table_s_m[j - 1];
  const double hi = im.table_s_m[j];
  // y(s) is a cubic on each knot interval: Newton's method from the table's linear interpolation
  // (bracketed by the table's samples) takes two or three steps where TOMS 748 took six to ten
  // evaluations; the contact search inverts y(s) at every sample of its locus.
  const auto offset_and_slope = [&](double s) {
    const Impl::Interval& interval = im.interval_at(s);
    const CubicValue c = cubic_at(interval.y, s - interval.middle_m);
    return std::pair{c.value - y_m, c.first};
  };
  const double y_lo = ys[j - 1], y_hi = ys[j];
  const double guess = y_hi > y_lo ? lo + (hi - lo) * (y_m - y_lo) / (y_hi - y_lo) : 0.5 * (lo + hi);
  const auto root = geometry::newton_root(offset_and_slope, lo, hi, guess, 1e-14,
                                          "the profile parameter at a lateral position");
  return root ? *root : 0.5 * (lo + hi);
}

double SmoothProfile::z(double y_m) const { return at(parameter_at(y_m)).z_m; }

double SmoothProfile::dz_dy(double y_m) const {
  const ProfileCurvePoint p = at(parameter_at(y_m));
  return p.dz_ds / p.dy_ds;
}

double SmoothProfile::d2z_dy2_per_m(double y_m) const {
  const ProfileCurvePoint p = at(parameter_at(y_m));
  return (p.dy_ds * p.d2z_ds2_per_m - p.dz_ds * p.d2y_ds2_per_m) / (p.dy_ds * p.dy_ds * p.dy_ds);
}

double SmoothProfile::curvature_per_m(double y_m) const { return curvature_at(parameter_at(y_m)); }

}  // namespace railcontact
