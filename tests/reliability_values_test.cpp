// Reliability of values and solvers (issue 14, items 1, 7, 11, 12, 13; docs/RELIABILITY.md "Values
// and solvers"): every value outside its physical or numerical range is refused with one message
// naming it, its value and the allowed range, in the library's terms (the parameter) and in the
// user's (the case key, the CLI option); no solver returns a non-finite number or reports one as
// converged; the spin moment's change is printed only against a moment that is not noise; tests
// leave nothing in /tmp; nu = 0.5 (incompressible) is accepted and right.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "case/case.hpp"
#include "case/case_output.hpp"
#include "case/case_run.hpp"
#include "cli_run.hpp"
#include "railcontact/railcontact.hpp"
#include "tangential/rolling_system.hpp"

namespace railcontact {
namespace {

using test::CommandResult;
using test::expect_one_error_line;
using test::run_cli;
using test::ScratchDirectory;

const Material kSteel{2.1e11, 0.3};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Failure {
  bool thrown = false;
  ErrorKind kind = ErrorKind::internal;
  std::string message;
};

Failure failure_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return {true, e.kind(), e.what()};
  }
  return {};
}

// f throws Error of `kind` whose message contains every one of `parts`.
void expect_error(const std::function<void()>& f, ErrorKind kind, const std::vector<std::string>& parts) {
  const Failure failure = failure_of(f);
  ASSERT_TRUE(failure.thrown) << "no error; expected one containing '" << parts.front() << "'";
  EXPECT_EQ(failure.kind, kind) << failure.message;
  for (const std::string& part : parts) EXPECT_NE(failure.message.find(part), std::string::npos) << failure.message;
}

ContactPatch ellipse_patch(int elements = 400, const Material& material = kSteel) {
  const double a = 6e-3, b = 4e-3;
  return hertzian_patch(elliptical_contact_with_count(a, b, elements, EllipseMeshLayout::rolling_resolved), a, b,
                        98100.0, material);
}

bool all_finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

// An ellipse case file with the given replacement lines appended to their sections (TOML allows
// a key only once, so the base file lacks the keys the tests set).
std::string ellipse_case(const std::string& material = "E = 2.1e11\nnu = 0.3\n",
                         const std::string& load = "normal_force = 98100.0\n", const std::string& solvers = "") {
  return "[geometry]\ntype = \"ellipse\"\na = 0.006\nb = 0.004\n[material]\n" + material + "[load]\n" + load +
         "[friction]\nmu = 0.3\n[creepage]\nxi = 0.001\neta = 0.0\nphi = 0.0\n[mesh]\nelements = 300\n"
         "[solvers]\nrun = [\"exact-regularised\"]\n" +
         solvers;
}

