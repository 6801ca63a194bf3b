// Case files: a valid file is read as written; every kind of bad input gives one clear error
// naming the file, the line and the key.
#include <gtest/gtest.h>

#include <string>

#include "case/case.hpp"
#include "railcontact/error.hpp"

namespace railcontact {
namespace {

const std::string kValid = R"(
[geometry]
type = "ellipse"
a = 0.006
b = 0.004
[material]
E = 2.1e11
nu = 0.3
[load]
normal_force = 98100.0
[friction]
mu = 0.3
[creepage]
xi = 0.001
eta = -0.0005
phi = 0.2
[mesh]
elements = 1500
[solvers]
run = ["exact", "nh-fastsim"]
)";

TEST(CaseFile, ReadsEveryKey) {
  const Case c = parse_case(kValid, "valid.toml");
  EXPECT_EQ(c.geometry, GeometryKind::ellipse);
  EXPECT_DOUBLE_EQ(*c.ellipse.a_m, 0.006);
  EXPECT_DOUBLE_EQ(*c.ellipse.b_m, 0.004);
  EXPECT_DOUBLE_EQ(c.material.youngs_modulus_Pa, 2.1e11);
  EXPECT_DOUBLE_EQ(c.material.poisson_ratio, 0.3);
  EXPECT_DOUBLE_EQ(c.normal_force_N, 98100.0);
  EXPECT_DOUBLE_EQ(c.mu, 0.3);
  EXPECT_DOUBLE_EQ(c.creepage.raw.xi, 0.001);
  EXPECT_DOUBLE_EQ(c.creepage.raw.eta, -0.0005);
  EXPECT_DOUBLE_EQ(c.creepage.raw.phi, 0.2);
  EXPECT_EQ(c.target_elements, 1500);
  ASSERT_EQ(c.solvers.size(), 2u);
  EXPECT_EQ(c.solvers[0], TangentialSolver::exact);
  EXPECT_EQ(c.solvers[1], TangentialSolver::nh_fastsim);
  EXPECT_EQ(c.bound_skew, TractionBound{}.skew);  // defaults
  EXPECT_EQ(c.flexibility_coarsening, 0);         // automatic
}


TEST(CaseFile, ShearModulusAndCurvaturesAreAccepted) {
  std::string text = kValid;
  text.replace(text.find("E = 2.1e11"), 10, "G = 8.0e10");
  text.replace(text.find("a = 0.006\nb = 0.004"), 19, "A = 1.087\nB = 1.667");
  const Case c = parse_case(text, "g.toml");
  EXPECT_NEAR(c.material.shear_modulus_Pa(), 8.0e10, 1.0);
  EXPECT_DOUBLE_EQ(*c.ellipse.A_per_m, 1.087);
}

std::string error_of(const std::string& text) {
  try {
    parse_case(text, "case.toml");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(CaseFile, SolverOptionsBoundSkewAndCoarsening) {
  const Case c = parse_case(replaced(kValid, "run = [", "bound_skew = 0\nflexibility_coarsening = 2\nrun = ["), "s.toml");
  EXPECT_EQ(c.bound_skew, 0.0);
  EXPECT_EQ(c.flexibility_coarsening, 2);
  EXPECT_NE(error_of(replaced(kValid, "run = [", "bound_skew = 1.5\nrun = [")).find("bound_skew must lie in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "run = [", "bound_skew = nan\nrun = [")).find("bound_skew"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "run = [", "flexibility_coarsening = 9\nrun = [")).find("an integer from 1 to 8"),
            std::string::npos);
}

TEST(CaseFile, MalformedTomlNamesTheLine) {
  const std::string e = error_of(replaced(kValid, "mu = 0.3", "mu = = 0.3"));
  EXPECT_NE(e.find("case.toml:12"), std::string::npos) << e;
  EXPECT_NE(e.find("malformed"), std::string::npos) << e;
}

TEST(CaseFile, UnknownKeyNamesKeyAndLine) {
  const std::string e = error_of(replaced(kValid, "mu = 0.3", "mu = 0.3\nmue = 0.4"));
  EXPECT_NE(e.find("case.toml:13"), std::string::npos) << e;
  EXPECT_NE(e.find("'mue'"), std::string::npos) << e;
  EXPECT_NE(error_of(kValid + "[extra]\nx = 1\n").find("'extra'"), std::string::npos);
}

TEST(CaseFile, MissingSectionsAndKeys) {
  EXPECT_NE(error_of(replaced(kValid, "[friction]\nmu = 0.3\n", "")).find("missing section [friction]"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "normal_force = 98100.0", "")).find("'normal_force'"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "b = 0.004\n", "")).find("a and b"), std::string::npos);
}

TEST(CaseFile, NonPhysicalValues) {
  EXPECT_NE(error_of(replaced(kValid, "mu = 0.3", "mu = 0")).find("mu must be positive"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "mu = 0.3", "mu = -0.2")).find("mu"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "xi = 0.001", "xi = nan")).find("finite"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "phi = 0.2", "phi = inf")).find("finite"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "xi = 0.001", "xi = 3.0")).find("absurd"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "phi = 0.2", "phi = 5000")).find("absurd"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "nu = 0.3", "nu = 0.51")).find("nu"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "normal_force = 98100.0", "normal_force = -1")).find("positive"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "a = 0.006", "a = \"big\"")).find("must be a number"), std::string::npos);
  EXPECT_NE(error_of(replaced(kValid, "elements = 1500", "elements = 1e9")).find("elements"), std::string::npos);
}

