// The tangential models' one seam (TangentialModel, railcontact/tangential_model.hpp): each
// TangentialSolver prepares the model the method defines (checked against the building blocks
// called directly, to a stated tolerance), per lobe on a patch of two lobes, Eq 9's fallback on a
// patch too small for K2, given flexibilities; the equivalent ellipse against Hertz's; bad options.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "railcontact/error.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/tangential_model.hpp"

namespace railcontact {
namespace {

constexpr double kMu = 0.3;
constexpr double kF3_N = 1e5;

// A Hertzian ellipse of 6 x 4 mm with about `elements` elements in contact.
ContactPatch ellipse_patch(int elements = 1200) {
  return hertzian_patch(elliptical_contact_with_count(6e-3, 4e-3, elements, EllipseMeshLayout::rolling_resolved),
                        6e-3, 4e-3, kF3_N, Material{});
}

// Two Hertzian lobes 9 mm apart across the rolling direction on one 0.25 mm mesh (as a tread and a
// flange-root patch merged by the wheel-rail stage).
ContactPatch two_lobe_patch() {
  const Mesh mesh = Mesh::covering(-6e-3, 6e-3, -8e-3, 7e-3, 48, 60);
  std::vector<double> p(mesh.size(), 0.0);
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const double x1 = mesh.x1(i1), x2 = mesh.x2(i2);
      const double big = 1.0 - std::pow(x1 / 5e-3, 2) - std::pow((x2 + 4.5e-3) / 3e-3, 2);
      const double small = 1.0 - std::pow(x1 / 3e-3, 2) - std::pow((x2 - 4.5e-3) / 2e-3, 2);
      if (big > 0.0) p[mesh.index(i1, i2)] = 1e9 * std::sqrt(big);
      if (small > 0.0) p[mesh.index(i1, i2)] = 8e8 * std::sqrt(small);
    }
  return ContactPatch(mesh, p, Material{});
}

TangentialModelOptions options_for(TangentialSolver solver) {
  TangentialModelOptions o;
  o.solver = solver;
  return o;
}

// Forces of two code paths agree to this fraction of mu F3 (the same arithmetic, perhaps in another
// order).
void expect_same_forces(const TangentialForces& a, const TangentialForces& b, double mu_F3_N) {
  EXPECT_NEAR(a.F1_N, b.F1_N, 1e-12 * mu_F3_N);
  EXPECT_NEAR(a.F2_N, b.F2_N, 1e-12 * mu_F3_N);
  EXPECT_NEAR(a.M3_Nm, b.M3_Nm, 1e-12 * mu_F3_N * 1e-2);
}

const Creepage kCreepage{1.5e-3, -1e-3, 0.3};

TEST(TangentialModel, EachSolverIsItsMethod) {
  const ContactPatch patch = ellipse_patch();
  const double muF3 = kMu * patch.normal_force_N();

  const TangentialModel nh(patch, options_for(TangentialSolver::nh_fastsim));
  const NhFastSim direct_nh(patch);
  expect_same_forces(nh.solve(kCreepage, kMu).forces, direct_nh.solve(kCreepage, kMu).forces, muF3);
  ASSERT_TRUE(nh.flexibility().has_value());
  EXPECT_EQ(nh.flexibility()->L1, direct_nh.flexibility().L1);
  ASSERT_NE(nh.nh_fastsim(), nullptr);
  EXPECT_EQ(nh.nh_fastsim_per_lobe(), nullptr);
  EXPECT_EQ(nh.preparation_krylov_iterations(), direct_nh.krylov_iterations());
  EXPECT_EQ(nh.flexibility_source(), "K2 of the patch coarsened by 2");

  // Classic FastSim: Eq 9 of the given ellipse, the parabolic bound (Eq 1).
  TangentialModelOptions classic = options_for(TangentialSolver::fastsim);
  classic.ellipse_semi_axes_m = std::array<double, 2>{6e-3, 4e-3};
  const TangentialModel fastsim(patch, classic);
  const Flexibility eq9 = fastsim_flexibility(6e-3, 4e-3, patch.material());
  expect_same_forces(fastsim.solve(kCreepage, kMu).forces,
                     FastSim(patch, TractionBound::parabolic()).solve(kCreepage, eq9, kMu).forces, muF3);
  EXPECT_EQ(fastsim.flexibility()->L3, eq9.L3);
  EXPECT_EQ(fastsim.flexibility_source(), "Eq 9");
  EXPECT_EQ(fastsim.nh_fastsim(), nullptr);

  for (TangentialSolver s : {TangentialSolver::exact, TangentialSolver::exact_regularised}) {
    const TangentialModel exact(patch, options_for(s));
    const TangentialSolution t = exact.solve(kCreepage, kMu, TangentialOutput::forces);
    const RollingSolution r = s == TangentialSolver::exact ? solve_rolling_exact(patch, kCreepage, kMu)
                                                          : solve_rolling_regularised(patch, kCreepage, kMu);
    expect_same_forces(t.forces, r.forces, muF3);
    EXPECT_EQ(t.newton_iterations, r.newton_iterations);
    EXPECT_EQ(t.p1_Pa.size(), patch.elements().count()) << "the exact solvers give the fields always";
    EXPECT_FALSE(exact.flexibility().has_value());
    EXPECT_EQ(exact.solver(), s);
  }
}

TEST(TangentialModel, ForcesAloneAreTheForcesOfTheFields) {
  const ContactPatch patch = ellipse_patch();
  const double muF3 = kMu * patch.normal_force_N();
  for (TangentialSolver s : {TangentialSolver::nh_fastsim, TangentialSolver::fastsim}) {
    const TangentialModel model(patch, options_for(s));
    const TangentialSolution forces = model.solve(kCreepage, kMu, TangentialOutput::forces);
    const TangentialSolution fields = model.solve(kCreepage, kMu, TangentialOutput::fields);
    expect_same_forces(forces.forces, fields.forces, muF3);
    EXPECT_EQ(forces.adhesion_fraction, fields.adhesion_fraction);
    const TangentialSolution only = model.solve(kCreepage, kMu, TangentialOutput::forces_only);
    expect_same_forces(only.forces, fields.forces, muF3);
    EXPECT_EQ(only.adhesion_fraction, 0.0);
    EXPECT_TRUE(forces.p1_Pa.empty());
    ASSERT_EQ(fields.p1_Pa.size(), patch.elements().count());
    // The fields sum to the forces (F = S sum p).
    double F1 = 0.0;
    for (double p : fields.p1_Pa) F1 += p * patch.mesh().element_area_m2();
    EXPECT_NEAR(F1, fields.forces.F1_N, 1e-9 * muF3);
    EXPECT_GT(fields.adhesion_fraction, 0.0);
    EXPECT_LT(fields.adhesion_fraction, 1.0);
  }
}

TEST(TangentialModel, StripCreepagesOfOneCreepageGiveItsSolution) {
  // Every strip with (xi - phi x2, eta, phi) is the planar creepage (FastSim::solve(StripCreepages)).
  const ContactPatch patch = ellipse_patch();
  const Mesh& m = patch.mesh();
  StripCreepages strips(static_cast<std::size_t>(m.n2));
  for (int i2 = 0; i2 < m.n2; ++i2)
    strips[static_cast<std::size_t>(i2)] = {kCreepage.xi - kCreepage.phi * m.x2(i2), kCreepage.eta, kCreepage.phi};
  for (TangentialSolver s : kTangentialSolvers) {
    const TangentialModel model(patch, options_for(s));
    const TangentialForces a = model.solve(kCreepage, kMu).forces, b = model.solve(strips, kMu).forces;
    // The exact solvers converge to 1e-9 of mu max p3 each way.
    const double tolerance = (s == TangentialSolver::exact || s == TangentialSolver::exact_regularised ? 1e-6 : 1e-9) *
                             kMu * patch.normal_force_N();
    EXPECT_NEAR(a.F1_N, b.F1_N, tolerance) << solver_name(s);
    EXPECT_NEAR(a.F2_N, b.F2_N, tolerance) << solver_name(s);
  }
  StripCreepages too_few(strips.begin(), strips.end() - 1);
  EXPECT_THROW((void)TangentialModel(patch, options_for(TangentialSolver::nh_fastsim)).solve(too_few, kMu), Error);
}

TEST(TangentialModel, TwoLobesAreSolvedPerLobeUnlessAskedNot) {
  const ContactPatch patch = two_lobe_patch();
  const double muF3 = kMu * patch.normal_force_N();
  const TangentialModel per_lobe(patch, options_for(TangentialSolver::nh_fastsim));
  ASSERT_NE(per_lobe.nh_fastsim_per_lobe(), nullptr);
  EXPECT_EQ(per_lobe.nh_fastsim(), nullptr);
  EXPECT_EQ(per_lobe.flexibility_source(), "K2 of each of its 2 lobes (the most loaded one's shown)");
  const NhFastSimPerLobe direct(patch);
  expect_same_forces(per_lobe.solve(kCreepage, kMu).forces, direct.solve(kCreepage, kMu).forces, muF3);
  EXPECT_EQ(per_lobe.preparation_krylov_iterations(), direct.krylov_iterations());

  TangentialModelOptions whole = options_for(TangentialSolver::nh_fastsim);
  whole.per_lobe = false;
  const TangentialModel one(patch, whole);
  ASSERT_NE(one.nh_fastsim(), nullptr);
  expect_same_forces(one.solve(kCreepage, kMu).forces, NhFastSim(patch).solve(kCreepage, kMu).forces, muF3);
  // The two differ: one set of flexibilities for two lobes is what per lobe corrects.
  EXPECT_GT(std::abs(one.solve(kCreepage, kMu).forces.F2_N - per_lobe.solve(kCreepage, kMu).forces.F2_N), 1e-3 * muF3);
}

TEST(TangentialModel, APatchTooSmallForK2TakesItsEquivalentEllipse) {
  const ContactPatch patch = ellipse_patch(12);
  ASSERT_LT(patch.elements().count(), 20u);
  const TangentialModel model(patch, options_for(TangentialSolver::nh_fastsim));
  EXPECT_EQ(model.nh_fastsim(), nullptr);
  EXPECT_EQ(model.flexibility_source(), "Eq 9 (too few elements for K2)");
  const std::array<double, 2> ab = equivalent_ellipse_semi_axes(patch);
  const Flexibility eq9 = fastsim_flexibility(ab[0], ab[1], patch.material());
  EXPECT_EQ(model.flexibility()->L2, eq9.L2);
  // nH-FastSim's bound (skewed), not classic FastSim's parabola.
  expect_same_forces(model.solve(kCreepage, kMu).forces, FastSim(patch).solve(kCreepage, eq9, kMu).forces,
                     kMu * patch.normal_force_N());
}

TEST(TangentialModel, GivenFlexibilitiesAreUsedAsGiven) {
  const ContactPatch patch = ellipse_patch();
  const NhFastSim on_the_fly(patch);
  TangentialModelOptions o = options_for(TangentialSolver::nh_fastsim);
  o.given_flexibilities = on_the_fly.flexibilities();
  o.given_flexibilities->flexibility.L1 *= 2.0;
  const TangentialModel given(patch, o);
  EXPECT_EQ(given.flexibility_source(), "given");
  EXPECT_EQ(given.preparation_krylov_iterations(), 0);
  EXPECT_EQ(given.flexibility()->L1, 2.0 * on_the_fly.flexibility().L1);
  // Small creepage, full adhesion: F1 = -(S D B)_11 xi / L1 (Eq 19), half of the model on the fly's.
  const Creepage small{1e-6, 0.0, 0.0};
  EXPECT_NEAR(given.solve(small, kMu).forces.F1_N, 0.5 * on_the_fly.solve(small, kMu).forces.F1_N,
              1e-9 * std::abs(on_the_fly.solve(small, kMu).forces.F1_N));
}

TEST(TangentialModel, TheEquivalentEllipseOfAnEllipseIsNearlyItself) {
  // The box of an ellipse's elements is 2a x 2b to an element; the area is the discrete one.
  const ContactPatch patch = ellipse_patch(4000);
  const std::array<double, 2> ab = equivalent_ellipse_semi_axes(patch);
  EXPECT_NEAR(ab[0], 6e-3, 0.03 * 6e-3);
  EXPECT_NEAR(ab[1], 4e-3, 0.03 * 4e-3);
  EXPECT_NEAR(M_PI * ab[0] * ab[1], patch.area_m2(), 1e-12 * patch.area_m2());
  EXPECT_THROW((void)equivalent_ellipse_semi_axes(ContactPatch{}), Error);
}

// The table-driven model: a StoredPatch of the lobes NhFastSimPerLobe cut, with their flexibilities
// and centres, is NhFastSimPerLobe's solution (each lobe's FastSim with its stored flexibilities).
StoredPatch stored_lobes_of(const NhFastSimPerLobe& per_lobe) {
  StoredPatch stored;
  for (std::size_t k = 0; k < per_lobe.lobe_count(); ++k) {
    const NhFastSimPerLobe::LobeView lobe = per_lobe.lobe(k);
    stored.lobes.push_back({lobe.patch, lobe.flexibility, lobe.x1_centre_m, lobe.x2_centre_m, lobe.coupling});
  }
  return stored;
}

TEST(TangentialModel, AStoredPatchIsSolvedAsPerLobe) {
  const ContactPatch patch = two_lobe_patch();
  const double muF3 = kMu * patch.normal_force_N();
  const NhFastSimPerLobe per_lobe(patch);
  ASSERT_EQ(per_lobe.lobe_count(), 2u);
  const TangentialModel stored(stored_lobes_of(per_lobe), options_for(TangentialSolver::nh_fastsim));
  EXPECT_EQ(stored.flexibility_source(), "given for each of its 2 lobes");
  EXPECT_EQ(stored.flexibility()->L1, per_lobe.flexibility().L1);
  for (const Creepage& c : {kCreepage, Creepage{-2e-3, 1e-3, -0.5}, Creepage{1e-5, 0.0, 0.0}}) {
    const TangentialSolution a = stored.solve(c, kMu, TangentialOutput::forces);
    const FastSimResult b = per_lobe.solve(c, kMu);
    expect_same_forces(a.forces, b.forces, muF3);
    expect_same_forces(stored.solve(c, kMu, TangentialOutput::forces_only).forces, b.forces, muF3);
    EXPECT_NEAR(a.adhesion_fraction, b.adhesion_fraction, 1e-12);
  }
  // Several lobes are separate copies: no fields, no strip creepages.
  EXPECT_THROW((void)stored.solve(kCreepage, kMu, TangentialOutput::fields), Error);
  EXPECT_THROW((void)stored.solve(StripCreepages(3, kCreepage), kMu), Error);

  // Blended with the whole patch (weight w): (1 − w) per lobe + w whole, the whole patch's
  // flexibilities those of nH-FastSim on it.
  StoredPatch blended = stored_lobes_of(per_lobe);
  const NhFastSim whole(patch);
  blended.whole = StoredLobe{patch, whole.flexibility(), 0.0, 0.0, whole.coupling()};
  blended.whole_patch_weight = 0.25;
  const TangentialForces f = TangentialModel(blended, options_for(TangentialSolver::nh_fastsim)).solve(kCreepage, kMu, TangentialOutput::forces).forces;
  const TangentialForces lobes = per_lobe.solve(kCreepage, kMu).forces, one = whole.solve(kCreepage, kMu).forces;
  EXPECT_NEAR(f.F2_N, 0.75 * lobes.F2_N + 0.25 * one.F2_N, 1e-12 * muF3);
  EXPECT_NEAR(f.M3_Nm, 0.75 * lobes.M3_Nm + 0.25 * one.M3_Nm, 1e-14 * muF3);
}

TEST(TangentialModel, AStoredPatchOfOneLobeIsFastSimWithItsFlexibilities) {
  const ContactPatch patch = ellipse_patch();
  const double muF3 = kMu * patch.normal_force_N();
  const NhFastSim nh(patch);
  StoredPatch one;
  one.lobes.push_back({patch, nh.flexibility(), 0.0, 0.0, nh.coupling()});
  const TangentialModel stored(one, options_for(TangentialSolver::nh_fastsim));
  EXPECT_EQ(stored.flexibility_source(), "given");
  const TangentialSolution fields = stored.solve(kCreepage, kMu, TangentialOutput::fields);
  expect_same_forces(fields.forces, nh.solve(kCreepage, kMu).forces, muF3);
  ASSERT_EQ(fields.p1_Pa.size(), patch.elements().count());
}

TEST(TangentialModel, StripForcesSumToTheForcesOnEveryPath) {
  // Each strip's sums of traction (TangentialOutput::strip_forces): FastSim's own march (fastsim,
  // a stored patch) or the fields summed per column (nh-fastsim, exact) add up to F1, F2.
  const ContactPatch patch = ellipse_patch(800);
  const Mesh& m = patch.mesh();
  const double muF3 = kMu * patch.normal_force_N();
  StripCreepages strips(static_cast<std::size_t>(m.n2));
  for (int i2 = 0; i2 < m.n2; ++i2)
    strips[static_cast<std::size_t>(i2)] = {kCreepage.xi - kCreepage.phi * m.x2(i2) + 1e-4 * m.x2(i2) / 4e-3,
                                            kCreepage.eta, kCreepage.phi};
  StoredPatch one;
  one.lobes.push_back({patch, NhFastSim(patch).flexibility(), 0.0, 0.0});
  const std::vector<TangentialModel> models{TangentialModel(patch, options_for(TangentialSolver::fastsim)),
                                            TangentialModel(one, options_for(TangentialSolver::nh_fastsim)),
                                            TangentialModel(patch, options_for(TangentialSolver::nh_fastsim)),
                                            TangentialModel(patch, options_for(TangentialSolver::exact))};
  for (const TangentialModel& model : models) {
    const TangentialSolution s = model.solve(strips, kMu, TangentialOutput::strip_forces);
    const TangentialSolution fields = model.solve(strips, kMu, TangentialOutput::fields);
    ASSERT_EQ(s.strip_F1_N.size(), strips.size()) << solver_name(model.solver());
    EXPECT_TRUE(s.p1_Pa.empty());
    double F1 = 0.0, F2 = 0.0;
    for (std::size_t j = 0; j < strips.size(); ++j) {
      F1 += s.strip_F1_N[j];
      F2 += s.strip_F2_N[j];
    }
    const double tolerance = (model.solver() == TangentialSolver::exact ? 1e-6 : 1e-9) * muF3;
    EXPECT_NEAR(F1, fields.forces.F1_N, tolerance) << solver_name(model.solver());
    EXPECT_NEAR(F2, fields.forces.F2_N, tolerance) << solver_name(model.solver());
    EXPECT_NEAR(s.adhesion_fraction, fields.adhesion_fraction, 1e-12) << solver_name(model.solver());
    EXPECT_GT(s.adhesion_fraction, 0.0);
  }
  // The stored patch and nh-fastsim have the same flexibilities: the same strips' sums.
  const TangentialSolution a = models[1].solve(strips, kMu, TangentialOutput::strip_forces);
  const TangentialSolution b = models[2].solve(strips, kMu, TangentialOutput::strip_forces);
  for (std::size_t j = 0; j < strips.size(); ++j) EXPECT_NEAR(a.strip_F2_N[j], b.strip_F2_N[j], 1e-9 * muF3);
}

// The message of the Error (invalid_input) a model's preparation throws on `from` (a patch or a
// stored patch) with the options o; empty when it prepares.
template <typename From>
std::string message_of(const From& from, const TangentialModelOptions& o) {
  try {
    (void)TangentialModel(from, o);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_input) << e.what();
    return e.what();
  }
  return "";
}