std::string write_case(const ScratchDirectory& dir, const std::string& name, const std::string& text) {
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

// ---- Item 1: the regularisation, the rolling options, non-finite results -------------------------

TEST(RollingOptions, EveryOptionOutsideItsRangeIsNamedWithItsValueAndRange) {
  const ContactPatch patch = ellipse_patch();
  const Creepage creepage{1e-3, 0.0, 0.2};
  const auto with = [](auto change) {
    RollingOptions o;
    change(o);
    return o;
  };
  const auto refused = [&](const RollingOptions& o, const std::vector<std::string>& parts) {
    expect_error([&] { validate(o); }, ErrorKind::invalid_input, parts);
    expect_error([&] { (void)solve_rolling_regularised(patch, creepage, 0.3, o); }, ErrorKind::invalid_input, parts);
    expect_error([&] { (void)solve_rolling_exact(patch, creepage, 0.3, o); }, ErrorKind::invalid_input, parts);
  };
  // The case: 1e200 gave NaN forces reported as converged.
  refused(with([](RollingOptions& o) { o.regularisation = 1e200; }), {"regularisation = 1e+200", "[1e-14, 0.01]"});
  refused(with([](RollingOptions& o) { o.regularisation = 0.1; }), {"regularisation = 0.1", "[1e-14, 0.01]"});
  refused(with([](RollingOptions& o) { o.regularisation = 1e-20; }), {"regularisation = 1e-20"});
  refused(with([](RollingOptions& o) { o.regularisation = kNaN; }), {"regularisation = nan"});
  refused(with([](RollingOptions& o) { o.tolerance = 0.0; }), {"tolerance = 0", "(0, 0.001]"});
  refused(with([](RollingOptions& o) { o.tolerance = 1.0; }), {"tolerance = 1", "(0, 0.001]"});
  refused(with([](RollingOptions& o) { o.tolerance = kNaN; }), {"tolerance = nan"});
  refused(with([](RollingOptions& o) { o.krylov_tolerance = 2.0; }), {"krylov_tolerance = 2", "(0, 0.5]"});
  refused(with([](RollingOptions& o) { o.max_newton_iterations = 0; }), {"max_newton_iterations = 0", "positive"});
  refused(with([](RollingOptions& o) { o.max_krylov_iterations = -1; }), {"max_krylov_iterations = -1"});
  refused(with([](RollingOptions& o) { o.collocation_offset = -0.999; }), {"alpha = -0.999", "[-0.95, 1]"});
  // The limits themselves are valid.
  EXPECT_NO_THROW(validate(with([](RollingOptions& o) { o.regularisation = kMaximumRegularisation; })));
  EXPECT_NO_THROW(validate(with([](RollingOptions& o) { o.regularisation = kMinimumRegularisation; })));
  EXPECT_NO_THROW(validate(with([](RollingOptions& o) { o.collocation_offset = kMinimumCollocationOffset; })));
  EXPECT_NO_THROW(validate(RollingOptions{}));
}

// The largest allowed regularisation still gives finite, converged forces (of the regularised law).
TEST(RollingOptions, LargestRegularisationGivesAFiniteSolution) {
  RollingOptions o;
  o.regularisation = kMaximumRegularisation;
  const RollingSolution r = solve_rolling_regularised(ellipse_patch(), {1e-3, 0.0, 0.2}, 0.3, o);
  EXPECT_TRUE(std::isfinite(r.forces.F1_N) && std::isfinite(r.forces.F2_N) && std::isfinite(r.forces.M3_Nm));
  EXPECT_LT(r.forces.F1_N, 0.0);
  EXPECT_LE(r.residual, o.tolerance);
}

// A residual taken with std::max hides NaN elements (std::max(0.0, NaN) is 0.0): that is how NaN
// forces were reported as converged. The solvers' residual propagates NaN.
TEST(RollingSolvers, ResidualMaximumPropagatesNaN) {
  EXPECT_EQ(std::max(0.0, kNaN), 0.0);  // the trap
  EXPECT_TRUE(std::isnan(max_or_nan(0.0, kNaN)));
  EXPECT_TRUE(std::isnan(max_or_nan(kNaN, 1.0)));
  EXPECT_EQ(max_or_nan(1.0, 2.0), 2.0);
  EXPECT_EQ(max_or_nan(2.0, 1.0), 2.0);
}

// Valid options, a patch whose pressure is 1e-300 Pa (finite and non-negative, so accepted): the
// regularised law's slope underflows and the Newton iteration produces NaN. It returned NaN forces
// as a converged solution; now it reports that it broke down (not_converged).
TEST(RollingSolvers, ABreakdownIsReportedNotReturned) {
  const ContactElements ellipse = elliptical_contact_with_count(6e-3, 4e-3, 300, EllipseMeshLayout::rolling_resolved);
  std::vector<double> pressure(ellipse.mesh().size(), 0.0);
  for (std::size_t k : ellipse.indices()) pressure[k] = 1e-300;
  const ContactPatch tiny(ellipse.mesh(), pressure, kSteel);
  expect_error([&] { (void)solve_rolling_regularised(tiny, {1e-3, 0.0, 0.2}, 0.3); }, ErrorKind::not_converged,
               {"regularised rolling solver", "broke down"});
  EXPECT_EQ(failure_of([&] { (void)solve_rolling_exact(tiny, {1e-3, 0.0, 0.2}, 0.3); }).kind, ErrorKind::not_converged);
  // A normal patch: finite everywhere.
  const RollingSolution r = solve_rolling_regularised(ellipse_patch(), {1e-3, 0.0, 0.2}, 0.3);
  EXPECT_TRUE(all_finite(r.p1_Pa) && all_finite(r.p2_Pa) && all_finite(r.s1) && all_finite(r.s2));
}

// FastSim: flexibilities of 1e-300 m/Pa overflow the squared tractions of the limiting (Eq 8); the
// march returned zero forces. Now refused, naming the flexibilities.
TEST(FastSimValues, TractionsBeyondWhatTheMarchCanSquareAreRefused) {
  const ContactPatch patch = ellipse_patch();
  const FastSim fastsim(patch);
  const Flexibility tiny{1e-300, 1e-300, 1e-300};
  expect_error([&] { (void)fastsim.forces({0.5, 0.0, 0.0}, tiny, 0.3); }, ErrorKind::invalid_input,
               {"L1 = 1e-300", "not physical"});
  expect_error([&] { (void)fastsim.solve({0.5, 0.0, 0.0}, tiny, 0.3); }, ErrorKind::invalid_input, {"L1 = 1e-300"});
  // Physical flexibilities at full slip: |F| = mu F3, finite.
  const TangentialForces f = fastsim.forces({0.5, 0.0, 0.0}, fastsim_flexibility(6e-3, 4e-3, kSteel), 0.3);
  EXPECT_NEAR(std::hypot(f.F1_N, f.F2_N), 0.3 * patch.normal_force_N(), 1e-3 * 0.3 * patch.normal_force_N());
}

// The adhesion solver: a tolerance of infinity made GMRES stop after one iteration per column and
// return that as K2, 16 % off (K2_11 = -7.99e6 instead of -9.48e6 N on this patch); alpha = -0.999
// surfaced as a GMRES failure.
TEST(AdhesionValues, ToleranceAndAlphaAreRefusedWithTheirRange) {
  const ContactElements ellipse = elliptical_contact_with_count(6e-3, 4e-3, 300);
  AdhesionOptions o;
  o.tolerance = std::numeric_limits<double>::infinity();
  expect_error([&] { (void)solve_full_adhesion(ellipse, kSteel, o); }, ErrorKind::invalid_input,
               {"tolerance = inf", "(0, 0.01]"});
  o = AdhesionOptions{};
  o.collocation_offset = -0.999;
  expect_error([&] { (void)solve_full_adhesion(ellipse, kSteel, o); }, ErrorKind::invalid_input,
               {"alpha = -0.999", "[-0.95, 1]"});
  o = AdhesionOptions{};
  o.spin_collocation_offset = -0.97;
  expect_error([&] { (void)solve_full_adhesion(ellipse, kSteel, o); }, ErrorKind::invalid_input,
               {"spin column = -0.97", "[-0.95, 1]"});
  NhFastSimOptions nh;
  nh.collocation_offset = -0.999;
  expect_error([&] { const NhFastSim s(ellipse_patch(), nh); }, ErrorKind::invalid_input, {"alpha = -0.999"});
  // The lower limit converges and gives finite K2.
  o = AdhesionOptions{};
  o.collocation_offset = kMinimumCollocationOffset;
  EXPECT_TRUE(solve_full_adhesion(ellipse, kSteel, o).creepage_matrix.all_finite());
}

// The normal solver on a mesh of 1e-151 m elements (positive and finite, so accepted): the element
// area underflows and the conjugate gradients produce NaN pressures, which counted as "no element
// carries pressure": the error said "no contact formed" (kind no_contact). Now the breakdown is
// named (not_converged).
TEST(NormalValues, ABreakdownIsReportedNotReturned) {
  const Mesh mesh = Mesh::covering(-1e-150, 1e-150, -1e-150, 1e-150, 20, 20);
  std::vector<double> h(mesh.size());
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1) h[mesh.index(i1, i2)] = mesh.x1(i1) * mesh.x1(i1) + mesh.x2(i2) * mesh.x2(i2);
  expect_error([&] { (void)solve_normal_contact(mesh, h, 1e5, kSteel); }, ErrorKind::not_converged, {"broke down"});
}

