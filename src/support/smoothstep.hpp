#pragma once
// The smoothstep S(t) = t² (3 − 2t) of t clamped to [0, 1]: 0 below 0, 1 above 1, C¹ at both ends.
// The blends that must not jump use it (the automatic contact surface's weight, the elastic slip's).
#include <algorithm>

namespace railcontact::detail {

inline double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace railcontact::detail
