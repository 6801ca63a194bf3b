// The wheelset's normal tolerance (docs/WHEELSET.md §8, WheelsetOptions::normal): for each tolerance,
// 60 warm time steps of 1 µm from the state at y (mm, the first argument; default 0) where both
// wheels carry 98.1 kN with the roll balanced (wheelset_bench's state), at 0.2 mm elements, by
// position or, with the second argument `load`, by load (each wheel's height solved, the
// tangential forces in the balance). It prints the time per step, the conjugate-gradient
// iterations and height trials per step (both wheels), and how far the forces lie from a fresh
// solve to 1e-12 at every sixth step: each patch's normal force over its F3, F1 and F2 over μF3, and
// each wheel's force in the track frame over μ times 98.1 kN.
//   build/bench/wheelset_normal_tolerance 0
//   build/bench/wheelset_normal_tolerance -6.5 load
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "railcontact/wheelset.hpp"

int main(int argc, char** argv) {
  using namespace railcontact;
  const WheelsetTrack track = default_wheelset_track();
  const double y0 = (argc > 1 ? std::atof(argv[1]) : 0.0) * 1e-3;
  const bool by_load = argc > 2 && std::strcmp(argv[2], "load") == 0;
  constexpr double kLoad_N = 98.1e3;
  WheelsetOptions balanced;
  balanced.loads = WheelLoads{kLoad_N, kLoad_N, true};
  WheelsetState state;
  state.position.lateral_displacement_m = y0;
  state.position = Wheelset(track, balanced).evaluate(state).state.position;
  std::printf("y = %g mm, %s\n", y0 * 1e3, by_load ? "by load" : "by position");
  for (const double tolerance : {1e-8, 1e-7, 1e-6, 2e-6, 5e-6, 1e-5, 1e-4}) {
    WheelsetOptions options;
    if (!by_load) options.loads.reset();
    options.normal.tolerance = tolerance;
    WheelsetOptions reference = options;
    reference.normal.tolerance = 1e-12;
    Wheelset wheelset(track, options);
    WheelsetState s = state;
    (void)wheelset.evaluate(s);
    constexpr int kSteps = 60;
    double seconds = 0.0, iterations = 0.0, trials = 0.0, normal = 0.0, tangential = 0.0, wheel = 0.0;
    for (int k = 0; k < kSteps; ++k) {
      s.position.lateral_displacement_m = y0 + 1e-6 * (k + 1);
      const auto start = std::chrono::steady_clock::now();
      const WheelsetResult r = wheelset.evaluate(s);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      for (const WheelResult& w : r.wheels) {
        trials += w.load_iterations;
        for (const WheelsetPatch& p : w.patches) iterations += p.normal_iterations;
      }
      if (k % 6 != 5) continue;
      const WheelsetResult exact = Wheelset(track, reference).evaluate(s);
      for (std::size_t w = 0; w < 2; ++w) {
        const WheelResult &a = r.wheels[w], &b = exact.wheels[w];
        for (std::size_t i = 0; i < 3; ++i)
          wheel = std::max(wheel, std::abs(a.force_track_N[i] - b.force_track_N[i]) /
                                      (options.friction_coefficient * kLoad_N));
        for (std::size_t j = 0; j < b.patches.size() && j < a.patches.size(); ++j) {
          const WheelsetPatch &pa = a.patches[j], &pb = b.patches[j];
          const double muF3 = options.friction_coefficient * pb.normal_force_N;
          normal = std::max(normal, std::abs(pa.normal_force_N - pb.normal_force_N) / pb.normal_force_N);
          tangential = std::max({tangential, std::abs(pa.forces().F1_N - pb.forces().F1_N) / muF3,
                                 std::abs(pa.forces().F2_N - pb.forces().F2_N) / muF3});
        }
      }
    }
    std::printf("tolerance %g: %.2f ms per step, %.1f CG iterations and %.1f height trials per step, |dF3|/F3 %.1e, "
                "|dF1,2|/(mu F3) %.1e, wheel |dF|/(mu Fz) %.1e\n",
                tolerance, 1e3 * seconds / kSteps, iterations / kSteps, trials / kSteps, normal, tangential, wheel);
  }
  return 0;
}