// Through the CLI with a case file, as the issue found it: a non-zero exit and one error line
// naming the case key (it printed NaN forces, "converged", and exited 0).
TEST(ValuesCli, RegularisationOfACaseIsRefused) {
  const ScratchDirectory dir("values_regularisation");
  const std::string file = write_case(dir, "case.toml", ellipse_case("E = 2.1e11\nnu = 0.3\n", "normal_force = 98100.0\n",
                                                                     "regularisation = 1e200\n"));
  const CommandResult r = run_cli("run " + file);
  expect_one_error_line(r, "regularisation");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("[solvers] regularisation = 1e+200 must lie in [1e-14, 0.01]"), std::string::npos) << r.err;
  const std::string ok = write_case(dir, "ok.toml", ellipse_case("E = 2.1e11\nnu = 0.3\n", "normal_force = 98100.0\n",
                                                                 "regularisation = 1e-6\n"));
  EXPECT_EQ(run_cli("run " + ok + " --json").exit_code, 0);
}

// ---- Item 11: the normal force; the spin moment's change against noise ---------------------------

TEST(NormalForce, NonPhysicalLoadsAreRefusedByEveryEntryPoint) {
  const std::vector<std::string> range{"is too large (1e+300 N; allowed [1, 1e+07] N)"};
  expect_error([] { (void)hertz_from_curvatures(1.0, 2.0, 1e300, kSteel); }, ErrorKind::invalid_input, range);
  expect_error([] { (void)hertz_curvatures_for_semi_axes(6e-3, 4e-3, 1e300, kSteel); }, ErrorKind::invalid_input, range);
  expect_error([] { (void)hertzian_patch(elliptical_contact(6e-3, 4e-3, 20), 6e-3, 4e-3, 1e300, kSteel); },
               ErrorKind::invalid_input, range);
  const Mesh mesh = Mesh::covering(-1e-2, 1e-2, -1e-2, 1e-2, 16, 16);
  const std::vector<double> h(mesh.size(), 0.0);
  expect_error([&] { (void)solve_normal_contact(mesh, h, 1e300, kSteel); }, ErrorKind::invalid_input, range);
  expect_error([&] { (void)solve_normal_contact(mesh, h, 0.5, kSteel); }, ErrorKind::invalid_input,
               {"normal force F3 is too small (0.5 N; allowed [1, 1e+07] N)"});
  WheelRailPatchOptions options;
  options.vertical_load_N = 1e300;
  expect_error([&] { (void)solve_wheel_rail_patch(default_wheel_rail_pair(), 0.0, options); }, ErrorKind::invalid_input,
               {"vertical wheel load is too large (1e+300 N; allowed [1, 1e+07] N)"});
  // The limits are loads.
  EXPECT_NO_THROW((void)hertz_from_curvatures(1.0, 2.0, kMinimumNormalForce_N, kSteel));
  EXPECT_NO_THROW((void)hertz_from_curvatures(1.0, 2.0, kMaximumNormalForce_N, kSteel));
}

TEST(NormalForce, CaseAndCliNameTheKeyAndTheOption) {
  const ScratchDirectory dir("values_load");
  const std::string file = write_case(dir, "case.toml", ellipse_case("E = 2.1e11\nnu = 0.3\n", "normal_force = 1e300\n"));
  expect_one_error_line(run_cli("run " + file), "[load] normal_force is too large (1e+300 N; allowed [1, 1e+07] N)");
  expect_one_error_line(run_cli("patch --load-N 1e300"), "--load-N is too large (1e+300 N; allowed [1, 1e+07] N)");
  expect_one_error_line(run_cli("flextable build --out " + (dir / "t.json").string() + " --load-N 1e300"),
                        "--load-N is too large (1e+300 N; allowed [1, 1e+07] N)");
}

