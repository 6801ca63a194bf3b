// Exact steady rolling with friction: limits (linear theory, full slip), the regularised law
// against the exact one, and sign agreement of the four solvers.
#include <gtest/gtest.h>

#include <cmath>

#include "railcontact/tangential.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"
#include "carter.hpp"
#include "tangential/matrix3_eigen.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};
constexpr double kMu = 0.3, kLoad = 98100.0;

ContactPatch patch(double a, double b, int elements) {
  return hertzian_patch(elliptical_contact_with_count(a, b, elements, EllipseMeshLayout::rolling_resolved), a, b, kLoad,
                        kSteel);
}

TEST(ExactRolling, SmallCreepageEqualsLinearTheoryOfTheSamePatch) {
  const ContactPatch p = patch(6e-3, 4e-3, 1200);
  const Matrix3 K2 = solve_full_adhesion(p.elements(), kSteel).creepage_matrix;
  for (const Creepage c : {Creepage{2e-6, 0, 0}, Creepage{0, 2e-6, 0}, Creepage{0, 0, 2e-3}, Creepage{1e-6, -1e-6, 1e-3}}) {
    const RollingSolution s = solve_rolling_exact(p, c, kMu);
    const Eigen::Vector3d linear = detail::to_eigen(K2) * Eigen::Vector3d(c.xi, c.eta, c.phi);
    const double scale = std::hypot(linear(0), linear(1));
    EXPECT_NEAR(s.forces.F1_N, linear(0), 0.005 * scale);
    EXPECT_NEAR(s.forces.F2_N, linear(1), 0.005 * scale);
    EXPECT_NEAR(s.forces.M3_Nm, linear(2), 0.005 * std::fabs(linear(2)) + 1e-12);
    EXPECT_GT(s.adhesion_fraction, 0.95);
  }
}

TEST(ExactRolling, LargeCreepageSaturatesAtMuTimesNormalForce) {
  const ContactPatch p = patch(6e-3, 4e-3, 1200);
  for (const Creepage c : {Creepage{0.02, 0, 0}, Creepage{0, -0.02, 0}, Creepage{0.015, 0.015, 0}}) {
    const RollingSolution s = solve_rolling_exact(p, c, kMu);
    EXPECT_NEAR(std::hypot(s.forces.F1_N, s.forces.F2_N), kMu * p.normal_force_N(), 2e-3 * kMu * p.normal_force_N());
    // Opposite to the creepage.
    EXPECT_LT(s.forces.F1_N * c.xi + s.forces.F2_N * c.eta, 0.0);
    EXPECT_LT(s.adhesion_fraction, 0.01);
  }
}

// Inexact Newton (each GMRES solve only as tight as the Newton residual warrants) converges to
// the same solution as solving every step to krylov_tolerance, with far fewer GMRES iterations.
TEST(ExactRolling, InexactNewtonGivesTheSameSolutionWithFewerKrylovIterations) {
  const ContactPatch p = patch(6e-3, 4e-3, 1200);
  RollingOptions fixed;
  fixed.inexact_newton = false;
  int inexact_iterations = 0, fixed_iterations = 0;
  for (const Creepage c : {Creepage{5e-4, 5e-4, 0.5}, Creepage{1e-4, 0, 0}, Creepage{0, 0, 2.0}, Creepage{2e-3, -1e-3, 0}}) {
    const RollingSolution inexact = solve_rolling_exact(p, c, kMu);
    const RollingSolution tight = solve_rolling_exact(p, c, kMu, fixed);
    const double scale = kMu * p.normal_force_N();
    EXPECT_NEAR(inexact.forces.F1_N, tight.forces.F1_N, 1e-8 * scale);
    EXPECT_NEAR(inexact.forces.F2_N, tight.forces.F2_N, 1e-8 * scale);
    EXPECT_NEAR(inexact.forces.M3_Nm, tight.forces.M3_Nm, 1e-8 * scale * 6e-3);
    EXPECT_LE(inexact.residual, RollingOptions{}.tolerance);
    inexact_iterations += inexact.krylov_iterations;
    fixed_iterations += tight.krylov_iterations;
  }
  // 373 against 587 in the native build, 445 against 595 without FMA (the sanitizer build): the
  // rounding moves the iteration counts; on these small patches the saving is smaller than on the
  // wheel-rail patches of docs/BENCHMARKS.md (about half).
  EXPECT_LT(inexact_iterations, 0.85 * fixed_iterations) << inexact_iterations << " against " << fixed_iterations;
}

