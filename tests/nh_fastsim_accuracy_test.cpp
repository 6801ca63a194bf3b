// nH-FastSim's creep forces against the exact solver in partial slip (docs/FASTSIM.md §6,
// docs/VALIDATION.md §2-3): railcontact's skewed traction bound on Hertzian ellipses over a wide
// range of a/b, and on the S1002/UIC60 patch near the two-point contact (y = -0.5 mm), where the
// paper's parabolic bound (Eq 1) is at its worst.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "railcontact/tangential.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {
namespace {

constexpr double kMu = 0.3;

double magnitude(const TangentialForces& f) { return std::hypot(f.F1_N, f.F2_N); }

struct Errors {
  double ours = 0.0, paper = 0.0;  // largest |F - F_exact| / F_exact: skewed bound, parabola
  double ours_default = 0.0;       // skewed bound, flexibilities as case runs compute them (coarsened)
};

// Largest error over the normalised creepages (Eq 22-23 with f11, f22 of the patch's K2) of the
// three families of the paper's Fig 5 at levels 0.25, 0.5, 0.75, with the spin `phi` in B and C.
Errors worst_errors(const ContactPatch& patch, double phi) {
  const Matrix3 K2 = solve_full_adhesion(patch.elements(), patch.material()).creepage_matrix;
  const FastSim ours(patch), paper(patch, TractionBound::parabolic());
  const Flexibility L = nh_fastsim_flexibility(ours, K2);
  const Flexibility L_default = NhFastSim(patch).flexibility();  // the default recipe
  const double unit = 3.0 * kMu * patch.normal_force_N();
  Errors worst;
  for (double level : {0.25, 0.5, 0.75}) {
    const double xi = level * unit / -K2(0, 0), eta = level * unit / -K2(1, 1);
    for (const Creepage& c : {Creepage{xi, 0, 0}, Creepage{0, eta, phi}, Creepage{xi, eta, phi}}) {
      const RollingSolution exact = solve_rolling_exact(patch, c, kMu);
      EXPECT_LE(exact.residual, RollingOptions{}.tolerance);
      const double F = magnitude(exact.forces);
      worst.ours = std::max(worst.ours, std::fabs(magnitude(ours.forces(c, L, kMu)) / F - 1.0));
      worst.paper = std::max(worst.paper, std::fabs(magnitude(paper.forces(c, L, kMu)) / F - 1.0));
      worst.ours_default = std::max(worst.ours_default, std::fabs(magnitude(ours.forces(c, L_default, kMu)) / F - 1.0));
    }
  }
  return worst;
}

// The default skew was chosen on ellipses a/b = 0.1 ... 10 (largest error 3.0 %, parabola 6.2 %);
// here three of them at a coarser mesh, with a small spin in families B and C.
TEST(NhFastSimAccuracy, WithinThreeAndAHalfPercentOfExactOnEllipses) {
  const Material steel{2.1e11, 0.3};
  for (double a_over_b : {0.2, 1.0, 5.0}) {
    const double c = 6e-3, a = c * std::sqrt(a_over_b), b = c / std::sqrt(a_over_b);
    const ContactPatch patch = hertzian_patch(
        elliptical_contact_with_count(a, b, 1500, EllipseMeshLayout::rolling_resolved), a, b, 98100.0, steel);
    const Errors e = worst_errors(patch, 0.1);
    std::cout << "  a/b = " << a_over_b << ": largest error " << 100 * e.ours << " % (parabola " << 100 * e.paper
              << " %)\n";
    EXPECT_LT(e.ours, 0.035) << "a/b = " << a_over_b;
  }
}

// The paper's Fig 5 set-up at y = -0.5 mm: the parabola's error exceeds 5 %, railcontact's bound
// stays below the paper's 4 %.
TEST(NhFastSimAccuracy, BeatsTheParabolicBoundNearTheTwoPointContact) {
  WheelRailPatchOptions options;
  options.target_elements = 3000;
  const WheelRailPatch wr = solve_wheel_rail_patch(default_wheel_rail_pair(), -0.5e-3, options);
  const Errors e = worst_errors(wr.patch, wr.spin_per_m);
  std::cout << "  y = -0.5 mm: largest error " << 100 * e.ours << " % (parabola " << 100 * e.paper
            << " %, default coarsened flexibilities " << 100 * e.ours_default << " %)\n";
  EXPECT_LT(e.ours, 0.04);
  EXPECT_GT(e.paper, 0.05);
  EXPECT_EQ(NhFastSim::automatic_coarsening(wr.patch), 3);  // 3000 elements: a coarse patch of ~330
  EXPECT_LT(e.ours_default, 0.04);
}

// The automatic coarsening keeps at least 250 coarse elements, and coarsens by 2 from 400.
TEST(NhFastSimFlexibility, AutomaticCoarseningKeepsAtLeast250Elements) {
  const Material steel{2.1e11, 0.3};
  const double a = 6e-3, b = 4e-3;
  for (auto [elements, expected] : {std::pair{300, 1}, {600, 2}, {1200, 2}, {3000, 3}, {5000, 4}, {12000, 6}}) {
    const ContactPatch patch =
        hertzian_patch(elliptical_contact_with_count(a, b, elements), a, b, 98100.0, steel);
    const int factor = NhFastSim::automatic_coarsening(patch);
    EXPECT_EQ(factor, expected) << patch.elements().count() << " elements";
    if (factor > 2) EXPECT_GE(coarsened(patch, factor).elements().count(), 240u);
  }
}

}  // namespace
}  // namespace railcontact