// Pure longitudinal creepage on an ellipse: the exact M3 vanishes up to noise (~1e-12 N m against
// mu F3 c ~ 140 N m). The report printed the other solvers' change against it as -88 % and -94 %;
// now "(M3 ≈ 0)". With spin, M3 is a real moment and its change is printed.
TEST(CaseReport, SpinMomentChangeOnlyAgainstAMomentAboveTheNoise) {
  Case c;
  c.source = "test";
  c.geometry = GeometryKind::ellipse;
  c.ellipse.a_m = 6e-3;
  c.ellipse.b_m = 4e-3;
  c.normal_force_N = 98100.0;
  c.target_elements = 400;
  c.creepage.raw = {1e-3, 0.0, 0.0};
  c.solvers = {TangentialSolver::exact, TangentialSolver::fastsim};
  const auto report = [](const CaseResult& r) {
    std::ostringstream out;
    print_case_report(r, out);
    return out.str();
  };
  const CaseResult no_spin = run_case(c);
  const double M3 = no_spin.find(TangentialSolver::exact)->forces.M3_Nm;
  ASSERT_LT(std::fabs(M3), 1e-6 * 0.3 * 98100.0 * std::sqrt(6e-3 * 4e-3));
  const std::string text = report(no_spin);
  const std::size_t line = text.find("\nfastsim");
  ASSERT_NE(line, std::string::npos) << text;
  const std::string fastsim_line = text.substr(line + 1, text.find('\n', line + 1) - line - 1);
  EXPECT_NE(fastsim_line.find("(M3 ≈ 0)"), std::string::npos) << text;
  EXPECT_EQ(std::count(fastsim_line.begin(), fastsim_line.end(), '%'), 4) << fastsim_line;  // adhesion, dF1, dF2, d|F|

  c.creepage.raw = {1e-3, 0.0, 0.5};
  const std::string with_spin = report(run_case(c));
  EXPECT_EQ(with_spin.find("(M3 ≈ 0)"), std::string::npos) << with_spin;
}

// ---- Item 7: misleading errors --------------------------------------------------------------------

TEST(MaterialValues, YoungsModulusOutsideThePhysicalRangeIsNamed) {
  // E = 1e308 surfaced as a FastSim flexibility message (the flexibilities underflowed).
  expect_error([] { validate(Material{1e308, 0.3}); }, ErrorKind::invalid_input,
               {"Young's modulus E = 1e+308 Pa", "[1e+06, 1e+13] Pa"});
  expect_error([] { (void)fastsim_flexibility(6e-3, 4e-3, Material{1e308, 0.3}); }, ErrorKind::invalid_input,
               {"Young's modulus E = 1e+308 Pa"});
  expect_error([] { validate(Material{1e5, 0.3}); }, ErrorKind::invalid_input, {"E = 100000 Pa"});
  expect_error([] { validate(Material{kNaN, 0.3}); }, ErrorKind::invalid_input, {"E = nan Pa"});
  EXPECT_NO_THROW(validate(Material{kMinimumYoungsModulus_Pa, 0.3}));
  EXPECT_NO_THROW(validate(Material{kMaximumYoungsModulus_Pa, 0.3}));
  const ScratchDirectory dir("values_material");
  const std::string file = write_case(dir, "case.toml", ellipse_case("E = 1e308\nnu = 0.3\n"));
  expect_one_error_line(run_cli("run " + file), "[material] Young's modulus E = 1e+308 Pa");
}

// target_elements = 10 failed with "is the load Fz = 98100 N too large for these profiles?": the
// elements (about 4 x 7 mm) are so large that the first potential contact area, with its border of
// whole elements, reaches beyond the rail head.
TEST(WheelRailValues, TooFewElementsAreRefusedWithTheMinimum) {
  WheelRailPatchOptions options;
  options.target_elements = 10;
  expect_error([&] { (void)solve_wheel_rail_patch(default_wheel_rail_pair(), 0.0, options); }, ErrorKind::invalid_input,
               {"target_elements = 10 must lie in [100, 200000]"});
  expect_one_error_line(run_cli("patch --elements 10"), "--elements 10 must lie in [100, 200000]");
  const ScratchDirectory dir("values_elements");
  const std::string file = write_case(
      dir, "case.toml",
      "[geometry]\ntype = \"wheel-rail\"\n[material]\nE = 2.1e11\nnu = 0.3\n[load]\nnormal_force = 98100\n"
      "[friction]\nmu = 0.3\n[creepage]\nxi = 0.001\n[mesh]\nelements = 20\n[solvers]\nrun = [\"fastsim\"]\n");
  expect_one_error_line(run_cli("run " + file), "[mesh] elements = 20 must lie in [100, 200000] for a wheel-rail case");
}

// When the potential contact area does not fit on the profiles, the message says whether smaller
// elements would fit (and how many) or the load is too large. At 2 MN with 100 elements the area's
// border reaches beyond the rail head; with 4x as many elements it fits.
TEST(WheelRailValues, APotentialAreaBeyondTheProfilesNamesItsRealCause) {
  WheelRailPatchOptions options;
  options.target_elements = 100;
  options.vertical_load_N = 2e6;
  const Failure f = failure_of([&] { (void)solve_wheel_rail_patch(default_wheel_rail_pair(), 0.5e-3, options); });
  ASSERT_TRUE(f.thrown);
  for (const char* part : {"target_elements = 100", "are too large for these profiles", "use more elements (about"})
    EXPECT_NE(f.message.find(part), std::string::npos) << f.message;
  EXPECT_EQ(f.message.find("load Fz = 2e+06 N is too large"), std::string::npos) << f.message;
}

