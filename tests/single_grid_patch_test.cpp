// The one contact patch of a grid's normal problem (single_grid_patch, railcontact/normal.hpp): by
// load and by approach it is the same Hertzian patch; a speck is dropped, a second patch refused,
// an approach without contact reported.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "railcontact/error.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/normal.hpp"

namespace railcontact {
namespace {

constexpr double kF3_N = 5e4;

// h of two bodies with relative curvatures A = 1/(2 R1), B = 1/(2 R2) around (x1c, x2c), plus
// `bumps`: further paraboloids of the same curvature, `depth_m` higher (lower h) at their centre.
struct Bump {
  double x1_m, x2_m, depth_m;
};
std::vector<double> gap(const Mesh& mesh, const std::vector<Bump>& bumps) {
  std::vector<double> h(mesh.size(), 1.0);
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1)
      for (const Bump& b : bumps) {
        const double d1 = mesh.x1(i1) - b.x1_m, d2 = mesh.x2(i2) - b.x2_m;
        h[mesh.index(i1, i2)] = std::min(h[mesh.index(i1, i2)], 2.0 * d1 * d1 + 1.0 * d2 * d2 - b.depth_m);
      }
  return h;
}

const Mesh kMesh = Mesh::covering(-12e-3, 12e-3, -16e-3, 16e-3, 60, 80);

TEST(SingleGridPatch, ByLoadAndByApproachGiveTheHertzianPatch) {
  const std::vector<double> h = gap(kMesh, {{0.0, 0.0, 0.0}});
  const GridPatch by_load = single_grid_patch(kMesh, h, kF3_N, Material{}, {}, "grid");
  EXPECT_NEAR(by_load.patch.normal_force_N(), kF3_N, 1e-8 * kF3_N);
  const HertzContact hertz = hertz_from_curvatures(2.0, 1.0, kF3_N, Material{});
  EXPECT_NEAR(by_load.normal.approach_m, hertz.approach_m, 0.02 * hertz.approach_m);
  EXPECT_NEAR(by_load.patch.area_m2(), M_PI * hertz.a_m * hertz.b_m, 0.05 * M_PI * hertz.a_m * hertz.b_m);
  const GridPatch by_approach =
      single_grid_patch_at_approach(kMesh, h, by_load.normal.approach_m, Material{}, {}, "grid");
  EXPECT_NEAR(by_approach.patch.normal_force_N(), kF3_N, 1e-6 * kF3_N);
  EXPECT_EQ(by_approach.patch.elements().count(), by_load.patch.elements().count());
}

TEST(SingleGridPatch, ASpeckIsDroppedASecondPatchIsRefused) {
  // A second contact 14 mm away whose top lies 12 um less than the approach below the main one's
  // (the main patch's load lowers the surface there by about 10 um): a speck of the load (15 um: 1.8 %).
  const double approach_m = hertz_from_curvatures(2.0, 1.0, kF3_N, Material{}).approach_m;
  const std::vector<double> speck = gap(kMesh, {{0.0, -5e-3, 0.0}, {0.0, 9e-3, -(approach_m - 12e-6)}});
  const GridPatch one = single_grid_patch(kMesh, speck, kF3_N, Material{}, {}, "grid");
  const std::vector<ContactRegion> regions = contact_regions(kMesh, one.normal.pressure_Pa);
  ASSERT_EQ(regions.size(), 2u);
  ASSERT_LT(regions[1].load_fraction, kSpeckLoadFraction);
  EXPECT_NEAR(one.patch.normal_force_N(), regions[0].normal_force_N, 1e-9 * kF3_N);
  EXPECT_LT(one.patch.normal_force_N(), kF3_N);

  const std::vector<double> two = gap(kMesh, {{0.0, -5e-3, 0.0}, {0.0, 9e-3, 0.0}});
  try {
    (void)single_grid_patch(kMesh, two, kF3_N, Material{}, {}, "rc_patch grid");
    FAIL() << "two equal patches";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::several_patches);
    EXPECT_NE(std::string(e.what()).find("rc_patch grid: the normal solution has 2 separate contact patches"),
              std::string::npos)
        << e.what();
  }
}

TEST(SingleGridPatch, NoContactAtTheApproachAndNonConvergenceAreReported) {
  const std::vector<double> h = gap(kMesh, {{0.0, 0.0, 0.0}});
  try {
    (void)single_grid_patch_at_approach(kMesh, h, -1e-6, Material{}, {}, "rc_patch grid");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::no_contact);
    EXPECT_NE(std::string(e.what()).find("rc_patch grid at approach -1e-06 m: no element"), std::string::npos);
  }
  NormalOptions two_iterations;
  two_iterations.max_iterations = 2;
  try {
    (void)single_grid_patch(kMesh, h, kF3_N, Material{}, two_iterations, "grid");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::not_converged);
    EXPECT_NE(std::string(e.what()).find("grid: the normal solver did not converge in 2 iterations"), std::string::npos);
  }
}

}  // namespace
}  // namespace railcontact