TEST(TangentialModel, BadStoredPatchesAreRefusedByName) {
  const ContactPatch patch = ellipse_patch(400);
  const Flexibility L = NhFastSim(patch).flexibility();
  StoredPatch stored;
  EXPECT_EQ(message_of(stored, options_for(TangentialSolver::nh_fastsim)),
            "tangential model: a stored patch needs at least one lobe");
  stored.lobes.push_back({patch, L, 0.0, 0.0});
  EXPECT_EQ(message_of(stored, options_for(TangentialSolver::exact)),
            "tangential model: a stored patch is solved by nh-fastsim, not exact");
  stored.whole_patch_weight = 1.5;
  EXPECT_EQ(message_of(stored, options_for(TangentialSolver::nh_fastsim)),
            "tangential model: a stored patch's whole_patch_weight = 1.5 must lie in [0, 1]");
  stored.whole_patch_weight = 0.5;
  EXPECT_EQ(message_of(stored, options_for(TangentialSolver::nh_fastsim)),
            "tangential model: a stored patch with a whole_patch_weight above 0 needs its whole patch");
  stored.whole_patch_weight = 0.0;
  stored.lobes.front().flexibility.L2 = NAN;
  EXPECT_NE(message_of(stored, options_for(TangentialSolver::nh_fastsim))
                .find("a stored lobe's flexibility.L2 = nan m/Pa must be positive and finite"),
            std::string::npos);
  stored.lobes.front() = StoredLobe{ContactPatch{}, L, 0.0, 0.0};
  EXPECT_EQ(message_of(stored, options_for(TangentialSolver::nh_fastsim)),
            "tangential model: a stored lobe has no element in contact");
}

