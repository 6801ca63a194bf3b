// The flexibility table (docs/FLEXTABLE.md): exact at its nodes, within the stated error between
// them, contact jumps bracketed, gaps at several patches, exact save/load round trip, and clear
// errors for other profiles, other materials, y or Fz out of range and malformed files.
// Coarse tables (0.5 mm, ~800 elements) keep the suite fast.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "case/case_run.hpp"
#include "cli_run.hpp"
#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/flexibility_table.hpp"
#include "support/file_fingerprint.hpp"
#include "study/flexibility_table_check.hpp"

namespace railcontact {
namespace {

constexpr double kMm = 1e-3;
constexpr double kFz = 98100.0;
constexpr int kElements = 800;

const WheelRailPair& pair() {
  static const WheelRailPair p = default_wheel_rail_pair();
  return p;
}

// The tables of these tests take K2 on the patch itself (flexibility coarsening 1): their
// interpolation is then measured without the coarse patch's shape noise (docs/FLEXTABLE.md §4).
FlexibilityTableOptions coarse_options() {
  FlexibilityTableOptions options;
  options.patch.target_elements = kElements;
  options.nh_fastsim.flexibility_coarsening = 1;
  return options;
}

// y = -1 ... 1 mm in 0.5 mm steps at 98.1 kN on the point of first touch: holds its contact jump
// at y ≈ -0.221 mm.
FlexibilityTableOptions first_touch_options() {
  FlexibilityTableOptions options = coarse_options();
  options.patch.reference = ContactReference::first_touch;
  return options;
}
const FlexibilityTable& jump_table() {
  static const FlexibilityTable t =
      build_flexibility_table(pair(), flexibility_table_y_grid(-1e-3, 1e-3, 0.5e-3), {kFz}, first_touch_options());
  return t;
}

// The same grid on the smooth reference (the default): no jump.
const FlexibilityTable& smooth_table() {
  static const FlexibilityTable t =
      build_flexibility_table(pair(), flexibility_table_y_grid(-1e-3, 1e-3, 0.5e-3), {kFz}, coarse_options());
  return t;
}

// y = 1.0, 1.5 mm at 80 and 100 kN.
const FlexibilityTable& load_table() {
  static const FlexibilityTable t = build_flexibility_table(pair(), {1.0e-3, 1.5e-3}, {80000.0, 100000.0}, coarse_options());
  return t;
}

// y = -5.0 (two patches at 10 kN: tread and flange root) and -4.5 mm.
constexpr double kLightFz = 10000.0;
const FlexibilityTable& gap_table() {
  static const FlexibilityTable t = build_flexibility_table(pair(), {-5.0e-3, -4.5e-3}, {kLightFz}, coarse_options());
  return t;
}


std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// nH-FastSim on the fly with the recipe of the tables above (NhFastSim, K2 of the patch itself).
struct OnTheFly {
  WheelRailPatch patch;
  Flexibility L;
  Matrix3 K2;
};
OnTheFly on_the_fly(double y_m, double Fz_N, ContactReference reference = ContactReference::smooth) {
  WheelRailPatchOptions options;
  options.target_elements = kElements;
  options.reference = reference;
  options.vertical_load_N = Fz_N;
  OnTheFly r{solve_wheel_rail_patch(pair(), y_m, options), {}, {}};
  const NhFastSim nh(r.patch.patch, coarse_options().nh_fastsim);
  r.K2 = *nh.creepage_matrix();
  r.L = nh.flexibility();
  return r;
}

void expect_relative(double value, double expected, double tolerance, const std::string& what) {
  EXPECT_NEAR(value, expected, tolerance * std::fabs(expected)) << what;
}

TEST(FlexibilityTable, NodesReproduceOnTheFlyFlexibilitiesExactly) {
  const FlexibilityTable& t = jump_table();
  for (std::size_t iy = 0; iy < t.y_m().size(); ++iy) {
    const double y = t.y_m()[iy];
    const OnTheFly ref = on_the_fly(y, kFz, ContactReference::first_touch);
    for (const FlexibilityTableValues& v : {t.lookup(y, kFz), t.lookup_for_patch(y, kFz, ref.patch.area_m2)}) {
      const std::string at = "y = " + std::to_string(y / kMm) + " mm";
      expect_relative(v.flexibility.L1, ref.L.L1, 1e-13, "L1 " + at);
      expect_relative(v.flexibility.L2, ref.L.L2, 1e-13, "L2 " + at);
      expect_relative(v.flexibility.L3, ref.L.L3, 1e-13, "L3 " + at);
      expect_relative(v.f11_N, -ref.K2(0, 0), 1e-13, "f11 " + at);
      expect_relative(v.f22_N, -ref.K2(1, 1), 1e-13, "f22 " + at);
      expect_relative(v.f23_Nm, -ref.K2(1, 2), 1e-13, "f23 " + at);
      EXPECT_EQ(v.normal_force_N, ref.patch.normal_force_N) << at;
      EXPECT_EQ(v.contact_angle_rad, ref.patch.contact_angle_rad) << at;
      EXPECT_EQ(v.spin_per_m, ref.patch.spin_per_m) << at;
      EXPECT_EQ(v.area_m2, ref.patch.area_m2) << at;
      EXPECT_EQ(v.elements_in_contact, static_cast<double>(ref.patch.elements_in_contact)) << at;
    }
  }
}

// docs/FLEXTABLE.md §4: this coarse table (0.5 mm, ~800 elements) measures 0.58 % at most at the
// midpoints (y = -0.75 mm, xi' = 0.1); the default table (0.25 mm, 3000 elements) 0.26 %.
TEST(FlexibilityTable, BetweenNodesWithinTheStatedError) {
  study::FlexibilityTableCheckOptions options;
  const study::FlexibilityTableCheck check = study::check_flexibility_table(jump_table(), pair(), options);
  ASSERT_EQ(check.points.size(), 5u);  // 4 grid intervals, the one with the jump split in two
  EXPECT_TRUE(check.skipped.empty());
  EXPECT_LT(check.max_force_difference, 0.01);
  EXPECT_LT(check.mean_force_difference, 0.003);
  EXPECT_LT(check.max_force_difference_table_normalised, 0.012);
  for (const auto& p : check.points) {
    EXPECT_NEAR(p.table.L1 / p.on_the_fly.L1, 1.0, 0.012) << p.y_m;
    EXPECT_NEAR(p.table.L2 / p.on_the_fly.L2, 1.0, 0.012) << p.y_m;
    EXPECT_NEAR(p.table.L3 / p.on_the_fly.L3, 1.0, 0.02) << p.y_m;
  }
}

// The default table, on the smooth reference: no contact jump to bracket, the spin continuous, and
// between the nodes within the error stated for the first-touch table.
TEST(FlexibilityTable, SmoothReferenceTableHasNoJump) {
  const FlexibilityTable& t = smooth_table();
  EXPECT_EQ(t.metadata().contact_reference, ContactReference::smooth);
  EXPECT_TRUE(t.contact_jumps().empty());
  ASSERT_EQ(t.y_m().size(), 5u);
  for (std::size_t k = 0; k + 1 < t.y_m().size(); ++k)  // 0.5 mm apart: γ moves by at most ~12 mrad
    EXPECT_LT(std::fabs(t.node(k + 1, 0).contact_angle_rad - t.node(k, 0).contact_angle_rad), 0.015) << k;
  study::FlexibilityTableCheckOptions options;
  const study::FlexibilityTableCheck scaled = study::check_flexibility_table(t, pair(), options);
  options.interpolation = FlexibilityInterpolation::plain;
  const study::FlexibilityTableCheck plain = study::check_flexibility_table(t, pair(), options);
  std::printf("  smooth table between nodes: area-scaled max %.4f mean %.4f, plain max %.4f mean %.4f\n",
              scaled.max_force_difference, scaled.mean_force_difference, plain.max_force_difference,
              plain.mean_force_difference);
  EXPECT_EQ(scaled.points.size(), 4u);
  EXPECT_LT(scaled.max_force_difference, 0.01);
  EXPECT_LT(scaled.mean_force_difference, 0.003);
}

TEST(FlexibilityTable, AreaScalingBeatsPlainInterpolationOnTheCoarseTable) {
  study::FlexibilityTableCheckOptions options;
  const double scaled = study::check_flexibility_table(jump_table(), pair(), options).mean_force_difference;
  options.interpolation = FlexibilityInterpolation::plain;
  const double plain = study::check_flexibility_table(jump_table(), pair(), options).mean_force_difference;
  EXPECT_LT(scaled, plain);
}

TEST(FlexibilityTable, ContactJumpIsBracketedNotInterpolated) {
  const FlexibilityTable& t = jump_table();
  ASSERT_EQ(t.contact_jumps().size(), 1u);
  const ContactJump& jump = t.contact_jumps().front();
  const double left = t.y_m()[jump.interval], right = t.y_m()[jump.interval + 1];
  EXPECT_LE(right - left, 1e-6 + 1e-15);
  EXPECT_GT(left, -0.25e-3);
  EXPECT_LT(right, -0.20e-3);
  EXPECT_GT(std::fabs(jump.y_rail_left_m - jump.y_rail_right_m), 5e-3);  // the first-touch point jumps ~10 mm
  ASSERT_EQ(t.y_m().size(), 7u);  // 5 grid values + 2 brackets
  // Each side is interpolated within itself: the spin (from γ) does not blend across the jump.
  const FlexibilityTableNode& l = t.node(jump.interval, 0);
  const FlexibilityTableNode& r = t.node(jump.interval + 1, 0);
  EXPECT_GT(l.spin_per_m, 2 * r.spin_per_m);
  EXPECT_EQ(t.lookup(left + 0.2e-6, kFz).spin_per_m, l.spin_per_m);
  EXPECT_EQ(t.lookup(right - 0.2e-6, kFz).spin_per_m, r.spin_per_m);
  const double just_left = t.lookup(left - 1e-6, kFz).spin_per_m;
  const double just_right = t.lookup(right + 1e-6, kFz).spin_per_m;
  EXPECT_NEAR(just_left, l.spin_per_m, 1e-3 * l.spin_per_m);
  EXPECT_NEAR(just_right, r.spin_per_m, 1e-3 * r.spin_per_m);
  // The flexibilities hardly change across the jump (the loaded patch does not jump).
  EXPECT_NEAR(l.flexibility.L1 / r.flexibility.L1, 1.0, 0.02);
}

TEST(FlexibilityTable, SaveLoadRoundTripIsExact) {
  const test::ScratchDirectory dir("flextable_roundtrip");  // removed with its files at the end
  for (const FlexibilityTable* t : {&jump_table(), &load_table(), &gap_table()}) {
    const std::string path = (dir / "roundtrip.json").string();
    save_flexibility_table(*t, path);
    const FlexibilityTable back = load_flexibility_table(path);
    std::filesystem::remove(path);
    EXPECT_EQ(back.source(), path);
    EXPECT_EQ(back.y_m(), t->y_m());
    EXPECT_EQ(back.vertical_loads_N(), t->vertical_loads_N());
    const FlexibilityTableMetadata &a = back.metadata(), &b = t->metadata();
    EXPECT_EQ(a.wheel_profile.file, b.wheel_profile.file);
    EXPECT_EQ(a.wheel_profile.fnv1a64, b.wheel_profile.fnv1a64);
    EXPECT_EQ(a.rail_profile.fnv1a64, b.rail_profile.fnv1a64);
    EXPECT_EQ(a.material.youngs_modulus_Pa, b.material.youngs_modulus_Pa);
    EXPECT_EQ(a.material.poisson_ratio, b.material.poisson_ratio);
    EXPECT_EQ(a.target_elements, b.target_elements);
    EXPECT_EQ(a.track.track_gauge_m, b.track.track_gauge_m);
    EXPECT_EQ(a.track.nominal_rolling_radius_m, b.track.nominal_rolling_radius_m);
    EXPECT_EQ(a.railcontact_version, b.railcontact_version);
    EXPECT_EQ(a.created_utc, b.created_utc);
    ASSERT_EQ(back.contact_jumps().size(), t->contact_jumps().size());
    for (std::size_t k = 0; k < back.contact_jumps().size(); ++k) {
      EXPECT_EQ(back.contact_jumps()[k].interval, t->contact_jumps()[k].interval);
      EXPECT_EQ(back.contact_jumps()[k].y_rail_left_m, t->contact_jumps()[k].y_rail_left_m);
    }
    ASSERT_EQ(back.nodes().size(), t->nodes().size());
    for (std::size_t k = 0; k < back.nodes().size(); ++k) {
      const FlexibilityTableNode &x = back.nodes()[k], &y = t->nodes()[k];
      EXPECT_EQ(x.status, y.status);
      EXPECT_EQ(x.message, y.message);
      if (y.status != FlexibilityNodeStatus::solved) continue;
      EXPECT_EQ(x.flexibility.L1, y.flexibility.L1);
      EXPECT_EQ(x.flexibility.L2, y.flexibility.L2);
      EXPECT_EQ(x.flexibility.L3, y.flexibility.L3);
      EXPECT_EQ(x.f11_N, y.f11_N);
      EXPECT_EQ(x.f22_N, y.f22_N);
      EXPECT_EQ(x.f23_Nm, y.f23_Nm);
      EXPECT_EQ(x.normal_force_N, y.normal_force_N);
      EXPECT_EQ(x.contact_angle_rad, y.contact_angle_rad);
      EXPECT_EQ(x.spin_per_m, y.spin_per_m);
      EXPECT_EQ(x.area_m2, y.area_m2);
      EXPECT_EQ(x.elements_in_contact, y.elements_in_contact);
    }
  }
}

TEST(FlexibilityTable, MetadataNamesProfilesMaterialAndVersion) {
  const FlexibilityTableMetadata& m = jump_table().metadata();
  EXPECT_EQ(m.wheel_profile.file, default_wheel_profile_path().string());
  EXPECT_EQ(m.wheel_profile.fnv1a64, file_fingerprint(default_wheel_profile_path()).fnv1a64);
  EXPECT_EQ(m.rail_profile.fnv1a64, file_fingerprint(default_rail_profile_path()).fnv1a64);
  EXPECT_NE(m.wheel_profile.fnv1a64, m.rail_profile.fnv1a64);
  EXPECT_EQ(m.target_elements, kElements);
  EXPECT_EQ(m.material.youngs_modulus_Pa, 2.1e11);
  EXPECT_FALSE(m.railcontact_version.empty());
  EXPECT_EQ(m.created_utc.size(), 20u);  // 2024-05-01T12:00:00Z
  // FNV-1a 64 reference values: "" and "a".
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(parse_fnv1a64_hex(fnv1a64_hex(0x0123456789abcdefULL)), 0x0123456789abcdefULL);
}

TEST(FlexibilityTable, OtherProfilesAreRejected) {
  // The same rail, rewritten as a text profile: the geometry is the same, the file is not.
  const test::ScratchDirectory dir("flextable_other_rail");  // removed with its files at the end
  const std::string rail = (dir / "rail.txt").string();
  write_text_profile(rail, read_profile(default_rail_profile_path()));
  const WheelRailPair other = load_wheel_rail_pair(default_wheel_profile_path(), rail);
  const std::string e = error_of([&] { jump_table().check_profiles(other); });
  EXPECT_NE(e.find("was built for other profiles"), std::string::npos) << e;
  EXPECT_NE(e.find(rail), std::string::npos) << e;
  EXPECT_NE(error_of([&] {
              const FlexibilityTableFastSim nh(jump_table(), other);
              (void)nh;
            }).find("other profiles"),
            std::string::npos);
  EXPECT_NO_THROW(jump_table().check_profiles(pair()));
  // Another material or collocation offset.
  EXPECT_NE(error_of([&] { jump_table().check_material(Material{2.0e11, 0.3}); }).find("another material"), std::string::npos);
  EXPECT_NE(error_of([&] { jump_table().check_material(Material{2.1e11, 0.3}, 0.5); }).find("collocation offset"),
            std::string::npos);
}

TEST(FlexibilityTable, OutOfRangeNamesTheRange) {
  const std::string y_error = error_of([] { (void)jump_table().lookup(1.2e-3, kFz); });
  EXPECT_NE(y_error.find("y = 1.2000 mm lies outside its range y = -1.0000 ... 1.0000 mm"), std::string::npos) << y_error;
  EXPECT_NE(error_of([] { (void)jump_table().lookup(-1.001e-3, kFz); }).find("outside its range"), std::string::npos);
  const std::string single = error_of([] { (void)jump_table().lookup(0.0, 90000.0); });
  EXPECT_NE(single.find("Fz = 90000 N lies outside its range: it holds the one vertical load Fz = 98100 N"),
            std::string::npos)
      << single;
  const std::string loads = error_of([] { (void)load_table().lookup(1.2e-3, 120000.0); });
  EXPECT_NE(loads.find("Fz = 120000 N lies outside its range Fz = 80000 ... 100000 N"), std::string::npos) << loads;
  EXPECT_NE(error_of([] { (void)jump_table().lookup(NAN, kFz); }).find("finite"), std::string::npos);
  // The table-driven step checks the range before it solves anything.
  const FlexibilityTableFastSim nh(jump_table(), pair());
  EXPECT_NE(error_of([&] { (void)nh.prepare(2e-3, kFz); }).find("outside its range"), std::string::npos);
}

TEST(FlexibilityTable, SeveralPatchesLeaveAGap) {
  const FlexibilityTable& t = gap_table();
  ASSERT_EQ(t.node(0, 0).status, FlexibilityNodeStatus::several_patches);
  EXPECT_NE(t.node(0, 0).message.find("2 contact patches, the largest carrying"), std::string::npos)
      << t.node(0, 0).message;
  EXPECT_EQ(t.node(1, 0).status, FlexibilityNodeStatus::solved);
  const std::string e = error_of([&] { (void)t.lookup(-4.75e-3, kLightFz); });
  EXPECT_NE(e.find("gap"), std::string::npos) << e;
  EXPECT_NE(e.find("y = -5.0000 mm"), std::string::npos) << e;
  EXPECT_NE(e.find("several-patches"), std::string::npos) << e;
  EXPECT_NO_THROW((void)t.lookup(-4.5e-3, kLightFz));  // the solved node itself
}

TEST(FlexibilityTable, LoadAxisIsExactAtItsNodesAndCloseBetween) {
  const FlexibilityTable& t = load_table();
  for (std::size_t il = 0; il < 2; ++il) {
    const FlexibilityTableNode& n = t.node(0, il);
    const FlexibilityTableValues v = t.lookup(n.y_m, n.vertical_load_N);
    expect_relative(v.flexibility.L1, n.flexibility.L1, 1e-13, "L1");
    expect_relative(v.f23_Nm, n.f23_Nm, 1e-13, "f23");
    EXPECT_EQ(v.normal_force_N, n.normal_force_N);
  }
  // Geometric mid-load and mid-y: against on the fly, on the same patch.
  const double y = 1.25e-3, Fz = std::sqrt(80000.0 * 100000.0);
  const OnTheFly ref = on_the_fly(y, Fz);
  const FlexibilityTableValues v = t.lookup_for_patch(y, Fz, ref.patch.area_m2);
  expect_relative(v.flexibility.L1, ref.L.L1, 0.01, "L1");
  expect_relative(v.flexibility.L2, ref.L.L2, 0.01, "L2");
  expect_relative(v.flexibility.L3, ref.L.L3, 0.015, "L3");
  expect_relative(v.f11_N, -ref.K2(0, 0), 0.01, "f11");
  expect_relative(v.normal_force_N, ref.patch.normal_force_N, 1e-4, "F3");
}

TEST(FlexibilityTableFastSim, CachedPatchAndFullStepAgreeWithOnTheFly) {
  const FlexibilityTableFastSim nh(smooth_table(), pair());
  EXPECT_EQ(nh.patch_options().target_elements, kElements);
  EXPECT_EQ(nh.patch_options().reference, ContactReference::smooth);
  const double y = 0.25e-3, mu = 0.3;
  const FlexibilityTableFastSim::Patch patch = nh.prepare(y, kFz);
  const OnTheFly ref = on_the_fly(y, kFz);
  EXPECT_EQ(patch.wheel_rail_patch().elements_in_contact, ref.patch.elements_in_contact);
  const Creepage c = patch.creepage_from_normalised(0.5, 0.5, patch.spin_per_m(), mu);
  EXPECT_NEAR(c.xi, 0.5 * 3 * mu * patch.normal_force_N() / patch.table_values().f11_N, 1e-15);
  EXPECT_EQ(c.phi, ref.patch.spin_per_m);
  // (b) FastSim only, (a) the full step: the same numbers.
  const TangentialForces cached = patch.forces(c, mu);
  const TangentialForces full = nh.forces(y, kFz, c, mu);
  EXPECT_EQ(cached.F1_N, full.F1_N);
  EXPECT_EQ(cached.F2_N, full.F2_N);
  EXPECT_EQ(cached.M3_Nm, full.M3_Nm);
  // The march with tractions kept and the forces-only march: two code paths, the same forces to
  // rounding.
  EXPECT_NEAR(patch.solve(c, mu).forces.F1_N, cached.F1_N, 1e-12 * std::abs(cached.F1_N));
  // Against nH-FastSim with on-the-fly flexibilities on the same patch and creepage.
  const TangentialForces reference = FastSim(ref.patch.patch).forces(c, ref.L, mu);
  EXPECT_NEAR(std::hypot(cached.F1_N - reference.F1_N, cached.F2_N - reference.F2_N),
              0.0, 0.005 * std::hypot(reference.F1_N, reference.F2_N));
}

TEST(FlexibilityTableFastSim, CaseRunTakesFlexibilitiesFromTheTable) {
  Case c = default_case();
  c.wheel_rail.y_m = 0.25e-3;
  c.wheel_rail.reference = ContactReference::first_touch;  // the table's
  c.target_elements = kElements;
  c.solvers = {TangentialSolver::nh_fastsim, TangentialSolver::fastsim};
  const CaseResult on_the_fly_result = run_case(c);
  CaseRunOptions options;
  options.flexibility_table = std::make_shared<const FlexibilityTable>(jump_table());
  // The table's recipe is checked against the case's (FlexibilityTable::check_recipe): the case's
  // automatic coarsening is not the table's 1.
  const std::string recipe = error_of([&] { (void)run_case(c, options); });
  EXPECT_NE(recipe.find("was built with the flexibility coarsening 1 and is used with 0 (automatic)"), std::string::npos)
      << recipe;
  c.flexibility_coarsening = 1;  // the table's recipe
  // ... and its contact reference (FlexibilityTable::check_contact_reference): a case on the smooth
  // reference may not use a table built on first touch.
  Case smooth = c;
  smooth.wheel_rail.reference = ContactReference::smooth;
  const std::string reference = error_of([&] { (void)run_case(smooth, options); });
  EXPECT_NE(reference.find("was built on the first-touch contact reference and is used on the smooth one"),
            std::string::npos)
      << reference;
  const CaseResult tabled = run_case(c, options);
  EXPECT_FALSE(tabled.creepage_matrix.has_value());  // no K2
  ASSERT_TRUE(tabled.flexibility_table_values.has_value());
  const SolverRun* nh = tabled.find(TangentialSolver::nh_fastsim);
  ASSERT_NE(nh, nullptr);
  EXPECT_EQ(nh->flexibility_source, "table");
  EXPECT_EQ(on_the_fly_result.find(TangentialSolver::nh_fastsim)->flexibility_source, "K2 of the patch coarsened by 2");
  EXPECT_EQ(tabled.find(TangentialSolver::fastsim)->flexibility_source, "Eq 9");
  EXPECT_EQ(nh->flexibility->L1, tabled.flexibility_table_values->flexibility.L1);
  const TangentialForces& a = nh->forces;
  const TangentialForces& b = on_the_fly_result.find(TangentialSolver::nh_fastsim)->forces;
  EXPECT_NEAR(std::hypot(a.F1_N - b.F1_N, a.F2_N - b.F2_N), 0.0, 0.01 * std::hypot(b.F1_N, b.F2_N));

  Case ellipse;
  ellipse.source = "ellipse.toml";
  ellipse.ellipse.a_m = 6e-3;
  ellipse.ellipse.b_m = 4e-3;
  ellipse.normal_force_N = kFz;
  const std::string e = error_of([&] { (void)run_case(ellipse, options); });
  EXPECT_NE(e.find("wheel-rail cases only"), std::string::npos) << e;
  c.wheel_rail.y_m = 3e-3;
  EXPECT_NE(error_of([&] { (void)run_case(c, options); }).find("outside its range"), std::string::npos);
}

TEST(FlexibilityTableFile, MalformedFilesNameTheProblem) {
  const std::string good = flexibility_table_json(load_table());
  const auto error_for = [](const std::string& text) {
    return error_of([&] { (void)parse_flexibility_table(text, "t.json"); });
  };
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  EXPECT_NO_THROW((void)parse_flexibility_table(good, "t.json"));
  EXPECT_NE(error_for("{\n \"format\": ").find("t.json:2: malformed JSON"), std::string::npos) << error_for("{\n \"format\": ");
  EXPECT_NE(error_for("{}").find("not a flexibility table"), std::string::npos);
  EXPECT_NE(error_for(replaced("\"format_version\": 5", "\"format_version\": 6")).find("format_version 6"), std::string::npos);
  EXPECT_NE(error_for(replaced("\"nh_fastsim_recipe\": 3", "\"nh_fastsim_recipe\": 5"))
                .find("nh_fastsim_recipe 5 must lie in [0, 4]"),
            std::string::npos);
  EXPECT_NE(error_for(replaced("\"contact_reference\": \"smooth\"", "\"contact_reference\": \"lowest\""))
                .find("contact_reference \"lowest\" must be \"smooth\" or \"first-touch\""),
            std::string::npos);
  EXPECT_NE(error_for(replaced("\"target_elements\"", "\"target_element\"")).find("missing key 'target_elements'"),
            std::string::npos);
  EXPECT_NE(error_for(replaced("\"target_elements\"", "\"extra\": 1, \"target_elements\"")).find("unknown key 'extra'"),
            std::string::npos);
  EXPECT_NE(error_for(replaced("\"f11_N\"", "\"f11\"")).find("nodes[0]"), std::string::npos);
  // A creepage coupling beyond what a patch gives (ratios below 0.01, lengths below 1 mm measured) is
  // refused, naming the node.
  EXPECT_NE(error_for(replaced("\"xi_per_eta\": 0.0", "\"xi_per_eta\": 50.0"))
                .find("nodes[0] (y = 1.0000 mm, Fz = 80000 N): creepage_coupling (50, 0 m, 0, 0 m) is not plausible"),
            std::string::npos)
      << error_for(replaced("\"xi_per_eta\": 0.0", "\"xi_per_eta\": 50.0"));
  EXPECT_NE(error_for(replaced("\"L1_m_per_Pa\": ", "\"L1_m_per_Pa\": \"x\", \"y\": ")).find("must be a number"),
            std::string::npos);
  EXPECT_NE(error_for(replaced("\"fnv1a64\": \"", "\"fnv1a64\": \"zz")).find("fnv1a64"), std::string::npos);
  EXPECT_NE(error_of([] { (void)load_flexibility_table("/nonexistent/table.json"); }).find("cannot read the flexibility table"),
            std::string::npos);
}

TEST(FlexibilityTableBuild, BadGridsAndOptionsThrow) {
  EXPECT_NE(error_of([] { (void)build_flexibility_table(pair(), {1e-3, 0.0}, {kFz}); }).find("strictly increasing"),
            std::string::npos);
  EXPECT_NE(error_of([] { (void)build_flexibility_table(pair(), {0.0}, {}); }).find("at least one"), std::string::npos);
  EXPECT_NE(error_of([] { (void)build_flexibility_table(pair(), {0.0}, {-1.0}); }).find("positive"), std::string::npos);
  EXPECT_NE(error_of([] { (void)flexibility_table_y_grid(0.0, 1e-3, 0.0); }).find("step"), std::string::npos);
  EXPECT_NE(error_of([] { (void)flexibility_table_y_grid(1e-3, 0.0, 1e-4); }).find("y_to >= y_from"), std::string::npos);
  // A y where the profiles never touch: every node fails, and the build says why.
  EXPECT_NE(error_of([] { (void)build_flexibility_table(pair(), {0.1}, {kFz}, coarse_options()); }).find("no node"),
            std::string::npos);
  const std::vector<double> grid = flexibility_table_y_grid(-4.5e-3, 4.5e-3, 0.25e-3);
  ASSERT_EQ(grid.size(), 37u);
  EXPECT_EQ(grid[18], 0.0);
  EXPECT_DOUBLE_EQ(grid.back(), 4.5e-3);
}

}  // namespace
}  // namespace railcontact

