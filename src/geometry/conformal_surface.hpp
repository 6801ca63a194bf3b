#pragma once
// The conformal contact surface's own check (docs/WHEELSET.md §4 "Conformal contact"), apart from
// WheelsetTrack::conformal_contact_area so that it can be tested on strips of any shape.
#include <vector>

#include "railcontact/wheelset_geometry.hpp"

namespace railcontact::geometry {

// The developed surface must not fold over in the tangent plane: the tangent-plane points x2_m of
// the strips that can touch rise with their developed coordinate. A fold needs the surface to turn
// by more than 90° from the reference's tangent plane within one region. Throws Error
// (invalid_input) naming the wheel, the position and the two strips' angles where it folds.
void require_unfolded(const std::vector<ConformalStrip>& strips, WheelSide side, const WheelsetPosition& position);

}  // namespace railcontact::geometry