TEST(TangentialModel, BadOptionsAreRefusedByName) {
  const ContactPatch patch = ellipse_patch(400);
  TangentialModelOptions o;
  o.solver = static_cast<TangentialSolver>(7);
  EXPECT_EQ(message_of(patch, o),
            "tangential model: solver = 7 is not a TangentialSolver (0 nh-fastsim, 1 fastsim, 2 exact, 3 "
            "exact-regularised)");
  o = {};
  o.nh_fastsim.bound.skew = 1.5;
  EXPECT_NE(message_of(patch, o).find("nh_fastsim.bound.skew = 1.5 must lie in [0, 1]"), std::string::npos);
  o = {};
  o.nh_fastsim.flexibility_coarsening = -1;
  EXPECT_NE(message_of(patch, o).find("nh_fastsim.flexibility_coarsening = -1"), std::string::npos);
  o = {};
  o.nh_fastsim.collocation_offset = -1.0;
  EXPECT_NE(message_of(patch, o).find("nh_fastsim.collocation_offset = -1 must lie in [-0.95, 1]"),
            std::string::npos);
  o = {};
  o.nh_fastsim.match = static_cast<FlexibilityMatch>(5);
  EXPECT_NE(message_of(patch, o).find("nh_fastsim.match = 5 is not a FlexibilityMatch"), std::string::npos);
  o = {};
  o.given_flexibilities = NhFastSimFlexibilities{{1e-10, -1e-10, 1e-10}, 1.0, 1.0, 1.0};
  EXPECT_NE(message_of(patch, o).find("given_flexibilities.flexibility.L2 = -1e-10 m/Pa must be positive"),
            std::string::npos);
  o = options_for(TangentialSolver::fastsim);
  o.ellipse_semi_axes_m = std::array<double, 2>{0.0, 1e-3};
  EXPECT_NE(message_of(patch, o).find("ellipse_semi_axes_m[0] = 0 m must be positive"), std::string::npos);
  o = options_for(TangentialSolver::exact);
  o.rolling.tolerance = 1.0;
  EXPECT_NE(message_of(patch, o).find("tolerance"), std::string::npos);
  for (TangentialSolver s : kTangentialSolvers)
    EXPECT_NE(message_of(ContactPatch{}, options_for(s)), "") << "a patch without contact: " << solver_name(s);

  const TangentialModel model(patch, options_for(TangentialSolver::nh_fastsim));
  EXPECT_THROW((void)model.solve(kCreepage, 0.0), Error);
  EXPECT_THROW((void)model.solve(Creepage{NAN, 0.0, 0.0}, kMu), Error);
}

TEST(TangentialModel, SolverNamesAndNumbersAreOneTable) {
  for (TangentialSolver s : kTangentialSolvers) {
    EXPECT_EQ(parse_tangential_solver(solver_name(s)), s);
    EXPECT_EQ(tangential_solver_of(static_cast<int>(s), "x"), s);
  }
  try {
    (void)tangential_solver_of(4, "rc_settings.method", "an rc_method");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "rc_settings.method = 4 is not an rc_method (0 nh-fastsim, 1 fastsim, 2 exact, 3 exact-regularised)");
  }
}

}  // namespace
}  // namespace railcontact
