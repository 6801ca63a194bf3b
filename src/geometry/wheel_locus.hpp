#pragma once
// A wheel's contact locus sampled once for every height (docs/WHEELSET.md §2, §8). The locus
// point of each wheel profile sample, and the rail point below it, depend on the wheelset's
// lateral position, roll and yaw; its vertical displacement z only lifts every locus point, and so
// its vertical gap, by z. The height iteration by load therefore samples a wheel's locus once per
// (y, roll, yaw) and searches it at every height it tries.
#include <cstdint>
#include <vector>

#include "railcontact/wheelset_geometry.hpp"

namespace railcontact::detail {

struct WheelLocus {
  WheelSide side = WheelSide::right;
  WheelsetPosition position;  // where it was sampled, at z = 0
  double step_m = 0.0;        // the sampling step along the wheel profile
  std::vector<ContactLocusSample> samples;
  std::vector<std::uint8_t> valid;  // 0 where a sample has no locus point or no rail below it

  // True when this is the locus of `side` at `p` up to its height, sampled with `step_m`.
  [[nodiscard]] bool serves(WheelSide s, const WheelsetPosition& p, double step) const {
    return !samples.empty() && s == side && p.lateral_displacement_m == position.lateral_displacement_m &&
           p.roll_rad == position.roll_rad && p.yaw_rad == position.yaw_rad && step == step_m;
  }
};

// The locus of one wheel at `position` (its z ignored), sampled every `step_m` of the wheel profile.
[[nodiscard]] WheelLocus sample_wheel_locus(const WheelsetTrack& track, WheelSide side,
                                            const WheelsetPosition& position, double step_m);

// The vertical displacement at which the wheel first touches its rail (WheelsetTrack::
// touching_vertical_displacement_m) from its locus.
[[nodiscard]] double touching_vertical_displacement_m(const WheelLocus& locus);

// The contact search of the locus's wheel at `position` (WheelsetTrack::contact_search): its
// locus lifted by z.
[[nodiscard]] WheelContactSearch contact_search(const WheelsetTrack& track, const WheelLocus& locus,
                                                const WheelsetPosition& position, const ContactSearchOptions& options);

}  // namespace railcontact::detail
