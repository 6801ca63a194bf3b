// The tangential problem of a conformal patch (see the header).
#include "wheel_rail/conformal_patch.hpp"

#include <cmath>

#include "railcontact/wheel_rail.hpp"
#include "tangential/cropped_patch.hpp"
#include "wheel_rail/patch_tangential_model.hpp"

namespace railcontact::detail {

namespace {

Vector3 along(const Vector3& a, double sa, const Vector3& b, double sb) {
  return {sa * a[0] + sb * b[0], sa * a[1] + sb * b[1], sa * a[2] + sb * b[2]};
}

}  // namespace

StripFrame strip_frame(const InterpenetrationRegion& region, const ConformalStrip& strip) {
  const double c = std::cos(strip.angle_rad), s = std::sin(strip.angle_rad);
  return {along(region.x2_axis, c, region.x3_axis, s), along(region.x3_axis, c, region.x2_axis, -s)};
}

Vector3 conformal_pressure_force_track_N(const InterpenetrationRegion& region, const TangentPlaneArea& area,
                                         const std::vector<double>& pressure_Pa) {
  Vector3 f{};
  const Mesh& mesh = area.mesh;
  for (int i2 = 0; i2 < mesh.n2; ++i2) {
    double strip_force = 0.0;
    for (int i1 = 0; i1 < mesh.n1; ++i1) strip_force += pressure_Pa[mesh.index(i1, i2)];
    const Vector3 n = strip_frame(region, area.strips[static_cast<std::size_t>(i2)]).n;
    for (std::size_t i = 0; i < 3; ++i) f[i] += strip_force * mesh.element_area_m2() * n[i];
  }
  return f;
}

StripCreepages conformal_strip_creepages(const WheelsetMotion& motion, const Vector3& wheelset_centre_m,
                                         const InterpenetrationRegion& region, const TangentPlaneArea& area,
                                         double patch_rolling_speed_m_per_s) {
  StripCreepages creepages(area.strips.size());
  const WheelsetKinematics kinematics(motion);
  for (std::size_t j = 0; j < area.strips.size(); ++j) {
    const ConformalStrip& strip = area.strips[j];
    if (!strip.possible_contact) continue;  // no element of it can be in contact
    const StripFrame f = strip_frame(region, strip);
    ContactFrame frame;
    frame.point_from_wheelset_centre_m = along(strip.wheel_point_track_m, 1.0, wheelset_centre_m, -1.0);
    frame.x1 = region.x1_axis;
    frame.x2 = f.t;
    frame.x3 = f.n;
    // The velocities of the strip's point over the patch's rolling speed, as the planar patch's
    // rigid slip divides every element's by its one rolling speed.
    const WheelsetKinematics::AtContact at = kinematics.at(frame);
    const double scale = at.rolling_speed_m_per_s / patch_rolling_speed_m_per_s;
    const Creepage& c = at.creepage;
    creepages[j] = {c.xi * scale, c.eta * scale, c.phi * scale};
  }
  return creepages;
}

ConformalSolve solve_conformal_patch(TangentialSolver solver, const InterpenetrationRegion& region,
                                     const TangentPlaneArea& area, const std::vector<double>& pressure_Pa,
                                     const StripCreepages& creepages, const WheelsetOptions& options) {
  // The left wheel's patch is solved as the mirror image of a right wheel's (x2 -> −x2: the strips
  // in reverse order, η, φ and the strips' angles change sign), as a planar patch is.
  const Mesh& mesh = area.mesh;
  const bool mirror = region.side == WheelSide::left;
  const double s2 = mirror ? -1.0 : 1.0;
  Mesh solve_mesh = mesh;
  std::vector<double> solve_pressure = pressure_Pa;
  StripCreepages solve_creepages = creepages;
  std::vector<double> solve_angle(static_cast<std::size_t>(mesh.n2));
  for (int i2 = 0; i2 < mesh.n2; ++i2) {
    const auto j = static_cast<std::size_t>(mirror ? mesh.n2 - 1 - i2 : i2);
    const Creepage& c = creepages[static_cast<std::size_t>(i2)];
    solve_creepages[j] = {c.xi, s2 * c.eta, s2 * c.phi};
    solve_angle[j] = s2 * area.strips[static_cast<std::size_t>(i2)].angle_rad;
    if (mirror)
      for (int i1 = 0; i1 < mesh.n1; ++i1)
        solve_pressure[mesh.index(i1, static_cast<int>(j))] = pressure_Pa[mesh.index(i1, i2)];
  }
  if (mirror) solve_mesh.x2_first_m = -mesh.x2(mesh.n2 - 1);
  std::vector<std::size_t> elements;
  for (std::size_t k = 0; k < solve_mesh.size(); ++k)
    if (solve_pressure[k] > 0.0) elements.push_back(k);
  ConformalSolve out;
  out.patch = cropped_patch(solve_mesh, solve_pressure, elements, options.material);
  const ContactPatch& contact = out.patch;
  out.pressure_centre_x1_m = -contact.x1_shift_m();
  out.pressure_centre_x2_m = -s2 * contact.x2_shift_m();
  // The cropped patch's strips are the solve mesh's columns; its origin the centre of pressure, so
  // η + φ x1 from the reference point is (η − φ x1_shift) + φ x1 from the patch's origin.
  const Mesh& cropped = contact.mesh();
  std::vector<std::size_t> column(static_cast<std::size_t>(cropped.n2));
  StripCreepages patch_creepages(column.size());
  for (int i2 = 0; i2 < cropped.n2; ++i2) {
    const auto j = static_cast<std::size_t>(
        std::lround((cropped.x2(i2) - contact.x2_shift_m() - solve_mesh.x2_first_m) / solve_mesh.dx2_m));
    column[static_cast<std::size_t>(i2)] = j;
    const Creepage& c = solve_creepages[j];
    patch_creepages[static_cast<std::size_t>(i2)] = {c.xi, c.eta - c.phi * contact.x1_shift_m(), c.phi};
  }
  // As on a planar patch: nH-FastSim per lobe where the patch has several (docs/WHEELSET.md §8),
  // else K2's flexibilities on the developed patch, or the equivalent ellipse's for a patch too
  // small for K2 (docs/WHEELSET.md §5); FastSim marches each strip with its own creepages.
  const TangentialModel model = patch_tangential_model(solver, contact, options);
  const TangentialSolution s = model.solve(patch_creepages, options.friction_coefficient, TangentialOutput::fields);
  // Every element's traction (p1, p2 along its strip's tangent) and pressure (along its strip's
  // normal) turned into the contact frame and summed: F2 = Σ (p2 cos Δ − p3 sin Δ) S,
  // F3 = Σ (p2 sin Δ + p3 cos Δ) S (in the solve frame; F2 mirrored back below).
  const double S = cropped.element_area_m2();
  const auto n1 = static_cast<std::size_t>(cropped.n1);
  // cos Δ and sin Δ once per strip of the cropped patch, not per element.
  std::vector<double> strip_cos(column.size()), strip_sin(column.size());
  for (std::size_t i2 = 0; i2 < column.size(); ++i2) {
    strip_cos[i2] = std::cos(solve_angle[column[i2]]);
    strip_sin[i2] = std::sin(solve_angle[column[i2]]);
  }
  double F1 = 0.0, F2 = 0.0, F3 = 0.0;
  const auto& indices = contact.elements().indices();
  for (std::size_t e = 0; e < indices.size(); ++e) {
    const std::size_t strip = indices[e] / n1;
    const double c = strip_cos[strip], sn = strip_sin[strip], p3 = contact.pressure_Pa()[e];
    F1 += s.p1_Pa[e] * S;
    F2 += (s.p2_Pa[e] * c - p3 * sn) * S;
    F3 += (s.p2_Pa[e] * sn + p3 * c) * S;
  }
  PatchSolverResult& r = out.result;
  r.solver = solver;
  r.flexibility = model.flexibility().value_or(Flexibility{0.0, 0.0, 0.0});
  r.coupling = model.coupling();
  r.forces = {F1, s2 * F2, s2 * s.forces.M3_Nm};
  r.force_track_N = along(along(region.x1_axis, F1, region.x2_axis, s2 * F2), 1.0, region.x3_axis, F3);
  r.adhesion_fraction = s.adhesion_fraction;
  if (options.keep_tractions) {
    r.p1_Pa = s.p1_Pa;
    r.p2_Pa = s.p2_Pa;
    for (double& p2 : r.p2_Pa) p2 *= s2;
    r.slip = s.slip;
  }
  return out;
}

}  // namespace railcontact::detail
