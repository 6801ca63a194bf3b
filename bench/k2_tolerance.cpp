// K2's GMRES tolerance in nH-FastSim (docs/FASTSIM.md "K2's solves"): for each tolerance, the
// largest relative difference of C11, C22 and C23 (the entries the term-by-term match uses) from a
// solve to 1e-9 on the automatically coarsened patch, and the GMRES iterations per patch for both
// force rows, with NhFastSim's options (adhesion_options and kAdhesionTuning in nh_fastsim.cpp).
// Patches: S1002/UIC60 at y = -7 ... 4 mm in 1 mm steps with 1000 ... 11 000 elements in contact,
// and Hertzian ellipses a/b = 0.2 ... 5 with 1000, 3000, 8000 elements. A plain program:
//   build/bench/k2_tolerance
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"
#include "tangential/adhesion_tuning.hpp"

namespace {

using namespace railcontact;

struct Tally {
  double largest_difference = 0.0;
  long iterations = 0;
  int patches = 0;
};

ContactPatch coarse_patch(const ContactPatch& patch) {
  const CoarseBlocks blocks = NhFastSim::automatic_coarse_blocks(patch);
  return blocks == CoarseBlocks{1, 1} ? patch : coarsened(patch, blocks);
}

AdhesionSolution force_rows(const ContactPatch& coarse, double tolerance) {
  AdhesionOptions options;
  options.part = CreepageMatrixPart::force_rows;
  options.tolerance = tolerance;
  return solve_full_adhesion(coarse.elements(), coarse.material(), options,
                             AdhesionTuning{AdhesionPreconditioner::marching_half_laplacian, 1.5});
}

void add(const ContactPatch& patch, double tolerance, Tally& tally) {
  const ContactPatch coarse = coarse_patch(patch);
  const AdhesionSolution loose = force_rows(coarse, tolerance);
  const AdhesionSolution tight = force_rows(coarse, 1e-9);
  for (const auto [i, j] : {std::pair{0, 0}, std::pair{1, 1}, std::pair{1, 2}}) {
    const double reference = tight.creepage_matrix(i, j);
    tally.largest_difference =
        std::max(tally.largest_difference, std::fabs(loose.creepage_matrix(i, j) - reference) / std::fabs(reference));
  }
  tally.iterations += loose.iterations;
  ++tally.patches;
}

}  // namespace

int main() try {
  std::vector<ContactPatch> wheel_rail, ellipses;
  for (const int target : {1000, 2000, 3000, 4700, 8000, 11000})
    for (int y_mm = -7; y_mm <= 4; ++y_mm) {
      WheelRailPatchOptions options;
      options.target_elements = target;
      wheel_rail.push_back(solve_wheel_rail_patch(default_wheel_rail_pair(), 1e-3 * y_mm, options).patch);
    }
  for (const double a_over_b : {0.2, 0.5, 1.0, 2.0, 5.0})
    for (const int target : {1000, 3000, 8000}) {
      const double a = 6e-3, b = a / a_over_b;
      ellipses.push_back(hertzian_patch(
          elliptical_contact_with_count(a, b, target, EllipseMeshLayout::rolling_resolved), a, b, 1e5, Material{}));
    }
  std::printf("tolerance  largest difference S1002/UIC60 (%zu)  ellipses (%zu)  GMRES iterations per patch (S1002/UIC60)\n",
              wheel_rail.size(), ellipses.size());
  for (const double tolerance : {1e-4, 1e-3, 2e-3, 3e-3, 5e-3, 1e-9}) {
    Tally w, e;
    for (const ContactPatch& p : wheel_rail) add(p, tolerance, w);
    for (const ContactPatch& p : ellipses) add(p, tolerance, e);
    std::printf("%9.0e  %36.1e  %14.1e  %.1f\n", tolerance, w.largest_difference, e.largest_difference,
                static_cast<double>(w.iterations) / w.patches);
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "k2_tolerance: %s\n", e.what());
  return 1;
}
