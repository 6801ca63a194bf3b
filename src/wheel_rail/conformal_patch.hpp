#pragma once
// The tangential problem of a conformal patch (docs/WHEELSET.md §4 "Conformal contact"): each
// strip's creepages from the wheelset's motion in the strip's own frame, the tangential solvers on
// the developed patch, and the pressures and tractions of every strip summed in the contact frame and
// the track frame.
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact::detail {

// A strip's frame (X1, t, n): the region's X1, and its (X2, X3) turned about X1 by the strip's angle.
struct StripFrame {
  Vector3 t{}, n{};
};
StripFrame strip_frame(const InterpenetrationRegion& region, const ConformalStrip& strip);

// The pressure's resultant on the wheel in the track frame: each element's pressure along its
// strip's normal (pressure_Pa on area.mesh).
Vector3 conformal_pressure_force_track_N(const InterpenetrationRegion& region, const TangentPlaneArea& area,
                                         const std::vector<double>& pressure_Pa);

// The creepages of each strip of area.mesh in its own frame, at its point on the undeformed wheel
// surface (as Kalker's CONTACT takes the rigid slip of a conformal patch at the wheel's surface
// points), over the patch's rolling speed. The wheel's radius there follows the curved surface, not
// the tangent plane: on a tread patch 10 mm wide the strips' ξ then differ from the planar
// ξ − φ x2 by about x2² / (2 R r) (R the rail's crown radius), which moves F1 by 1.7 kN on
// S1002/UIC60 at y = 0 (tests/conformal_contact_test.cpp).
StripCreepages conformal_strip_creepages(const WheelsetMotion& motion, const Vector3& wheelset_centre_m,
                                         const InterpenetrationRegion& region, const TangentPlaneArea& area,
                                         double patch_rolling_speed_m_per_s);

// One solver on a conformal patch: pressure_Pa on area.mesh, creepages per column of it; the
// exact solvers and FastSim (nH-FastSim with K2's flexibilities on the developed patch) march the
// strips' own creepages. A left wheel's patch is solved mirrored, as a planar one. The result's forces as PatchSolverResult
// describes them; force_track_N the whole contact force (pressure and tractions) in the track frame.
struct ConformalSolve {
  PatchSolverResult result;
  ContactPatch patch;  // as solved (the solve frame), for keep_tractions
  double pressure_centre_x1_m = 0.0, pressure_centre_x2_m = 0.0;  // from the reference point, developed
};
ConformalSolve solve_conformal_patch(TangentialSolver solver, const InterpenetrationRegion& region,
                                     const TangentPlaneArea& area, const std::vector<double>& pressure_Pa,
                                     const StripCreepages& creepages, const WheelsetOptions& options);

}  // namespace railcontact::detail
