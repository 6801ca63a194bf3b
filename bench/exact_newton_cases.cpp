// The exact solver's Newton on many cases, inexact against fixed inner tolerances
// (docs/BENCHMARKS.md "Speed on the S1002/UIC60 patch"; not a Google Benchmark program):
//  1. 48 S1002/UIC60 cases (y = -4, 0, 3 mm; about 1000 and 4700 elements; 8 creepages from
//     pure spin to saturation): total time, GMRES iterations, largest force difference;
//  2. 90 Hertzian ellipses with small creepage (300, 1200, 3000 elements; a/b = 1.5, 1, 0.5):
//     how many do not converge.
//   build/bench/exact_newton_cases
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"

namespace {

using namespace railcontact;
using Clock = std::chrono::steady_clock;
constexpr double kMu = 0.3;

struct Totals {
  double seconds = 0.0;
  int gmres_iterations = 0;
  double largest_difference = 0.0;  // of F1, F2 against the fixed tolerance's, / (mu F3)
};

void wheel_rail_cases() {
  const WheelRailPair pair = default_wheel_rail_pair();
  Totals totals[2];  // [0] every solve to 1e-6, [1] inexact Newton
  const double normalised[][3] = {{0.5, 0.5, 1}, {1, 0, 0}, {0, 1, 1}, {0.1, 0.1, 1},
                                  {2, 2, 1},     {0, 0, 1}, {0, 0, 10}, {0.05, 0, 0}};
  for (const double y : {-4e-3, 0.0, 3e-3}) {
    for (const int target : {1000, 4700}) {
      WheelRailPatchOptions options;
      options.target_elements = target;
      const WheelRailPatch wr = solve_wheel_rail_patch(pair, y, options);
      const NhFastSim nh(wr.patch);
      for (const auto& c : normalised) {
        const Creepage creepage =
            nh.creepage_from_normalised(c[0], c[1], c[2] * wr.spin_per_m, kMu, wr.patch.normal_force_N());
        TangentialForces reference;
        for (int inexact = 0; inexact < 2; ++inexact) {
          RollingOptions rolling;
          rolling.inexact_newton = inexact == 1;
          const auto start = Clock::now();
          const RollingSolution s = solve_rolling_exact(wr.patch, creepage, kMu, rolling);
          totals[inexact].seconds += std::chrono::duration<double>(Clock::now() - start).count();
          totals[inexact].gmres_iterations += s.krylov_iterations;
          if (inexact == 0) reference = s.forces;
          const double difference = std::max(std::fabs(s.forces.F1_N - reference.F1_N),
                                             std::fabs(s.forces.F2_N - reference.F2_N)) /
                                    (kMu * wr.patch.normal_force_N());
          totals[inexact].largest_difference = std::max(totals[inexact].largest_difference, difference);
        }
      }
    }
  }
  for (int inexact = 0; inexact < 2; ++inexact)
    std::printf("48 S1002/UIC60 cases, %s: %.2f s, %d GMRES iterations, largest |dF| / (mu F3) %.1e\n",
                inexact ? "inexact Newton" : "every solve to 1e-6", totals[inexact].seconds,
                totals[inexact].gmres_iterations, totals[inexact].largest_difference);
}

void small_creepage_ellipses() {
  const Material steel{2.1e11, 0.3};
  for (int inexact = 0; inexact < 2; ++inexact) {
    int cases = 0, failed = 0;
    for (const int elements : {300, 1200, 3000}) {
      for (const double a_over_b : {1.5, 1.0, 0.5}) {
        const double a = 6e-3, b = a / a_over_b;
        const ContactPatch patch = hertzian_patch(
            elliptical_contact_with_count(a, b, elements, EllipseMeshLayout::rolling_resolved), a, b, 98100, steel);
        for (const double xi : {2e-5, 5e-5, 1e-4, 2e-4, 4e-4}) {
          for (const double eta : {0.0, 1e-4}) {
            RollingOptions rolling;
            rolling.inexact_newton = inexact == 1;
            ++cases;
            try {
              (void)solve_rolling_exact(patch, Creepage{xi, eta, 0.0}, kMu, rolling);
            } catch (const Error& e) {
              ++failed;
              std::printf("  %d elements, a/b %g, xi %g, eta %g: %s\n", elements, a_over_b, xi, eta, e.what());
            }
          }
        }
      }
    }
    std::printf("%d ellipses with small creepage, %s: %d did not converge\n", cases,
                inexact ? "inexact Newton" : "every solve to 1e-6", failed);
  }
}

}  // namespace

int main() {
  wheel_rail_cases();
  small_creepage_ellipses();
  return 0;
}
