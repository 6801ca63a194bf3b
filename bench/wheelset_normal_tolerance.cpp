// The wheelset's normal tolerance (docs/WHEELSET.md §8, WheelsetOptions::normal): for each tolerance,
// 60 warm time steps of 1 µm from the loaded state at y (mm, the argument; default 0) at 0.2 mm
// elements, the time per step, the right wheel's normal iterations, and how far the last step's
// forces lie from a fresh solve to 1e-12 (normal force over F3, F1 and F2 over mu F3).
//   build/bench/wheelset_normal_tolerance 0
//   build/bench/wheelset_normal_tolerance -6.8
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "railcontact/wheelset.hpp"

int main(int argc, char** argv) {
  using namespace railcontact;
  const WheelsetTrack track = default_wheelset_track();
  const double y0 = (argc > 1 ? std::atof(argv[1]) : 0.0) * 1e-3;
  // The state where each wheel carries 98.1 kN, held by position (as wheelset_bench's time step).
  Wheelset by_load(track, WheelsetOptions{});
  WheelsetState state;
  state.position.lateral_displacement_m = y0;
  const WheelsetResult loaded = by_load.evaluate(state);
  const double right = loaded.wheels[0].vertical_displacement_m, left = loaded.wheels[1].vertical_displacement_m;
  state.position.vertical_displacement_m = 0.5 * (right + left);
  state.position.roll_rad = (left - right) / (2.0 * track.wheel_profile_origin_y_m(WheelSide::left));
  std::printf("y = %g mm\n", y0 * 1e3);
  for (const double tolerance : {1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4}) {
    WheelsetOptions options;
    options.loads.reset();
    options.normal.tolerance = tolerance;
    Wheelset wheelset(track, options);
    WheelsetState s = state;
    (void)wheelset.evaluate(s);
    constexpr int kSteps = 60;
    double iterations = 0.0;
    WheelsetResult last;
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kSteps; ++k) {
      s.position.lateral_displacement_m = y0 + 1e-6 * (k + 1);
      last = wheelset.evaluate(s);
      iterations += last.wheels[0].patches.front().normal_iterations;
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    WheelsetOptions reference = options;
    reference.normal.tolerance = 1e-12;
    const WheelsetResult exact = Wheelset(track, reference).evaluate(s);
    double normal = 0.0, tangential = 0.0;
    for (int w = 0; w < 2; ++w) {
      for (std::size_t j = 0; j < exact.wheels[w].patches.size() && j < last.wheels[w].patches.size(); ++j) {
        const WheelsetPatch& a = last.wheels[w].patches[j];
        const WheelsetPatch& b = exact.wheels[w].patches[j];
        const double muF3 = options.friction_coefficient * b.normal_force_N;
        normal = std::max(normal, std::abs(a.normal_force_N - b.normal_force_N) / b.normal_force_N);
        tangential = std::max({tangential, std::abs(a.forces().F1_N - b.forces().F1_N) / muF3,
                               std::abs(a.forces().F2_N - b.forces().F2_N) / muF3});
      }
    }
    std::printf("tolerance %g: %.2f ms per step, %.1f normal iterations (right wheel), |dF3|/F3 %.1e, "
                "|dF1,2|/(mu F3) %.1e\n",
                tolerance, ms / kSteps, iterations / kSteps, normal, tangential);
  }
  return 0;
}
