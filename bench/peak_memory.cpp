// Peak memory of the solvers on the S1002/UIC60 patch at y = 0 (docs/BENCHMARKS.md "Peak memory"):
// one solve per process, since the peak (getrusage's ru_maxrss) only grows. Prints the peak
// resident size after the normal problem and after the tangential solve, and the time of the
// process's first nH-FastSim (FFT planning of its coarse size included) and of a second one.
//   build/bench/peak_memory TARGET_ELEMENTS {exact|nh-fastsim}
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"
#include "tangential/adhesion_tuning.hpp"

namespace {

double peak_MiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

}  // namespace

int main(int argc, char** argv) try {
  using namespace railcontact;
  const std::string solver = argc == 3 ? argv[2] : "";
  char* end = nullptr;
  const long target = argc == 3 ? std::strtol(argv[1], &end, 10) : 0;
  if (argc != 3 || end == argv[1] || *end != '\0' || target <= 0 || target > 10'000'000 ||
      (solver != "exact" && solver != "nh-fastsim")) {
    std::fprintf(stderr, "usage: peak_memory TARGET_ELEMENTS {exact|nh-fastsim} (TARGET_ELEMENTS a whole number > 0)\n");
    return 2;
  }
  const double start_MiB = peak_MiB();
  WheelRailPatchOptions options;
  options.target_elements = static_cast<int>(target);
  const WheelRailPatch patch = solve_wheel_rail_patch(default_wheel_rail_pair(), 0.0, options);
  const double normal_MiB = peak_MiB();
  // The first nH-FastSim of the process (its coarse FFT size planned here), timed.
  auto begin = std::chrono::steady_clock::now();
  const NhFastSim nh(patch.patch);
  const Creepage creepage = nh.creepage_from_normalised(0.5, 0.5, patch.spin_per_m, 0.3, patch.patch.normal_force_N());
  TangentialForces forces = nh.forces(creepage, 0.3);
  const double first_nh_fastsim_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  // The same again (FFT plans and coarse kernels kept; K2's adjoints solved again, not taken from
  // the thread's memo): what the first solve pays extra, and on a noisy machine the spread of a
  // fixed amount of work from process to process.
  forget_remembered_adjoints();
  begin = std::chrono::steady_clock::now();
  const NhFastSim again(patch.patch);
  const TangentialForces forces_again = again.forces(creepage, 0.3);
  const double second_nh_fastsim_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  if (forces_again.F1_N != forces.F1_N || forces_again.F2_N != forces.F2_N) {
    std::fprintf(stderr, "peak_memory: the second nH-FastSim differs from the first\n");
    return 1;
  }
  double exact_s = 0.0;
  if (solver == "exact") {
    begin = std::chrono::steady_clock::now();
    forces = solve_rolling_exact(patch.patch, creepage, 0.3).forces;
    exact_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  }
  std::printf("%s elements_in_contact %zu potential_area %zu peak_MiB: start %.1f after_normal %.1f after_solve %.1f "
              "first_nh_fastsim_ms %.3f second_nh_fastsim_ms %.3f exact_s %.3f F1_N %.1f F2_N %.1f\n",
              argv[2], patch.elements_in_contact, patch.potential_area.size(), start_MiB, normal_MiB, peak_MiB(),
              1e3 * first_nh_fastsim_s, 1e3 * second_nh_fastsim_s, exact_s, forces.F1_N, forces.F2_N);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "peak_memory: %s\n", e.what());
  return 1;
}
