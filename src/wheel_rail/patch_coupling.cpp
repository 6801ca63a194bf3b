// The elastic coupling between a wheel's separate patches (docs/WHEELSET.md §5 "Coupled patches").
#include "wheel_rail/patch_coupling.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "support/smoothstep.hpp"
#include "wheel_rail/conformal_patch.hpp"

namespace railcontact::detail {

namespace {

// The edge of the block the coupling's source gathers (see pressure_blocks), and the distance from
// a block's centre within which a target takes the block's elements one by one.
constexpr double kBlockSize_m = 1e-3;
constexpr double kNearField_m = 2.0 * kBlockSize_m;
// 4 ln(1 + √2): a uniform pressure p on a square of side s displaces its centre by
// (1 − ν)/(πG) p s × this, as a point load p s² at the distance s / this would.
constexpr double kSquareCentreFactor = 3.5254943480781717;

// Where the vertical gap crosses zero between locus samples `inside` (overlapping) and `outside`.
Vector3 overlap_end(const std::vector<ContactLocusSample>& locus, std::size_t inside, std::size_t outside) {
  const ContactLocusSample& a = locus[inside];
  const ContactLocusSample& b = locus[outside];
  const double t = std::clamp(a.vertical_gap_m / (a.vertical_gap_m - b.vertical_gap_m), 0.0, 1.0);
  Vector3 p{};
  for (std::size_t i = 0; i < 3; ++i) p[i] = a.point_track_m[i] + t * (b.point_track_m[i] - a.point_track_m[i]);
  return p;
}

std::array<Vector3, 2> overlap_ends(const WheelContactSearch& search, const InterpenetrationRegion& r) {
  const std::size_t n = search.locus.size();
  const std::size_t before = r.first_sample > 0 ? r.first_sample - 1 : r.first_sample;
  const std::size_t after = r.last_sample + 1 < n ? r.last_sample + 1 : r.last_sample;
  return {overlap_end(search.locus, r.first_sample, before), overlap_end(search.locus, r.last_sample, after)};
}

double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

double patch_coupling_weight(double distance_m, const PatchCouplingOptions& options) {
  if (distance_m >= options.end_distance_m) return 0.0;
  if (distance_m <= options.full_distance_m) return 1.0;
  return smoothstep((options.end_distance_m - distance_m) / (options.end_distance_m - options.full_distance_m));
}

double overlap_distance_m(const WheelContactSearch& search, const InterpenetrationRegion& a,
                          const InterpenetrationRegion& b) {
  if (a.rail_profile_y_max_m >= b.rail_profile_y_min_m && b.rail_profile_y_max_m >= a.rail_profile_y_min_m) return 0.0;
  double d = std::numeric_limits<double>::infinity();
  for (const Vector3& p : overlap_ends(search, a))
    for (const Vector3& q : overlap_ends(search, b)) d = std::min(d, std::hypot(p[1] - q[1], p[2] - q[2]));
  return d;
}

SurfacePoints surface_points(const InterpenetrationRegion& region, const TangentPlaneArea& area) {
  const Mesh& mesh = area.mesh;
  SurfacePoints s;
  s.point_m.resize(mesh.size());
  s.normal.resize(mesh.size());
  for (int i2 = 0; i2 < mesh.n2; ++i2) {
    // The column's point at x1 = 0 and its normal.
    Vector3 origin{}, normal = region.x3_axis;
    if (area.strips.empty()) {
      for (std::size_t i = 0; i < 3; ++i)
        origin[i] = region.reference_point_track_m[i] + mesh.x2(i2) * region.x2_axis[i];
    } else {
      const ConformalStrip& strip = area.strips[static_cast<std::size_t>(i2)];
      origin = strip.wheel_point_track_m;
      normal = strip_frame(region, strip).n;
    }
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const std::size_t e = mesh.index(i1, i2);
      for (std::size_t i = 0; i < 3; ++i) s.point_m[e][i] = origin[i] + mesh.x1(i1) * region.x1_axis[i];
      s.normal[e] = normal;
    }
  }
  return s;
}

PressureBlocks pressure_blocks(const TangentPlaneArea& area, const SurfacePoints& points,
                               const std::vector<double>& pressure_Pa) {
  const Mesh& mesh = area.mesh;
  const int b1 = std::max(1, static_cast<int>(std::lround(kBlockSize_m / mesh.dx1_m)));
  const int b2 = std::max(1, static_cast<int>(std::lround(kBlockSize_m / mesh.dx2_m)));
  PressureBlocks blocks;
  blocks.element_core_m = std::sqrt(mesh.dx1_m * mesh.dx2_m) / kSquareCentreFactor;
  blocks.first_element.push_back(0);
  for (int j2 = 0; j2 < mesh.n2; j2 += b2) {
    for (int j1 = 0; j1 < mesh.n1; j1 += b1) {
      double force = 0.0;
      Vector3 centre{}, normal{};
      for (int i2 = j2; i2 < std::min(j2 + b2, mesh.n2); ++i2) {
        for (int i1 = j1; i1 < std::min(j1 + b1, mesh.n1); ++i1) {
          const std::size_t e = mesh.index(i1, i2);
          const double f = pressure_Pa[e] * mesh.element_area_m2();
          if (!(f > 0.0)) continue;
          force += f;
          blocks.element_point_m.push_back(points.point_m[e]);
          blocks.element_force_N.push_back(f);
          for (std::size_t i = 0; i < 3; ++i) {
            centre[i] += f * points.point_m[e][i];
            normal[i] += f * points.normal[e][i];
          }
        }
      }
      if (!(force > 0.0)) continue;
      const double length = std::sqrt(dot(normal, normal));
      for (std::size_t i = 0; i < 3; ++i) {
        centre[i] /= force;
        normal[i] /= length;
      }
      blocks.centre_m.push_back(centre);
      blocks.normal.push_back(normal);
      blocks.force_N.push_back(force);
      blocks.first_element.push_back(blocks.element_force_N.size());
    }
  }
  return blocks;
}

void add_coupling_displacement(const PressureBlocks& source, const SurfacePoints& target, double weight,
                               const Material& material, const std::vector<double>& h_m, std::vector<double>& lift_m) {
  // The approach of two half-spaces of one material under a normal point load P at distance r:
  // (1 − ν)/(πG) P / r, Boussinesq's surface displacement (1 − ν²)/(πE) P / r of each body.
  const double compliance = weight * (1.0 - material.poisson_ratio) / (M_PI * material.shear_modulus_Pa());
  // The overlapping elements as arrays, and Σ F n / r over the blocks at each (block by block: the
  // loop over the elements has no dependence between iterations, and vectorises).
  std::vector<std::size_t> index;
  for (std::size_t e = 0; e < h_m.size(); ++e)
    if (h_m[e] < 0.0) index.push_back(e);
  const std::size_t n = index.size();
  std::vector<double> x(n), y(n), z(n), vx(n, 0.0), vy(n, 0.0), vz(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = target.point_m[index[k]][0];
    y[k] = target.point_m[index[k]][1];
    z[k] = target.point_m[index[k]][2];
  }
  std::vector<std::size_t> near;
  const double core2 = source.element_core_m * source.element_core_m;
  for (std::size_t b = 0; b < source.force_N.size(); ++b) {
    const double cx = source.centre_m[b][0], cy = source.centre_m[b][1], cz = source.centre_m[b][2];
    const double fx = source.force_N[b] * source.normal[b][0], fy = source.force_N[b] * source.normal[b][1],
                 fz = source.force_N[b] * source.normal[b][2];
    bool any_near = false;
    for (std::size_t k = 0; k < n; ++k) {
      const double dx = x[k] - cx, dy = y[k] - cy, dz = z[k] - cz;
      const double r2 = dx * dx + dy * dy + dz * dz;
      const bool is_near = r2 < kNearField_m * kNearField_m;
      any_near |= is_near;
      const double inverse_r = is_near ? 0.0 : 1.0 / std::sqrt(r2);
      vx[k] += fx * inverse_r;
      vy[k] += fy * inverse_r;
      vz[k] += fz * inverse_r;
    }
    if (!any_near) continue;
    // The near targets: the block's elements one by one.
    near.clear();
    for (std::size_t k = 0; k < n; ++k) {
      const double dx = x[k] - cx, dy = y[k] - cy, dz = z[k] - cz;
      if (dx * dx + dy * dy + dz * dz < kNearField_m * kNearField_m) near.push_back(k);
    }
    for (const std::size_t k : near) {
      double sum = 0.0;
      for (std::size_t e = source.first_element[b]; e < source.first_element[b + 1]; ++e) {
        const Vector3& p = source.element_point_m[e];
        const double ex = x[k] - p[0], ey = y[k] - p[1], ez = z[k] - p[2];
        sum += source.element_force_N[e] / std::sqrt(std::max(ex * ex + ey * ey + ez * ez, core2));
      }
      vx[k] += source.normal[b][0] * sum;
      vy[k] += source.normal[b][1] * sum;
      vz[k] += source.normal[b][2] * sum;
    }
  }
  // Along each element's normal.
  for (std::size_t k = 0; k < n; ++k) lift_m[index[k]] += compliance * dot({vx[k], vy[k], vz[k]}, target.normal[index[k]]);
}

}  // namespace railcontact::detail