// Small creepages, mostly adhesion: the clipped starting guess puts the few slipping elements on
// the kink of the Newton function, where the Newton step need not descend. Before the line search
// fell back to the full step, these stalled (Newton did not converge in 100 iterations).
TEST(ExactRolling, ConvergesWhereTheLineSearchFindsNoDescent) {
  for (const bool inexact_newton : {false, true}) {
    RollingOptions options;
    options.inexact_newton = inexact_newton;
    const ContactPatch p = patch(6e-3, 4e-3, 1200);
    for (const Creepage c : {Creepage{1e-4, 0, 0}, Creepage{5e-5, 1e-4, 0}}) {
      const RollingSolution s = solve_rolling_exact(p, c, kMu, options);
      EXPECT_LE(s.residual, options.tolerance);
      // Mostly adhesion, so close to the linear theory of the same patch (within the slip's share).
      EXPECT_GT(s.adhesion_fraction, 0.8);
      EXPECT_LT(s.forces.F1_N * c.xi + s.forces.F2_N * c.eta, 0.0);
    }
    const ContactPatch small = patch(6e-3, 6e-3, 300);
    const RollingSolution s = solve_rolling_exact(small, Creepage{2e-5, 1e-4, 0}, kMu, options);
    EXPECT_LE(s.residual, options.tolerance);
  }
}

TEST(ExactRolling, SolutionSatisfiesCoulombsLawElementByElement) {
  const ContactPatch p = patch(6e-3, 6e-3, 1200);
  const RollingSolution s = solve_rolling_exact(p, {8e-4, 3e-4, 0.4}, kMu);
  ASSERT_LE(s.residual, RollingOptions{}.tolerance);
  int slipping = 0;
  for (std::size_t e = 0; e < p.elements().count(); ++e) {
    const double bound = kMu * p.pressure_Pa()[e];
    const double traction = std::hypot(s.p1_Pa[e], s.p2_Pa[e]);
    const double slip = std::hypot(s.s1[e], s.s2[e]);
    EXPECT_LE(traction, bound * (1 + 1e-8) + 1e-6);
    if (s.slip[e]) {
      ++slipping;
      EXPECT_NEAR(traction, bound, 1e-7 * bound);
      if (slip > 1e-9) EXPECT_LT((s.p1_Pa[e] * s.s1[e] + s.p2_Pa[e] * s.s2[e]) / (traction * slip), -0.999);
    } else {
      EXPECT_LT(slip, 1e-9);
    }
  }
  EXPECT_GT(slipping, 50);
  EXPECT_LT(slipping, static_cast<int>(p.elements().count()) - 50);
}

