#pragma once
// The wheel's height by load (docs/WHEELSET.md §5): the vertical overlap δ below first touch at
// which a wheel's normal forces carry a target load. Shared by the wheelset by load and the single
// wheel–rail patch on the smooth reference (docs/WHEEL_RAIL.md §1).
#include <algorithm>
#include <cmath>

namespace railcontact::detail {

// The deepest overlap of the undeformed wheel and rail a patch may have: about 1e7 N, the largest
// normal force, on S1002/UIC60.
inline constexpr double kMaximumWheelOverlap_m = 2e-3;

// Newton-like steps on δ: F ∝ δ^(3/2) (Hertz) for the first two, then secant steps; each step
// within a factor 4 of δ and at most kMaximumWheelOverlap_m. Given the contact stiffness dF/dδ of
// a nearby state (a time step's previous one), the first step is Newton's with it and the
// secant steps follow at once.
struct HeightIteration {
  double previous_delta_m = 0.0, previous_force_N = 0.0;
  double seed_stiffness_N_per_m = 0.0;  // dF/dδ of a nearby state (0: none)
  double stiffness_N_per_m = 0.0;       // the last secant's dF/dδ (0: none yet)

  // The next δ after the force `force_N` at δ = `delta_m` in iteration `iteration` (from 1).
  double next_overlap_m(double delta_m, double force_N, double target_N, int iteration) {
    const bool seeded = seed_stiffness_N_per_m > 0.0;
    if (iteration > 1 && force_N > 0.0 && previous_force_N > 0.0 && delta_m != previous_delta_m &&
        force_N != previous_force_N)
      stiffness_N_per_m = (force_N - previous_force_N) / (delta_m - previous_delta_m);
    double next;
    if (!(force_N > 0.0)) {
      next = 2.0 * delta_m;
    } else if (iteration == 1 && seeded) {
      next = delta_m + (target_N - force_N) / seed_stiffness_N_per_m;
    } else if ((iteration <= 2 && !seeded) || previous_force_N <= 0.0 || force_N == previous_force_N) {
      next = delta_m * std::pow(target_N / force_N, 2.0 / 3.0);
    } else {
      next = delta_m + (target_N - force_N) * (delta_m - previous_delta_m) / (force_N - previous_force_N);
      if (!(next > 0.0)) next = delta_m * std::pow(target_N / force_N, 2.0 / 3.0);
    }
    previous_delta_m = delta_m;
    previous_force_N = force_N;
    return std::min(std::clamp(next, 0.25 * delta_m, 4.0 * delta_m), kMaximumWheelOverlap_m);
  }
};

}  // namespace railcontact::detail
