#pragma once
// The profile fuzz targets (fuzz/*_profile_fuzz.cpp): a profile as a reader returns it has passed
// validate (railcontact/geometry.hpp ProfileLimits); it is then smoothed as a wheel-rail pair does
// (SmoothProfile), which is cheap for the profiles of the corpus (hundreds of points) and bounded
// here to profiles of at most kMaxSmoothedPoints points, so that one input stays well under a
// second.
#include <cstddef>

#include "railcontact/geometry.hpp"

namespace railcontact::fuzz {

inline constexpr std::size_t kMaxSmoothedPoints = 5000;

inline void smooth(const Profile& profile) {
  if (profile.size() <= kMaxSmoothedPoints) {
    const SmoothProfile smooth(profile);
    (void)smooth.z(0.5 * (smooth.y_min_m() + smooth.y_max_m()));
  }
}

}  // namespace railcontact::fuzz