// Partial slip against an independent closed form: on a patch 20 times wider than long with the
// 2-D Hertz pressure on every strip, the centre strip is Carter's two-dimensional contact
// (tests/carter.hpp): its force per unit width and the length of its adhesion zone at the
// leading edge. Measured: +0.7 % (40 elements along X1; +0.4 % at twice the width and resolution).
TEST(ExactRolling, WideContactReproducesCartersTwoDimensionalSolution) {
  const testing::CarterContact carter = testing::carter_contact(1e-3, 20e-3, 40, 101, kSteel, kMu);
  const ContactPatch& p = carter.patch;
  const Mesh& mesh = p.mesh();
  double strip_load = 0.0;  // discrete normal load per unit width of the centre strip
  for (int i1 = 0; i1 < mesh.n1; ++i1) strip_load += p.pressure_Pa()[static_cast<std::size_t>(carter.centre_strip * mesh.n1 + i1)] * mesh.dx1_m;
  for (double r : {0.25, 0.5, 0.75}) {
    const RollingSolution s = solve_rolling_exact(p, {r * carter.xi_c, 0, 0}, kMu);
    ASSERT_LE(s.residual, RollingOptions{}.tolerance);
    double force = 0.0, adhesion_m = 0.0, adhesion_leading_m = -1.0;
    for (std::size_t e = 0; e < p.elements().count(); ++e) {
      if (static_cast<int>(p.elements().indices()[e] / static_cast<std::size_t>(mesh.n1)) != carter.centre_strip) continue;
      force += s.p1_Pa[e] * mesh.dx1_m;
      if (!s.slip[e]) {
        adhesion_m += mesh.dx1_m;
        adhesion_leading_m = std::max(adhesion_leading_m, p.x1(e));
      }
    }
    const double carter_force = -kMu * strip_load * testing::carter_force_ratio(r);
    EXPECT_NEAR(force, carter_force, 0.012 * std::fabs(carter_force)) << "xi/xi_c = " << r;
    EXPECT_NEAR(adhesion_m, 2.0 * carter.a_m * (1.0 - r), 1.01 * mesh.dx1_m) << "xi/xi_c = " << r;
    EXPECT_GT(adhesion_leading_m, p.x1(p.elements().count() - 1) - 1.5 * mesh.dx1_m);  // at the leading edge
  }
}

TEST(RegularisedRolling, ApproachesExactAsEpsilonDecreases) {
  const ContactPatch p = patch(6e-3, 4e-3, 800);
  const Creepage c{6e-4, 2e-4, 0.3};
  const RollingSolution exact = solve_rolling_exact(p, c, kMu);
  const double F = std::hypot(exact.forces.F1_N, exact.forces.F2_N);
  double previous = 1e300;
  for (double eps : {1e-5, 1e-6, 1e-7, 1e-8}) {
    RollingOptions o;
    o.regularisation = eps;
    const RollingSolution r = solve_rolling_regularised(p, c, kMu, o);
    const double difference = std::hypot(r.forces.F1_N - exact.forces.F1_N, r.forces.F2_N - exact.forces.F2_N) / F;
    EXPECT_LT(difference, previous) << eps;
    previous = difference;
  }
  EXPECT_LT(previous, 1e-4);
}

TEST(RollingSolvers, AllFourAgreeOnTheSigns) {
  const double a = 6e-3, b = 4e-3;
  const ContactPatch p = patch(a, b, 1000);
  const FastSim fastsim(p);
  const Flexibility nh = nh_fastsim_flexibility(fastsim, solve_full_adhesion(p.elements(), kSteel).creepage_matrix);
  const Flexibility original = fastsim_flexibility(a, b, kSteel);
  for (const Creepage c : {Creepage{1e-3, 0, 0}, Creepage{-1e-3, 0, 0}, Creepage{0, 1e-3, 0}, Creepage{0, -5e-4, 0},
                           Creepage{0, 0, 1.0}, Creepage{0, 0, -1.0}, Creepage{5e-4, 5e-4, 0.5}}) {
    const TangentialForces forces[] = {fastsim.forces(c, nh, kMu), fastsim.forces(c, original, kMu),
                                       solve_rolling_exact(p, c, kMu).forces,
                                       solve_rolling_regularised(p, c, kMu).forces};
    const double F3 = p.normal_force_N();
    for (const TangentialForces& f : forces) {
      auto sign = [F3](double v, double scale) { return std::fabs(v) < 1e-6 * scale ? 0 : (v > 0 ? 1 : -1); };
      EXPECT_EQ(sign(f.F1_N, F3), sign(forces[2].F1_N, F3));
      EXPECT_EQ(sign(f.F2_N, F3), sign(forces[2].F2_N, F3));
      EXPECT_EQ(sign(f.M3_Nm, F3 * a), sign(forces[2].M3_Nm, F3 * a));
    }
    // Kalker's convention: F1 opposes xi, F2 opposes eta, and spin alone gives F2 = -f23 phi < 0 for phi > 0.
    if (c.xi != 0) EXPECT_LT(forces[2].F1_N * c.xi, 0);
    if (c.eta != 0 && c.phi == 0) EXPECT_LT(forces[2].F2_N * c.eta, 0);
    if (c.phi != 0 && c.xi == 0 && c.eta == 0) {
      EXPECT_LT(forces[2].F2_N * c.phi, 0);
      EXPECT_LT(forces[2].M3_Nm * c.phi, 0);
    }
  }
}