TEST(CaseFile, UnknownSolverName) {
  const std::string e = error_of(replaced(kValid, "\"nh-fastsim\"", "\"contact\""));
  EXPECT_NE(e.find("unknown solver 'contact'"), std::string::npos) << e;
  EXPECT_NE(e.find("case.toml:20"), std::string::npos) << e;
}

TEST(CaseFile, NormalisedCreepageNeedsAWheelRailPatch) {
  EXPECT_NE(error_of(replaced(kValid, "xi = 0.001", "xi_normalised = 0.5")).find("wheel-rail"), std::string::npos);
}

TEST(CaseFile, WheelRailContactReference) {
  const std::string wheel_rail = replaced(kValid, "type = \"ellipse\"\na = 0.006\nb = 0.004", "type = \"wheel-rail\"\ny = -0.002");
  const Case smooth = parse_case(wheel_rail, "wr.toml");
  EXPECT_EQ(smooth.geometry, GeometryKind::wheel_rail);
  EXPECT_DOUBLE_EQ(smooth.wheel_rail.y_m, -0.002);
  EXPECT_EQ(smooth.wheel_rail.reference, ContactReference::smooth);  // the default
  const Case first = parse_case(replaced(wheel_rail, "y = -0.002", "y = -0.002\ncontact_reference = \"first-touch\""), "wr.toml");
  EXPECT_EQ(first.wheel_rail.reference, ContactReference::first_touch);
  EXPECT_EQ(error_of(replaced(wheel_rail, "y = -0.002", "y = -0.002\ncontact_reference = \"centre\"")),
            "case.toml:5: [geometry] contact_reference must be \"smooth\" or \"first-touch\" (got \"centre\")");
}

// A solver named twice would run twice and print two rows: one error naming the key, the
// solver and the line of the second mention.
TEST(CaseFile, SolverNamedTwice) {
  const std::string e = error_of(replaced(kValid, "run = [\"exact\", \"nh-fastsim\"]", "run = [\"fastsim\", \"fastsim\"]"));
  EXPECT_NE(e.find("case.toml:20: [solvers] run names 'fastsim' twice"), std::string::npos) << e;
}

// The semi-axes and the curvatures give the ellipse two ways: any semi-axis with any curvature is
// an error naming both keys (with a, b and A, one of them would be ignored).
TEST(CaseFile, EllipseSemiAxesAndCurvaturesTogether) {
  std::string e = error_of(replaced(kValid, "b = 0.004", "b = 0.004\nA = 1.087"));
  EXPECT_NE(e.find("case.toml:6: [geometry] a and A both give the ellipse"), std::string::npos) << e;
  e = error_of(replaced(kValid, "a = 0.006\nb = 0.004", "a = 0.006\nA = 1.087\nB = 1.667"));
  EXPECT_NE(e.find("[geometry] a and A both give the ellipse"), std::string::npos) << e;
  e = error_of(replaced(kValid, "a = 0.006\nb = 0.004", "b = 0.004\nA = 1.087\nB = 1.667"));
  EXPECT_NE(e.find("[geometry] b and A both give the ellipse"), std::string::npos) << e;
}

TEST(CaseFile, MissingFile) { EXPECT_THROW(read_case_file("/nonexistent/case.toml"), Error); }

}  // namespace
}  // namespace railcontact