TEST(CollocationOffset, CliAndCaseNameTheirOption) {
  expect_one_error_line(run_cli("coefficients --a-over-b 1 --nu 0.3 --alpha -0.999"),
                        "--alpha -0.999 must lie in [-0.95, 1]");
  expect_one_error_line(run_cli("coefficients --a-over-b 1 --nu 0.3 --alpha-spin -0.99"),
                        "--alpha-spin -0.99 must lie in [-0.95, 1]");
  const ScratchDirectory dir("values_alpha");
  const std::string file =
      write_case(dir, "case.toml", ellipse_case("E = 2.1e11\nnu = 0.3\n", "normal_force = 98100.0\n", "alpha = -0.999\n"));
  expect_one_error_line(run_cli("run " + file), "[solvers] alpha = -0.999 must lie in [-0.95, 1]");
}

// The dense solver's size limit was phrased as advice to use "the Krylov solver"; the CLI names
// its option.
TEST(CliMessages, DenseSolverLimitNamesTheOption) {
  expect_one_error_line(run_cli("coefficients --a-over-b 1 --nu 0.3 --solver dense --elements 20000"),
                        "use --solver krylov");
}

// ---- Item 12: scratch directories are removed ----------------------------------------------------

TEST(ScratchDirectory, RemovesItsDirectoryAndFilesWhenItGoesOutOfScope) {
  std::filesystem::path kept;
  {
    const ScratchDirectory dir("values_scratch");
    kept = dir.path();
    std::filesystem::create_directories(dir / "sub");
    std::ofstream(dir / "sub" / "file.txt") << "x";
    EXPECT_TRUE(std::filesystem::exists(dir / "sub" / "file.txt"));
    EXPECT_NE(kept.filename().string().find("railcontact_values_scratch_"), std::string::npos);
  }
  EXPECT_FALSE(std::filesystem::exists(kept));
}

// ---- Item 13: nu = 0.5 --------------------------------------------------------------------------

TEST(Incompressible, PoissonsRatioOneHalfIsAcceptedAndOutsideIsNot) {
  EXPECT_NO_THROW(validate(Material{2.1e11, 0.5}));
  const Material incompressible{2.1e11, 0.5};
  EXPECT_DOUBLE_EQ(incompressible.contact_modulus_Pa(), 2.1e11 / 1.5);  // E / (2 (1 - 1/4))
  EXPECT_DOUBLE_EQ(incompressible.shear_modulus_Pa(), 2.1e11 / 3.0);
  expect_error([] { validate(Material{2.1e11, 0.51}); }, ErrorKind::invalid_input, {"nu = 0.51", "[0, 0.5]"});
  expect_error([] { validate(Material{2.1e11, -0.01}); }, ErrorKind::invalid_input, {"nu = -0.01", "[0, 0.5]"});
  expect_error([] { (void)kalker_coefficients(1.0, 0.51); }, ErrorKind::invalid_input, {"nu = 0.51"});
  expect_error([] { (void)ellipse_creepage_coefficients(1.0, 0.51); }, ErrorKind::invalid_input, {"nu = 0.51"});
  // The table's nu = 0.5 rows exactly.
  for (const KalkerTableRow& row : kalker_table_rows()) {
    if (row.nu != 0.5) continue;
    const KalkerCoefficients c = kalker_coefficients(row.a_over_b, 0.5);
    EXPECT_DOUBLE_EQ(c.C11, row.c11) << row.a_over_b;
    EXPECT_DOUBLE_EQ(c.C22, row.c22) << row.a_over_b;
    EXPECT_DOUBLE_EQ(c.C23, row.c23) << row.a_over_b;
  }
}

// K2 on ellipses at nu = 0.5 reproduces Kalker's nu = 0.5 column within the 2 % the nu = 0.25 cases
// of tests/adhesion_test.cpp use (same options: 1500 elements, alpha 0 / 0.5 for the spin column).
class IncompressibleAgainstKalker : public ::testing::TestWithParam<double> {};

TEST_P(IncompressibleAgainstKalker, CoefficientsWithinTwoPercentOfTheTable) {
  const double a_over_b = GetParam();
  EllipseCoefficientOptions options;
  options.target_elements = 1500;
  const EllipseCoefficientResult r = ellipse_creepage_coefficients(a_over_b, 0.5, options);
  const KalkerCoefficients table = kalker_coefficients(a_over_b, 0.5);
  EXPECT_NEAR(r.coefficients.C11 / table.C11, 1.0, 0.02);
  EXPECT_NEAR(r.coefficients.C22 / table.C22, 1.0, 0.02);
  EXPECT_NEAR(r.coefficients.C23 / table.C23, 1.0, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Ellipses, IncompressibleAgainstKalker, ::testing::Values(0.5, 1.0, 2.0));

// Hertz (E* = E / (2 (1 - nu^2)) = E/1.5) against the normal solver at nu = 0.5, the tolerances of
// tests/normal_test.cpp: approach, p0 and area within 1 % on a 141 x 141 mesh over 1.2 a x 1.2 b.
TEST(Incompressible, HertzMatchesTheNormalSolver) {
  const Material incompressible{2.1e11, 0.5};
  const double A = 1.0 / (2 * 0.46), B = 1.0 / (2 * 0.3);
  const HertzContact hertz = hertz_from_curvatures(A, B, 98.1e3, incompressible);
  const Mesh mesh = Mesh::covering(-1.2 * hertz.a_m, 1.2 * hertz.a_m, -1.2 * hertz.b_m, 1.2 * hertz.b_m, 141, 141);
  std::vector<double> h(mesh.size());
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1) h[mesh.index(i1, i2)] = A * mesh.x1(i1) * mesh.x1(i1) + B * mesh.x2(i2) * mesh.x2(i2);
  const NormalSolution s = solve_normal_contact(mesh, h, 98.1e3, incompressible);
  ASSERT_TRUE(s.converged);
  const double p0 = *std::max_element(s.pressure_Pa.begin(), s.pressure_Pa.end());
  const double area = static_cast<double>(s.elements_in_contact) * mesh.element_area_m2();
  EXPECT_NEAR(p0 / hertz.max_pressure_Pa, 1.0, 0.01);
  EXPECT_NEAR(s.approach_m / hertz.approach_m, 1.0, 0.01);
  EXPECT_NEAR(area / (M_PI * hertz.a_m * hertz.b_m), 1.0, 0.01);
  // And differs from nu = 0.3 by the contact modulus: a^3 ∝ 1/E*.
  const HertzContact steel = hertz_from_curvatures(A, B, 98.1e3, kSteel);
  EXPECT_NEAR(std::pow(steel.a_m / hertz.a_m, 3), incompressible.contact_modulus_Pa() / kSteel.contact_modulus_Pa(), 1e-9);
}