// A patch one element long (three elements across: a patch that has just appeared on a flange
// flank) has no element behind in its own mesh; its λ comes from a mesh two elements long. The
// exact and regularised solvers give the forces of the same elements embedded in a mesh three
// elements long with empty rows around them (another mesh, the same elements: within 1e-9 of μ F3).
TEST(ExactRolling, APatchOneElementLongEqualsItInALongerMesh) {
  Mesh row;
  row.n1 = 1;
  row.n2 = 3;
  row.dx1_m = row.dx2_m = 0.2e-3;
  row.x1_first_m = 0.0;
  row.x2_first_m = -0.2e-3;
  const std::vector<double> pressure{4e8, 8e8, 4e8};
  Mesh longer = row;
  longer.n1 = 3;
  longer.x1_first_m = -0.2e-3;
  std::vector<double> embedded(longer.size(), 0.0);
  for (int i2 = 0; i2 < 3; ++i2) embedded[longer.index(1, i2)] = pressure[static_cast<std::size_t>(i2)];
  const ContactPatch single(row, pressure, kSteel), wide(longer, embedded, kSteel);
  const Creepage creepage{3e-4, 0.0, 0.04};
  const double F3 = single.normal_force_N();
  const RollingSolution a = solve_rolling_exact(single, creepage, kMu);
  const RollingSolution b = solve_rolling_exact(wide, creepage, kMu);
  EXPECT_TRUE(std::isfinite(a.forces.F1_N));
  EXPECT_GT(std::abs(a.forces.F1_N), 0.01 * kMu * F3);
  EXPECT_NEAR(a.forces.F1_N, b.forces.F1_N, 1e-9 * kMu * F3);
  EXPECT_NEAR(a.forces.F2_N, b.forces.F2_N, 1e-9 * kMu * F3);
  const RollingSolution c = solve_rolling_regularised(single, creepage, kMu);
  const RollingSolution d = solve_rolling_regularised(wide, creepage, kMu);
  EXPECT_NEAR(c.forces.F1_N, d.forces.F1_N, 1e-9 * kMu * F3);
}

TEST(ExactRolling, RejectsBadInputAndReportsNonConvergence) {
  const ContactPatch p = patch(6e-3, 4e-3, 300);
  EXPECT_THROW(solve_rolling_exact(p, {1e-3, 0, 0}, 0.0), Error);
  EXPECT_THROW(solve_rolling_exact(p, {1e-3, 0, 0}, std::nan("")), Error);
  EXPECT_THROW(solve_rolling_exact(p, {std::nan(""), 0, 0}, 0.3), Error);
  EXPECT_THROW(solve_rolling_regularised(p, {1e-3, 0, 0}, -0.3), Error);
  RollingOptions o;
  o.max_newton_iterations = 1;
  o.tolerance = 1e-14;
  EXPECT_THROW(solve_rolling_exact(p, {1e-3, 0, 0.5}, 0.3, o), Error);
  o = RollingOptions{};
  o.regularisation = 0.0;
  EXPECT_THROW(solve_rolling_regularised(p, {1e-3, 0, 0}, 0.3, o), Error);
}

}  // namespace
}  // namespace railcontact
