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
  // A locus sampled on demand (sample_wheel_locus with coarse_every > 1): at first every
  // coarse_every-th sample and the last, the others where refine_locus needs them; computed[k]
  // says which are (empty: all). One not computed reads as valid and far from the rail (an
  // infinite gap): refine_locus computes every sample that can overlap and its neighbours.
  int coarse_every = 1;
  std::vector<std::uint8_t> computed;

  // True when this is the locus of `side` at `p` up to its height, sampled with `step_m`.
  [[nodiscard]] bool serves(WheelSide s, const WheelsetPosition& p, double step) const {
    return !samples.empty() && s == side && p.lateral_displacement_m == position.lateral_displacement_m &&
           p.roll_rad == position.roll_rad && p.yaw_rad == position.yaw_rad && step == step_m;
  }
};

// The locus of one wheel at `position` (its z ignored), sampled every `step_m` of the wheel profile;
// with coarse_every > 1 on demand (above).
[[nodiscard]] WheelLocus sample_wheel_locus(const WheelsetTrack& track, WheelSide side,
                                            const WheelsetPosition& position, double step_m, int coarse_every = 1);

// Computes the samples of an on-demand locus whose vertical gap may lie below `level_m` (the wheel
// overlapping its rail when lifted by z = −level_m), and their neighbours: those of every
// interval between computed samples where the gap at either end lies within a margin of the level
// (kLocusMargin_m and the larger second difference of the gap at the ends, eight times the most
// the gap can dip between them with that curvature), or where one end has no locus point (no rail
// below it, a vertical part of the profile) and the other has; between two ends without one, no
// sample is taken to have one (docs/WHEELSET.md §8 "The locus on demand").
void refine_locus(const WheelsetTrack& track, WheelLocus& locus, double level_m);

// The vertical displacement at which the wheel first touches its rail (WheelsetTrack::
// touching_vertical_displacement_m) from its locus (an on-demand one refined about its lowest gap).
[[nodiscard]] double touching_vertical_displacement_m(const WheelsetTrack& track, WheelLocus& locus);

// The contact search of the locus's wheel at `position` (WheelsetTrack::contact_search): its
// locus lifted by z (an on-demand one refined where it overlaps, and across the regions it merges).
[[nodiscard]] WheelContactSearch contact_search(const WheelsetTrack& track, WheelLocus& locus,
                                                const WheelsetPosition& position, const ContactSearchOptions& options);

}  // namespace railcontact::detail