TEST(Incompressible, CliAcceptsNuOneHalf) {
  const CommandResult r = run_cli("coefficients --a-over-b 1 --nu 0.5 --elements 1500 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["nu"].get<double>(), 0.5);
  for (const char* key : {"C11", "C22", "C23"}) EXPECT_LT(std::fabs(j["rel_error"][key].get<double>()), 0.02) << key;
  expect_one_error_line(run_cli("coefficients --a-over-b 1 --nu 0.51"), "--nu 0.51 must lie in [0, 0.5]");
  expect_one_error_line(run_cli("coefficients --a-over-b 1 --nu -0.1"), "--nu -0.1 must lie in [0, 0.5]");
}

// ---- Issue 28: physical ranges of the ellipse, the wheelset's rates and the track -----------------

TEST(EllipseRanges, SemiAxesAndCurvaturesOutsideTheirRangeAreRefusedByTheLibrary) {
  // a = b = 1e-9 m at 98 kN gave p0 = 4.7e16 MPa; A = B = 1e-300 a 6.8e97 mm ellipse; 1e300 an
  // internal error.
  expect_error([] { (void)hertzian_patch(elliptical_contact(1e-9, 1e-9, 20), 1e-9, 1e-9, 98100.0, kSteel); },
               ErrorKind::invalid_input, {"Hertzian patch: the semi-axis a = 1e-09 m must lie in [1e-05, 0.1] m"});
  expect_error([] { (void)hertz_curvatures_for_semi_axes(6e-3, 0.5, 98100.0, kSteel); }, ErrorKind::invalid_input,
               {"hertz: the semi-axis b = 0.5 m must lie in [1e-05, 0.1] m"});
  expect_error([] { (void)hertz_from_curvatures(1e-300, 1e-300, 98100.0, kSteel); }, ErrorKind::invalid_input,
               {"hertz: the relative curvature A = 1e-300 1/m must lie in [0.001, 10000] 1/m"});
  expect_error([] { (void)hertz_from_curvatures(1e300, 1e300, 98100.0, kSteel); }, ErrorKind::invalid_input,
               {"hertz: the relative curvature A = 1e+300 1/m"});
  // Each curvature in range, the ellipse they give under the load is not: the message names the
  // inputs (A, B, F3, E), not the derived semi-axes alone.
  expect_error([] { (void)hertz_from_curvatures(1e-3, 1e-3, 1e7, kSteel); }, ErrorKind::invalid_input,
               {"hertz: the curvatures A = 0.001 1/m, B = 0.001 1/m (with E = 2.1e+11 Pa) under F3 = 1e+07 N give an "
                "ellipse of semi-axes"});
  expect_error([] { (void)hertz_from_semi_axes(2e-5, 2e-5, 98100.0, kSteel); }, ErrorKind::invalid_input,
               {"hertz: the semi-axes a = 2e-05 m, b = 2e-05 m under F3 = 98100 N give a maximum pressure"});
  // The axis ratio limits the meshes of the solvers (Hertz's closed form takes any).
  expect_error([] { (void)hertzian_patch(elliptical_contact(6e-3, 4e-5, 20), 6e-3, 4e-5, 98100.0, kSteel); },
               ErrorKind::invalid_input,
               {"Hertzian patch: the semi-axes a = 0.006 m, b = 4e-05 m give an ellipse of a/b = 150, outside [0.01, 100]"});
  // Within the ranges: a wheel-rail ellipse, and the limits themselves.
  EXPECT_NO_THROW((void)hertz_from_curvatures(1.1, 5.0, 98100.0, kSteel));
  EXPECT_NO_THROW((void)hertz_curvatures_for_semi_axes(kMaximumSemiAxis_m, kMaximumSemiAxis_m, 98100.0, kSteel));
  EXPECT_NO_THROW((void)hertz_from_semi_axes(kMinimumSemiAxis_m, kMinimumSemiAxis_m, 1.0, kSteel));
}

// hertz_from_semi_axes (p0 and the approach from a, b directly) against the round trip through the
// curvatures (hertz_curvatures_for_semi_axes, then hertz_from_curvatures: a root search for b/a):
// the same closed form, to the few ulps of the root search (relative 1e-12).
TEST(EllipseRanges, HertzFromSemiAxesEqualsTheRoundTripThroughTheCurvatures) {
  for (const auto [a, b] : {std::pair{6e-3, 4e-3}, std::pair{3e-3, 9e-3}, std::pair{5e-3, 5e-3}}) {
    const HertzContact direct = hertz_from_semi_axes(a, b, 98100.0, kSteel);
    const HertzCurvatures c = hertz_curvatures_for_semi_axes(a, b, 98100.0, kSteel);
    const HertzContact round_trip = hertz_from_curvatures(c.A_per_m, c.B_per_m, 98100.0, kSteel);
    EXPECT_NEAR(direct.approach_m, round_trip.approach_m, 1e-12 * round_trip.approach_m);
    EXPECT_NEAR(direct.max_pressure_Pa, round_trip.max_pressure_Pa, 1e-12 * round_trip.max_pressure_Pa);
  }
}

TEST(EllipseRanges, CaseFilesNameTheKey) {
  const std::string data = RAILCONTACT_SOURCE_DIR "/tests/data/bad_inputs/";
  CommandResult r = run_cli("run " + data + "ellipse_nanometre.toml");
  expect_one_error_line(r, "[geometry] a = 1e-09 m must lie in [1e-05, 0.1] m");
  EXPECT_EQ(r.exit_code, 2);
  r = run_cli("run " + data + "ellipse_flat_curvatures.toml");
  expect_one_error_line(r, "[geometry] A = 1e-300 1/m must lie in [0.001, 10000] 1/m");
  EXPECT_EQ(r.exit_code, 2);
  r = run_cli("run " + data + "ellipse_sharp_curvatures.toml");
  expect_one_error_line(r, "[geometry] A = 1e+300 1/m must lie in");
  EXPECT_EQ(r.exit_code, 2);
  // Semi-axes in millimetres where metres are meant.
  const ScratchDirectory dir("values_ellipse_mm");
  std::string text = ellipse_case();
  text.replace(text.find("a = 0.006\nb = 0.004"), 19, "a = 6.0\nb = 4.0");
  r = run_cli("run " + write_case(dir, "mm.toml", text));
  expect_one_error_line(r, "[geometry] a = 6 m must lie in [1e-05, 0.1] m (a contact patch from a laboratory "
                           "micro-contact to beyond a rail head; the semi-axes are in metres: is it given in "
                           "millimetres?)");
}

TEST(WheelsetRates, EveryRateOutsideItsRangeIsNamedAsGiven) {
  WheelsetVelocity v;
  v.yaw_rate_rad_per_s = 1e300;
  expect_error([&] { validate(v); }, ErrorKind::invalid_input,
               {"wheelset: yaw_rate_rad_per_s = 1e+300 rad/s must lie in [-10, 10] rad/s"});
  v = {};
  v.forward_speed_m_per_s = 0.0;
  expect_error([&] { validate(v); }, ErrorKind::invalid_input,
               {"wheelset: forward_speed_m_per_s = 0 m/s must lie in (0, 200] m/s"});
  v = {};
  v.lateral_velocity_m_per_s = -11.0;
  expect_error([&] { validate(v); }, ErrorKind::invalid_input, {"lateral_velocity_m_per_s = -11 m/s must lie in [-10, 10]"});
  v = {};
  v.vertical_velocity_m_per_s = kNaN;
  expect_error([&] { validate(v); }, ErrorKind::invalid_input, {"vertical_velocity_m_per_s = nan m/s"});
  v = {};
  v.roll_rate_rad_per_s = 20.0;
  expect_error([&] { validate(v); }, ErrorKind::invalid_input, {"roll_rate_rad_per_s = 20 rad/s"});
  v = {};
  v.wheel_angular_velocity_rad_per_s = 2000.0;
  expect_error([&] { validate(v); }, ErrorKind::invalid_input,
               {"wheel_angular_velocity_rad_per_s = 2000 rad/s must lie in [-1000, 1000] rad/s"});
  v = {};
  v.extra_longitudinal_creepage = 0.9;
  expect_error([&] { validate(v); }, ErrorKind::invalid_input, {"extra_longitudinal_creepage = 0.9 must lie in [-0.5, 0.5]"});
  // Options are named as options.
  v = {};
  v.yaw_rate_rad_per_s = 1e6;
  WheelsetVelocityNames names;
  names.yaw_rate = "--yaw-rate-rad-per-s";
  expect_error([&] { validate(v, names); }, ErrorKind::invalid_input, {"--yaw-rate-rad-per-s 1e+06 rad/s must lie in [-10, 10] rad/s"});
  // The limits are velocities.
  v = {};
  v.forward_speed_m_per_s = kMaximumForwardSpeed_m_per_s;
  v.yaw_rate_rad_per_s = -kMaximumRollYawRate_rad_per_s;
  v.wheel_angular_velocity_rad_per_s = kMaximumWheelAngularVelocity_rad_per_s;
  EXPECT_NO_THROW(validate(v));
}

// The kinematic creepage of a contact beyond a contact's range names the velocity that gives it:
// a contact 0.75 m left of the centre on the right wheel... (the creepages are linear in the
// velocities; the largest share is named).
TEST(WheelsetRates, KinematicCreepageBeyondAContactsRangeNamesTheRate) {
  WheelsetMotion m;
  m.forward_speed_m_per_s = 1.0;
  m.wheel_angular_velocity_rad_per_s = 1.0 / 0.46;
  m.yaw_rate_rad_per_s = 10.0;
  const ContactFrame frame = contact_frame({0.0, -0.75, -0.46}, 0.03, WheelSide::right);
  const Creepage c = kinematic_creepage(m, frame);
  ASSERT_GT(std::abs(c.xi), kMaximumCreepage);
  expect_error([&] { check_kinematic_creepage(c, m, frame, WheelSide::right); }, ErrorKind::invalid_input,
               {"wheelset: the yaw rate yaw_rate_rad_per_s = 10 rad/s at the forward speed V = 1 m/s gives the right "
                "wheel's contact a longitudinal creepage xi = 7.5",
                "beyond [-0.5, 0.5]"});
  m.yaw_rate_rad_per_s = 0.1;  // xi = 0.075: a contact's creepage
  EXPECT_NO_THROW(check_kinematic_creepage(kinematic_creepage(m, frame), m, frame, WheelSide::right));
}

TEST(WheelsetRates, CliAndCaseNameTheOptionAndTheKey) {
  CommandResult r = run_cli("wheelset --yaw-rate-rad-per-s 1e6");
  expect_one_error_line(r, "--yaw-rate-rad-per-s 1e+06 rad/s must lie in [-10, 10] rad/s");
  EXPECT_EQ(r.exit_code, 2);
  r = run_cli("wheelset --yaw-rate-rad-per-s 1e300");
  expect_one_error_line(r, "--yaw-rate-rad-per-s 1e+300 rad/s must lie in [-10, 10] rad/s");
  r = run_cli("wheelset --speed-m-per-s 1e6");
  expect_one_error_line(r, "--speed-m-per-s 1e+06 m/s must lie in (0, 200] m/s");
  r = run_cli("wheelset --lateral-velocity-m-per-s -50");
  expect_one_error_line(r, "--lateral-velocity-m-per-s -50 m/s must lie in [-10, 10] m/s");
  r = run_cli("wheelset --extra-creepage 0.9");
  expect_one_error_line(r, "--extra-creepage 0.9 must lie in [-0.5, 0.5]");
  r = run_cli(std::string("wheelset ") + RAILCONTACT_SOURCE_DIR "/tests/data/bad_inputs/wheelset_yaw_rate.toml");
  expect_one_error_line(r, "wheelset_yaw_rate.toml:3: [velocity] yaw_rate_rad_per_s = 1e+06 rad/s must lie in [-10, 10]");
  EXPECT_EQ(r.exit_code, 2);
  // Rates in range whose combination is not: the creepage, named by its rate, before the tangential solve.
  r = run_cli("wheelset --yaw-rate-rad-per-s 10 --speed-m-per-s 1 --element-size-m 0.0005");
  expect_one_error_line(r, "the yaw rate yaw_rate_rad_per_s = 10 rad/s at the forward speed V = 1 m/s gives the right "
                           "wheel's contact a longitudinal creepage xi =");
  EXPECT_EQ(r.exit_code, 2);
}

TEST(TrackRanges, EveryTrackParameterIsCheckedAgainstItsRange) {
  const TrackWheelsetParameters ok;
  EXPECT_NO_THROW(validate(ok));
  const auto refused = [](TrackWheelsetParameters p, const std::string& part) {
    expect_error([&] { validate(p); }, ErrorKind::invalid_input, {part});
  };
  TrackWheelsetParameters p;
  p.nominal_rolling_radius_m = 46;
  refused(p, "track parameters: nominal_rolling_radius_m = 46 m must lie in [0.04, 1.5] m (from a scale roller-rig wheel "
             "to a locomotive's driving wheel; 0.46 for a UIC wheel); the value is in metres: 46 mm would be 0.046 m");
  p = {};
  p.track_gauge_m = 1435;
  refused(p, "track_gauge_m = 1435 m must lie in [0.38, 2.2] m");
  p = {};
  p.gauge_measuring_depth_m = 0.0;
  refused(p, "gauge_measuring_depth_m = 0 m must lie in [0.001, 0.03] m");
  p = {};
  p.flange_back_distance_m = 0.1;
  refused(p, "flange_back_distance_m = 0.1 m must lie in [0.3, 2.2] m");
  p = {};
  p.flange_back_y_m = -0.5;
  refused(p, "flange_back_y_m = -0.5 m must lie in [-0.2, 0.2] m");
  p = {};
  p.taping_line_from_flange_back_m = 70;
  refused(p, "taping_line_from_flange_back_m = 70 m must lie in [0.01, 0.2] m");
  p = {};
  p.flange_back_distance_m = 1.5;
  refused(p, "track_gauge_m - flange_back_distance_m = 1.435 - 1.5 = -0.065 m must lie in [0.02, 0.2] m");
  // Metre gauge with its flange backs.
  p = {};
  p.track_gauge_m = 1.000;
  p.flange_back_distance_m = 0.930;
  EXPECT_NO_THROW(validate(p));
}

TEST(TrackRanges, SetUpFileAndGeometryOptionsNameTheKeyAndTheOption) {
  CommandResult r = run_cli(std::string("wheelset ") + RAILCONTACT_SOURCE_DIR "/tests/data/bad_inputs/wheelset_setup_radius_46.toml");
  expect_one_error_line(r, "setup_radius_46.json: track: nominal_rolling_radius_m = 46 m must lie in [0.04, 1.5] m");
  EXPECT_NE(r.err.find("46 mm would be 0.046 m"), std::string::npos) << r.err;
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(run_cli("geometry --rolling-radius-m 46"), "--rolling-radius-m 46 m must lie in [0.04, 1.5] m");
  expect_one_error_line(run_cli("geometry --gauge-m 1"),
                        "the gauge 1 m less the flange backs' distance 1.36 m (--gauge-m, --flange-back-m) is -0.36 m");
}

}  // namespace
}  // namespace railcontact