namespace railcontact {
namespace {

// The table's builder runs nH-FastSim's recipe itself (NhFastSim), by default the very one of
// `railcontact run` (automatic coarsening), and records it: a node equals on-the-fly nH-FastSim.
TEST(FlexibilityTable, DefaultBuildUsesTheRecipeOfRunAndRecordsIt) {
  FlexibilityTableOptions options;
  options.patch.target_elements = kElements;
  const FlexibilityTable t = build_flexibility_table(pair(), {0.5e-3}, {kFz}, options);
  EXPECT_EQ(t.metadata().flexibility_coarsening, 0);
  WheelRailPatchOptions patch_options;
  patch_options.target_elements = kElements;
  const WheelRailPatch p = solve_wheel_rail_patch(pair(), 0.5e-3, patch_options);
  const NhFastSim nh(p.patch);
  EXPECT_EQ(nh.coarsening(), 2);  // ~800 elements
  const FlexibilityTableNode& n = t.node(0, 0);
  EXPECT_EQ(n.flexibility.L1, nh.flexibility().L1);
  EXPECT_EQ(n.flexibility.L3, nh.flexibility().L3);
  EXPECT_EQ(n.f22_N, nh.flexibilities().f22_N);
  // Saved and loaded, the recipe stays; a version-1 file (before the recipe was recorded) was
  // built on the patch itself, versions 1 and 2 on the point of first touch, versions 1 to 3 with
  // an nH-FastSim recipe not recorded (older than this one: the commands note it).
  const std::string json = flexibility_table_json(t);
  // The recipe of `railcontact run`: single patches march without the creepage coupling (recipe 3;
  // the flexibilities are recipe 4's).
  EXPECT_EQ(t.metadata().nh_fastsim_recipe, nh_fastsim_recipe(false));
  EXPECT_EQ(parse_flexibility_table(json, "t.json").metadata().flexibility_coarsening, 0);
  EXPECT_EQ(parse_flexibility_table(json, "t.json").metadata().contact_reference, ContactReference::smooth);
  EXPECT_EQ(parse_flexibility_table(json, "t.json").metadata().nh_fastsim_recipe, 3);
  EXPECT_EQ(older_nh_fastsim_recipe_note(kNhFastSimRecipe), "");
  EXPECT_EQ(older_nh_fastsim_recipe_note(3), "");
  std::string v1 = json;
  v1.replace(v1.find("\"format_version\": 5"), 19, "\"format_version\": 1");
  v1.replace(v1.find("\"flexibility_coarsening\": 0,"), 28, "");
  v1.replace(v1.find("\"contact_reference\": \"smooth\","), 30, "");
  v1.replace(v1.find("\"nh_fastsim_recipe\": 3,"), 24, "");
  const FlexibilityTable old = parse_flexibility_table(v1, "t.json");
  EXPECT_EQ(old.metadata().flexibility_coarsening, 1);
  EXPECT_EQ(old.metadata().contact_reference, ContactReference::first_touch);
  EXPECT_EQ(old.metadata().nh_fastsim_recipe, 0);
  EXPECT_NE(older_nh_fastsim_recipe_note(0).find("older nH-FastSim recipe (1 or 2, not recorded; this railcontact: 4)"),
            std::string::npos);
}

}  // namespace
}  // namespace railcontact
