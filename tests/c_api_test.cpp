// The C API (include/railcontact/railcontact.h, docs/C_API.md): the same numbers as the C++ API,
// statuses and messages for bad input, batches and handles on several threads equal to the serial
// loop, the flexibility table.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"
#include "different_paths.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/railcontact.h"
#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};
constexpr double kA = 6e-3, kB = 4e-3, kF3 = 8e4, kMu = 0.3;
constexpr int kElements = 600;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A solver handle that is destroyed with the test.
struct Solver {
  rc_solver* h = nullptr;
  explicit Solver(int method = RC_METHOD_NH_FASTSIM, double elements = kElements) {
    EXPECT_EQ(rc_solver_create(&h), RC_OK);
    rc_settings s;
    rc_settings_default(&s);
    s.method = method;
    s.mesh_value = elements;
    EXPECT_EQ(rc_solver_set_settings(h, &s), RC_OK);
  }
  ~Solver() { rc_solver_destroy(h); }
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;
  std::string error() const {
    std::size_t length = 0;
    rc_solver_last_error(h, nullptr, 0, &length);
    std::string message(length + 1, '\0');
    rc_solver_last_error(h, message.data(), message.size(), nullptr);
    message.resize(length);
    return message;
  }
};

ContactPatch cpp_ellipse(double a, double b, double F3, int elements) {
  return hertzian_patch(elliptical_contact_with_count(a, b, elements, EllipseMeshLayout::rolling_resolved), a, b, F3,
                        kSteel);
}

rc_patch ellipse(double a, double b, double F3) {
  rc_patch p{};
  p.kind = RC_GEOMETRY_ELLIPSE;
  p.a_m = a;
  p.b_m = b;
  p.normal_force_N = F3;
  return p;
}

TEST(CApi, VersionAndStatusStrings) {
  EXPECT_STREQ(rc_version_string(), RC_VERSION_STRING);
  int major = -1, minor = -1, patch = -1;
  EXPECT_EQ(rc_version(&major, &minor, &patch), RC_OK);
  EXPECT_EQ(std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch), RC_VERSION_STRING);
  EXPECT_EQ(rc_abi_version(), RC_ABI_VERSION);
  EXPECT_STREQ(rc_status_string(RC_OK), "ok");
  EXPECT_STREQ(rc_status_string(RC_NOT_CONVERGED), "not converged");
  EXPECT_STREQ(rc_status_string(RC_BUFFER_TOO_SMALL), "buffer too small");
  EXPECT_STREQ(rc_status_string(42), "unknown status");
}

// One version everywhere: the CLI prints the C API's.
TEST(CApi, CliPrintsTheVersion) {
  const test::CommandResult r = test::run_cli("--version");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, std::string("railcontact ") + rc_version_string() + "\n");
}

// Every method gives the C++ API's numbers on the same patch: the exact solvers to the last bit
// (the same functions), nH-FastSim and FastSim within test::kDifferentPathsRelative of mu F3 (the
// C API marches with forces_and_adhesion, the C++ call with forces: different code,
// tests/different_paths.hpp).
TEST(CApi, EllipseEqualsTheCppApiForEveryMethod) {
  const ContactPatch patch = cpp_ellipse(kA, kB, kF3, kElements);
  const Creepage c{1e-3, -5e-4, 0.4};
  const rc_creepage cc{c.xi, c.eta, c.phi};
  const TangentialForces expected[4] = {
      NhFastSim(patch).forces(c, kMu),
      FastSim(patch, TractionBound::parabolic()).forces(c, fastsim_flexibility(kA, kB, kSteel), kMu),
      solve_rolling_exact(patch, c, kMu).forces,
      solve_rolling_regularised(patch, c, kMu).forces,
  };
  for (int method = 0; method < 4; ++method) {
    Solver s(method);
    ASSERT_EQ(rc_solver_set_ellipse(s.h, kA, kB, kF3), RC_OK) << s.error();
    rc_forces f{};
    ASSERT_EQ(rc_solver_solve(s.h, &cc, &f), RC_OK) << s.error();
    if (method == RC_METHOD_NH_FASTSIM || method == RC_METHOD_FASTSIM) {
      test::expect_forces_near(f, expected[method], kMu * kF3, kA, std::to_string(method));
    } else {
      EXPECT_EQ(f.F1_N, expected[method].F1_N) << method;
      EXPECT_EQ(f.F2_N, expected[method].F2_N) << method;
      EXPECT_EQ(f.M3_Nm, expected[method].M3_Nm) << method;
    }
    EXPECT_GT(f.adhesion_fraction, 0.0);
    EXPECT_LT(f.adhesion_fraction, 1.0);
  }
}

// rc_settings.slip_direction reaches NhFastSim's bound: radial by default, flexibility-weighted on
// request, each equal to the C++ call within test::kDifferentPathsRelative of mu F3 (the C API's
// forces_and_adhesion against NhFastSim::forces: different code, tests/different_paths.hpp), and
// the two differ in deep slip with spin (where the weighting turns the slipping traction).
TEST(CApi, SlipDirectionReachesNhFastSim) {
  const ContactPatch patch = cpp_ellipse(kA, kB, kF3, kElements);
  const Creepage c{3e-3, -2e-3, 2.0};
  const rc_creepage cc{c.xi, c.eta, c.phi};
  rc_settings s;
  rc_settings_default(&s);
  EXPECT_EQ(s.slip_direction, RC_SLIP_RADIAL);
  rc_forces forces[4]{};
  for (const int direction : {RC_SLIP_RADIAL, RC_SLIP_FLEXIBILITY_WEIGHTED, RC_SLIP_RIGID, RC_SLIP_ELASTIC}) {
    Solver solver;
    rc_settings_default(&s);
    s.mesh_value = kElements;
    s.slip_direction = direction;
    ASSERT_EQ(rc_solver_set_settings(solver.h, &s), RC_OK) << solver.error();
    ASSERT_EQ(rc_solver_set_ellipse(solver.h, kA, kB, kF3), RC_OK) << solver.error();
    rc_forces& f = forces[direction];
    ASSERT_EQ(rc_solver_solve(solver.h, &cc, &f), RC_OK) << solver.error();
    NhFastSimOptions options;
    options.bound.slip_direction = static_cast<SlipDirection>(direction);  // the same numbers
    const TangentialForces expected = NhFastSim(patch, options).forces(c, kMu);
    test::expect_forces_near(f, expected, kMu * kF3, kA, std::to_string(direction));
  }
  EXPECT_GT(std::fabs(forces[1].F1_N - forces[0].F1_N), 1e-3 * kMu * kF3);
  EXPECT_GT(std::fabs(forces[2].F1_N - forces[1].F1_N), 1e-4 * kMu * kF3);

  Solver solver;
  rc_settings_default(&s);
  s.slip_direction = 4;
  EXPECT_EQ(rc_solver_set_settings(solver.h, &s), RC_INVALID_INPUT);
  EXPECT_NE(solver.error().find("rc_settings.slip_direction = 4 is not an rc_slip_direction (0 radial, 1 "
                                "flexibility-weighted, 2 rigid-slip, 3 elastic-slip)"),
            std::string::npos)
      << solver.error();
}

TEST(CApi, NormalResultsOfAnEllipseAndOfHertz) {
  const HertzContact h = hertz_from_curvatures(5.0, 8.0, kF3, kSteel);
  Solver s;
  ASSERT_EQ(rc_solver_set_hertz(s.h, 5.0, 8.0, kF3), RC_OK) << s.error();
  rc_normal_result n{};
  ASSERT_EQ(rc_solver_normal_result(s.h, &n), RC_OK);
  EXPECT_DOUBLE_EQ(n.a_m, h.a_m);
  EXPECT_DOUBLE_EQ(n.b_m, h.b_m);
  EXPECT_DOUBLE_EQ(n.approach_m, h.approach_m);
  EXPECT_NEAR(n.normal_force_N, kF3, 1e-9 * kF3);
  EXPECT_NEAR(n.area_m2, M_PI * h.a_m * h.b_m, 0.05 * M_PI * h.a_m * h.b_m);
  EXPECT_NEAR(n.max_pressure_Pa, h.max_pressure_Pa, 0.03 * h.max_pressure_Pa);
  EXPECT_NEAR(n.elements_in_contact, kElements, 0.15 * kElements);
  // The same ellipse given by its semi-axes: the same patch and Hertz's approach.
  Solver e;
  ASSERT_EQ(rc_solver_set_ellipse(e.h, h.a_m, h.b_m, kF3), RC_OK) << e.error();
  rc_normal_result ne{};
  ASSERT_EQ(rc_solver_normal_result(e.h, &ne), RC_OK);
  EXPECT_NEAR(ne.approach_m, h.approach_m, 1e-9 * h.approach_m);
  EXPECT_EQ(ne.elements_in_contact, n.elements_in_contact);
}

// A grid of h = A x1^2 + B x2^2: the normal solver's patch, equal to the C++ API's, close to Hertz.
TEST(CApi, GridEqualsTheCppApiAndHertz) {
  const double A = 5.0, B = 8.0;
  const HertzContact hz = hertz_from_curvatures(A, B, kF3, kSteel);
  const int n1 = 40, n2 = 32;
  const double dx1 = 3.0 * hz.a_m / n1, dx2 = 3.0 * hz.b_m / n2;
  std::vector<double> h(static_cast<std::size_t>(n1) * n2);
  for (int i2 = 0; i2 < n2; ++i2)
    for (int i1 = 0; i1 < n1; ++i1) {
      const double x1 = (i1 - 0.5 * (n1 - 1)) * dx1, x2 = (i2 - 0.5 * (n2 - 1)) * dx2;
      h[static_cast<std::size_t>(i2) * n1 + i1] = A * x1 * x1 + B * x2 * x2;
    }
  Solver s;
  ASSERT_EQ(rc_solver_set_grid(s.h, n1, n2, dx1, dx2, h.data(), kF3), RC_OK) << s.error();
  rc_normal_result n{};
  ASSERT_EQ(rc_solver_normal_result(s.h, &n), RC_OK);
  EXPECT_NEAR(n.area_m2, M_PI * hz.a_m * hz.b_m, 0.05 * M_PI * hz.a_m * hz.b_m);
  EXPECT_NEAR(n.approach_m, hz.approach_m, 0.02 * hz.approach_m);
  EXPECT_NEAR(n.max_pressure_Pa, hz.max_pressure_Pa, 0.05 * hz.max_pressure_Pa);

  Mesh mesh;
  mesh.n1 = n1;
  mesh.n2 = n2;
  mesh.dx1_m = dx1;
  mesh.dx2_m = dx2;
  mesh.x1_first_m = -0.5 * (n1 - 1) * dx1;
  mesh.x2_first_m = -0.5 * (n2 - 1) * dx2;
  const NormalSolution normal = solve_normal_contact(mesh, h, kF3, kSteel);
  const ContactPatch patch(mesh, normal.pressure_Pa, kSteel);
  const Creepage c{2e-3, 1e-3, 0.0};
  const rc_creepage cc{c.xi, c.eta, c.phi};
  rc_forces f{};
  ASSERT_EQ(rc_solver_solve(s.h, &cc, &f), RC_OK) << s.error();
  const TangentialForces expected = NhFastSim(patch).forces(c, kMu);
  // forces_and_adhesion against forces: different code (tests/different_paths.hpp).
  test::expect_forces_near(f, expected, kMu * kF3, hz.a_m);
}

// Kalker's linear theory at small creepage, saturation at mu F3, odd symmetry in eta.
TEST(CApi, LinearTheorySaturationAndSymmetry) {
  Solver s(RC_METHOD_NH_FASTSIM, 2800);
  ASSERT_EQ(rc_solver_set_ellipse(s.h, kA, kB, kF3), RC_OK) << s.error();
  const KalkerCoefficients k = kalker_coefficients(kA / kB, kSteel.poisson_ratio);
  const double G = kSteel.shear_modulus_Pa(), c2 = kA * kB;
  rc_forces f{};
  const rc_creepage small{1e-6, 0, 0};
  ASSERT_EQ(rc_solver_solve(s.h, &small, &f), RC_OK);
  EXPECT_NEAR(f.F1_N, -G * c2 * k.C11 * 1e-6, 0.03 * G * c2 * k.C11 * 1e-6);
  EXPECT_DOUBLE_EQ(f.adhesion_fraction, 1.0);
  const rc_creepage large{0.05, 0, 0};
  ASSERT_EQ(rc_solver_solve(s.h, &large, &f), RC_OK);
  EXPECT_NEAR(f.F1_N, -kMu * kF3, 1e-3 * kMu * kF3);
  rc_forces plus{}, minus{};
  const rc_creepage ep{0, 1e-3, 0}, em{0, -1e-3, 0};
  ASSERT_EQ(rc_solver_solve(s.h, &ep, &plus), RC_OK);
  ASSERT_EQ(rc_solver_solve(s.h, &em, &minus), RC_OK);
  EXPECT_NEAR(plus.F2_N, -minus.F2_N, 1e-9 * std::abs(plus.F2_N));
  EXPECT_LT(plus.F2_N, 0.0);
}

TEST(CApi, TractionFieldsSumToTheForces) {
  Solver s(RC_METHOD_EXACT);
  ASSERT_EQ(rc_solver_set_ellipse(s.h, kA, kB, kF3), RC_OK);
  int n1 = 0, n2 = 0;
  std::size_t count = 0;
  EXPECT_EQ(rc_solver_traction_size(s.h, &n1, &n2, &count), RC_OK);
  EXPECT_EQ(count, static_cast<std::size_t>(n1) * n2);
  std::vector<double> p1(count), p2(count), p3(count);
  std::vector<int> slip(count);
  // Before a solve there are no fields.
  EXPECT_EQ(rc_solver_tractions(s.h, count, p1.data(), nullptr, nullptr, nullptr), RC_INVALID_INPUT);
  const rc_creepage c{1e-3, 1e-3, 0.5};
  rc_forces f{};
  ASSERT_EQ(rc_solver_solve(s.h, &c, &f), RC_OK);
  EXPECT_EQ(rc_solver_tractions(s.h, count - 1, p1.data(), nullptr, nullptr, nullptr), RC_BUFFER_TOO_SMALL);
  EXPECT_NE(s.error().find("rc_solver_traction_size"), std::string::npos) << s.error();
  ASSERT_EQ(rc_solver_tractions(s.h, count, p1.data(), p2.data(), p3.data(), slip.data()), RC_OK);
  rc_normal_result n{};
  ASSERT_EQ(rc_solver_normal_result(s.h, &n), RC_OK);
  double F1 = 0, F2 = 0, F3 = 0;
  int slipping = 0, in_contact = 0;
  for (std::size_t k = 0; k < count; ++k) {
    F1 += p1[k] * n.dx1_m * n.dx2_m;
    F2 += p2[k] * n.dx1_m * n.dx2_m;
    F3 += p3[k] * n.dx1_m * n.dx2_m;
    slipping += slip[k];
    in_contact += p3[k] > 0;
  }
  EXPECT_NEAR(F1, f.F1_N, 1e-9 * kF3);
  EXPECT_NEAR(F2, f.F2_N, 1e-9 * kF3);
  EXPECT_NEAR(F3, kF3, 1e-9 * kF3);
  EXPECT_EQ(in_contact, n.elements_in_contact);
  EXPECT_NEAR(1.0 - static_cast<double>(slipping) / in_contact, f.adhesion_fraction, 1e-12);
}

// The exact solvers' options changed after the patch was set reach the next solve: the patch keeps
// its normal solution and its tangential model is prepared again.
TEST(CApi, ExactSolverOptionsSetAfterThePatchTakeEffect) {
  Solver s(RC_METHOD_EXACT);
  ASSERT_EQ(rc_solver_set_ellipse(s.h, kA, kB, kF3), RC_OK);
  const rc_creepage c{1e-3, 1e-3, 0.5};
  rc_forces converged{};
  ASSERT_EQ(rc_solver_solve(s.h, &c, &converged), RC_OK);
  rc_settings settings;
  ASSERT_EQ(rc_solver_get_settings(s.h, &settings), RC_OK);
  settings.max_newton_iterations = 1;
  ASSERT_EQ(rc_solver_set_settings(s.h, &settings), RC_OK);
  rc_forces f{};
  EXPECT_EQ(rc_solver_solve(s.h, &c, &f), RC_NOT_CONVERGED) << "one Newton step cannot reach 1e-9";
  settings.max_newton_iterations = 100;
  settings.tolerance = 1e-4;  // looser: fewer steps, the same forces to ~1e-4 of mu F3
  ASSERT_EQ(rc_solver_set_settings(s.h, &settings), RC_OK);
  ASSERT_EQ(rc_solver_solve(s.h, &c, &f), RC_OK);
  EXPECT_NEAR(f.F1_N, converged.F1_N, 1e-3 * 0.3 * kF3);
  EXPECT_NE(f.F1_N, converged.F1_N);
}

TEST(CApi, JacobianAtSmallCreepageIsTheCreepageMatrix) {
  Solver s;
  ASSERT_EQ(rc_solver_set_ellipse(s.h, kA, kB, kF3), RC_OK);
  const NhFastSim nh(cpp_ellipse(kA, kB, kF3, kElements));
  const rc_creepage c{1e-5, 0, 0};
  double J[9];
  rc_forces f{};
  ASSERT_EQ(rc_solver_jacobian(s.h, &c, &f, J), RC_OK) << s.error();
  // In full adhesion FastSim is linear: the differences are the slopes of the C++ API's forces.
  const double h = 1e-6;
  EXPECT_NEAR(J[0], nh.forces(Creepage{h, 0, 0}, kMu).F1_N / h, 1e-6 * std::abs(J[0]));
  EXPECT_NEAR(J[4], nh.forces(Creepage{1e-5, h, 0}, kMu).F2_N / h, 1e-6 * std::abs(J[4]));
  EXPECT_NEAR(J[5], nh.forces(Creepage{1e-5, 0, 1e-4}, kMu).F2_N / 1e-4, 1e-6 * std::abs(J[5]));
  EXPECT_NEAR(J[1], 0.0, 1e-6 * std::abs(J[0]));
  // ... and close to the creepage coefficients of K2 the flexibilities were matched to (on the
  // patch coarsened for K2: a few per cent).
  EXPECT_NEAR(J[0], -nh.flexibilities().f11_N, 0.06 * nh.flexibilities().f11_N);
  EXPECT_NEAR(J[4], -nh.flexibilities().f22_N, 0.06 * nh.flexibilities().f22_N);
  EXPECT_NEAR(J[5], -nh.flexibilities().f23_Nm, 0.10 * nh.flexibilities().f23_Nm);
  // forces_and_adhesion against forces: different code (tests/different_paths.hpp).
  test::expect_forces_near(f, nh.forces(Creepage{1e-5, 0, 0}, kMu), kMu * kF3, kA);
}

TEST(CApi, BadInputGivesStatusAndMessage) {
  Solver s;
  EXPECT_EQ(rc_solver_set_ellipse(s.h, kNaN, kB, kF3), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_patch.a_m = nan"), std::string::npos) << s.error();
  EXPECT_EQ(rc_solver_set_ellipse(s.h, kA, kB, 1e300), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("too large"), std::string::npos) << s.error();
  EXPECT_EQ(rc_solver_set_hertz(s.h, 5.0, std::numeric_limits<double>::infinity(), kF3), RC_INVALID_INPUT);
  rc_forces f{};
  const rc_creepage c{1e-3, 0, 0};
  EXPECT_EQ(rc_solver_solve(s.h, &c, &f), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("no contact patch is set"), std::string::npos) << s.error();
  EXPECT_EQ(rc_solver_solve(s.h, nullptr, &f), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("creepage is null"), std::string::npos) << s.error();
  EXPECT_EQ(rc_solver_set_grid(s.h, 10, 10, 1e-3, 1e-3, nullptr, kF3), RC_INVALID_INPUT);
  ASSERT_EQ(rc_solver_set_ellipse(s.h, kA, kB, kF3), RC_OK);
  const rc_creepage bad{kNaN, 0, 0};
  EXPECT_EQ(rc_solver_solve(s.h, &bad, &f), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_creepage.xi = nan must lie in [-0.5, 0.5]"), std::string::npos) << s.error();

  rc_settings settings;
  rc_settings_default(&settings);
  settings.friction_coefficient = kNaN;
  EXPECT_EQ(rc_solver_set_settings(s.h, &settings), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_settings.friction_coefficient = nan"), std::string::npos) << s.error();
  rc_settings_default(&settings);
  settings.method = 7;
  EXPECT_EQ(rc_solver_set_settings(s.h, &settings), RC_INVALID_INPUT);
  rc_settings_default(&settings);
  settings.regularisation = 1.0;
  EXPECT_EQ(rc_solver_set_settings(s.h, &settings), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("regularisation"), std::string::npos) << s.error();
  // A failed set_settings keeps the previous settings.
  rc_settings kept;
  rc_solver_get_settings(s.h, &kept);
  EXPECT_EQ(kept.friction_coefficient, 0.3);

  // Null handles and the message buffer.
  EXPECT_EQ(rc_solver_solve(nullptr, &c, &f), RC_INVALID_INPUT);
  EXPECT_EQ(rc_solver_destroy(nullptr), RC_OK);
  char small[8];
  std::size_t length = 0;
  EXPECT_EQ(rc_solver_last_error(s.h, small, sizeof small, &length), RC_BUFFER_TOO_SMALL);
  EXPECT_EQ(std::string(small), s.error().substr(0, 7));
  EXPECT_EQ(length, s.error().size());
}

TEST(CApi, GridWithTwoPatchesIsRefused) {
  const int n1 = 40, n2 = 20;
  const double dx = 1e-3;
  std::vector<double> h(static_cast<std::size_t>(n1) * n2);
  for (int i2 = 0; i2 < n2; ++i2)
    for (int i1 = 0; i1 < n1; ++i1) {
      const double x1 = (i1 - 0.5 * (n1 - 1)) * dx, x2 = (i2 - 0.5 * (n2 - 1)) * dx;
      const double d = std::abs(x1) - 10e-3;  // two bumps at x1 = -10 and +10 mm
      h[static_cast<std::size_t>(i2) * n1 + i1] = 5.0 * d * d + 5.0 * x2 * x2;
    }
  Solver s;
  EXPECT_EQ(rc_solver_set_grid(s.h, n1, n2, dx, dx, h.data(), kF3), RC_SEVERAL_PATCHES) << s.error();
  EXPECT_NE(s.error().find("2 separate contact patches"), std::string::npos) << s.error();
}

std::vector<rc_patch> batch_patches(std::size_t count) {
  std::vector<rc_patch> patches;
  for (std::size_t k = 0; k < count; ++k) patches.push_back(ellipse(kA * (1.0 + 0.1 * static_cast<double>(k % 3)), kB, kF3));
  return patches;
}

std::vector<rc_creepage> batch_creepages(std::size_t count) {
  std::vector<rc_creepage> c;
  for (std::size_t k = 0; k < count; ++k)
    c.push_back({1e-4 * static_cast<double>(k), -2e-4 * static_cast<double>(k % 5), 0.1 * static_cast<double>(k % 4)});
  return c;
}

TEST(CApi, BatchOnThreadsEqualsTheSerialLoop) {
  const std::size_t count = 12;
  const std::vector<rc_patch> patches = batch_patches(count);
  const std::vector<rc_creepage> creepages = batch_creepages(count);
  std::vector<rc_forces> serial(count);
  std::vector<rc_normal_result> serial_normal(count);
  std::vector<double> serial_jacobians(9 * count);
  {
    Solver s(RC_METHOD_NH_FASTSIM, 400);
    for (std::size_t k = 0; k < count; ++k) {
      ASSERT_EQ(rc_creep_forces(s.h, &patches[k], &creepages[k], &serial[k], &serial_normal[k]), RC_OK) << s.error();
      rc_forces again{};
      ASSERT_EQ(rc_solver_jacobian(s.h, &creepages[k], &again, &serial_jacobians[9 * k]), RC_OK);
    }
  }
  for (const int threads : {1, 3, 0}) {
    Solver s(RC_METHOD_NH_FASTSIM, 400);
    std::vector<rc_forces> forces(count);
    std::vector<rc_normal_result> normal(count);
    std::vector<double> jacobians(9 * count);
    std::vector<int> statuses(count, -1);
    ASSERT_EQ(rc_batch_creep_forces(s.h, count, patches.data(), count, creepages.data(), threads, forces.data(),
                                    normal.data(), jacobians.data(), statuses.data()),
              RC_OK)
        << s.error();
    for (std::size_t k = 0; k < count; ++k) {
      EXPECT_EQ(statuses[k], RC_OK);
      EXPECT_EQ(forces[k].F1_N, serial[k].F1_N) << threads << " " << k;
      EXPECT_EQ(forces[k].F2_N, serial[k].F2_N) << threads << " " << k;
      EXPECT_EQ(forces[k].M3_Nm, serial[k].M3_Nm) << threads << " " << k;
      EXPECT_EQ(normal[k].area_m2, serial_normal[k].area_m2);
      for (int j = 0; j < 9; ++j) EXPECT_EQ(jacobians[9 * k + j], serial_jacobians[9 * k + j]) << k << " " << j;
    }
  }
}

TEST(CApi, BatchWithOnePatchAndAFailingState) {
  const std::size_t count = 9;
  const rc_patch patch = ellipse(kA, kB, kF3);
  std::vector<rc_creepage> creepages = batch_creepages(count);
  creepages[4].eta = kNaN;
  Solver serial(RC_METHOD_FASTSIM, 400), batch(RC_METHOD_FASTSIM, 400);
  std::vector<rc_forces> forces(count);
  std::vector<int> statuses(count, -1);
  EXPECT_EQ(rc_batch_creep_forces(batch.h, count, &patch, 1, creepages.data(), 4, forces.data(), nullptr, nullptr,
                                  statuses.data()),
            RC_INVALID_INPUT);
  EXPECT_EQ(batch.error().rfind("state 4: rc_creepage", 0), 0u) << batch.error();
  for (std::size_t k = 0; k < count; ++k) {
    rc_forces f{};
    const rc_status status = rc_creep_forces(serial.h, &patch, &creepages[k], &f, nullptr);
    EXPECT_EQ(statuses[k], status) << k;
    if (status == RC_OK) EXPECT_EQ(forces[k].F1_N, f.F1_N) << k;
  }
  EXPECT_EQ(rc_batch_creep_forces(batch.h, count, &patch, 2, creepages.data(), 1, forces.data(), nullptr, nullptr,
                                  nullptr),
            RC_INVALID_INPUT);
}

// One handle per thread, all at once: the numbers of the serial runs.
TEST(CApi, HandlesOnFourThreadsEqualSerial) {
  const auto run = [](int worker) {
    Solver s(worker % 2 == 0 ? RC_METHOD_NH_FASTSIM : RC_METHOD_EXACT, 300 + 100 * worker);
    rc_forces f{};
    const rc_patch p = ellipse(kA, kB * (1.0 + 0.2 * worker), kF3);
    const rc_creepage c{1e-3, 5e-4, 0.3};
    EXPECT_EQ(rc_creep_forces(s.h, &p, &c, &f, nullptr), RC_OK) << s.error();
    return f;
  };
  constexpr int kWorkers = 4;
  rc_forces serial[kWorkers], parallel[kWorkers];
  for (int w = 0; w < kWorkers; ++w) serial[w] = run(w);
  std::vector<std::thread> threads;
  for (int w = 0; w < kWorkers; ++w) threads.emplace_back([w, &parallel, &run] { parallel[w] = run(w); });
  for (std::thread& t : threads) t.join();
  for (int w = 0; w < kWorkers; ++w) {
    EXPECT_EQ(parallel[w].F1_N, serial[w].F1_N) << w;
    EXPECT_EQ(parallel[w].F2_N, serial[w].F2_N) << w;
    EXPECT_EQ(parallel[w].M3_Nm, serial[w].M3_Nm) << w;
  }
}

int count_progress(std::size_t done, std::size_t total, void* user) {
  auto* calls = static_cast<std::vector<std::size_t>*>(user);
  calls->push_back(done);
  EXPECT_LE(done, total);
  return 0;
}

int cancel_progress(std::size_t, std::size_t, void*) { return 1; }

TEST(CApi, FlexibilityTableBuildSaveLoadAndUse) {
  rc_flextable* table = nullptr;
  ASSERT_EQ(rc_flextable_create(&table), RC_OK);
  const double y[] = {-1e-3, 0.0, 1e-3};
  const double loads[] = {98100.0};
  std::vector<std::size_t> calls;
  ASSERT_EQ(rc_flextable_build(table, nullptr, y, 3, loads, 1, 300, 2.1e11, 0.3, count_progress, &calls), RC_OK);
  ASSERT_GE(calls.size(), 3u);
  EXPECT_EQ(calls.front(), 1u);
  rc_flextable_info info{};
  ASSERT_EQ(rc_flextable_info_get(table, &info), RC_OK);
  EXPECT_EQ(info.load_count, 1);
  EXPECT_EQ(info.target_elements, 300);
  EXPECT_EQ(info.y_min_m, -1e-3);

  test::ScratchDirectory dir("c_api_flextable");
  const std::string file = (dir.path() / "table.json").string();
  ASSERT_EQ(rc_flextable_save(table, file.c_str()), RC_OK);
  rc_flextable* loaded = nullptr;
  ASSERT_EQ(rc_flextable_create(&loaded), RC_OK);
  ASSERT_EQ(rc_flextable_load(loaded, file.c_str(), nullptr), RC_OK);
  rc_flextable_values built{}, read{};
  ASSERT_EQ(rc_flextable_lookup(table, 0.5e-3, 98100.0, &built), RC_OK);
  ASSERT_EQ(rc_flextable_lookup(loaded, 0.5e-3, 98100.0, &read), RC_OK);
  EXPECT_NEAR(read.L1_m_per_Pa, built.L1_m_per_Pa, 1e-12 * built.L1_m_per_Pa);
  EXPECT_NEAR(read.f11_N, built.f11_N, 1e-12 * built.f11_N);
  EXPECT_EQ(rc_flextable_lookup(loaded, 5e-3, 98100.0, &read), RC_INVALID_INPUT);
  EXPECT_EQ(rc_flextable_lookup(loaded, kNaN, 98100.0, &read), RC_INVALID_INPUT);

  // nh-fastsim with the table's flexibilities on the wheel-rail patch: the C++ API's numbers.
  Solver s;
  ASSERT_EQ(rc_solver_set_patch_flextable(s.h, loaded, 0.5e-3, 98100.0), RC_OK) << s.error();
  rc_normal_result n{};
  ASSERT_EQ(rc_solver_normal_result(s.h, &n), RC_OK);
  EXPECT_GT(n.contact_angle_rad, 0.0);
  const rc_creepage c{1e-3, 0, n.spin_per_m};
  rc_forces f{};
  ASSERT_EQ(rc_solver_solve(s.h, &c, &f), RC_OK);
  const FlexibilityTableFastSim cpp(load_flexibility_table(file), default_wheel_rail_pair());
  const TangentialForces expected = cpp.prepare(0.5e-3, 98100.0).forces(Creepage{1e-3, 0, n.spin_per_m}, kMu);
  // forces_and_adhesion against forces: different code (tests/different_paths.hpp).
  test::expect_forces_near(f, expected, kMu * 98100.0, n.dx1_m * n.n1);

  // Errors: cancelled build, missing file, other material.
  EXPECT_EQ(rc_flextable_build(table, nullptr, y, 3, loads, 1, 300, 2.1e11, 0.3, cancel_progress, nullptr),
            RC_CANCELLED);
  EXPECT_EQ(rc_flextable_lookup(table, 0.5e-3, 98100.0, &built), RC_OK);  // the table is kept
  EXPECT_EQ(rc_flextable_load(loaded, (dir.path() / "missing.json").string().c_str(), nullptr), RC_IO);
  rc_settings settings;
  rc_settings_default(&settings);
  settings.youngs_modulus_Pa = 2.0e11;
  ASSERT_EQ(rc_solver_set_settings(s.h, &settings), RC_OK);
  EXPECT_EQ(rc_solver_set_patch_flextable(s.h, loaded, 0.5e-3, 98100.0), RC_INVALID_INPUT);
  rc_flextable_destroy(table);
  rc_flextable_destroy(loaded);
}

}  // namespace
}  // namespace railcontact

namespace railcontact {
namespace {

// The C API gives the CLI's numbers for the same case — a single patch with nh-fastsim and fastsim
// (`railcontact run`) within test::kDifferentPathsRelative of mu F3 (the CLI marches with solve,
// which records the tractions, the C API with forces_and_adhesion: different code,
// tests/different_paths.hpp; the adhesion fraction within 1e-3, two of the ~2800 elements, whose
// slip flags may flip where |p| sits on the bound to rounding), and a wheelset (`railcontact wheelset`, by load, both
// wheels: the same code) to the last digit.
TEST(CApiEqualsCli, SinglePatchAndWheelsetToTheLastDigit) {
  const test::ScratchDirectory dir("c_api_equals_cli");
  std::ofstream(dir / "case.toml") << "[geometry]\ntype = \"ellipse\"\na = 0.006\nb = 0.004\n[material]\nE = 2.1e11\n"
                                      "nu = 0.3\n[load]\nnormal_force = 80000\n[friction]\nmu = 0.3\n[creepage]\n"
                                      "xi = 0.001\neta = 0.0005\nphi = 0.3\n[mesh]\nelements = 2800\n[solvers]\n"
                                      "run = [\"nh-fastsim\", \"fastsim\"]\n";
  const test::CommandResult cli =
      test::run_cli("run " + (dir / "case.toml").string() + " --json --out " + (dir / "run").string());
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const nlohmann::json j = nlohmann::json::parse(cli.out);
  for (const auto& [method, name] : {std::pair{RC_METHOD_NH_FASTSIM, "nh-fastsim"}, std::pair{RC_METHOD_FASTSIM, "fastsim"}}) {
    rc_solver* solver = nullptr;
    ASSERT_EQ(rc_solver_create(&solver), RC_OK);
    rc_settings settings;
    rc_settings_default(&settings);
    settings.method = method;
    settings.mesh_value = 2800;
    ASSERT_EQ(rc_solver_set_settings(solver, &settings), RC_OK);
    rc_patch patch{};
    patch.kind = RC_GEOMETRY_ELLIPSE;
    patch.a_m = 0.006;
    patch.b_m = 0.004;
    patch.normal_force_N = 80000;
    const rc_creepage creepage{0.001, 0.0005, 0.3};
    rc_forces f{};
    ASSERT_EQ(rc_creep_forces(solver, &patch, &creepage, &f, nullptr), RC_OK);
    const TangentialForces cli_forces{j["results"][name]["F1"].get<double>(), j["results"][name]["F2"].get<double>(),
                                      j["results"][name]["M3"].get<double>()};
    test::expect_forces_near(f, cli_forces, 0.3 * 80000, 0.006, name);
    EXPECT_NEAR(f.adhesion_fraction, j["results"][name]["adhesion_fraction"].get<double>(), 1e-3) << name;
    rc_solver_destroy(solver);
  }

  const test::CommandResult wheelset_cli = test::run_cli("wheelset --y-m 0.0013 --yaw-rad 0.0005 --element-size-m 0.0005 --json");
  ASSERT_EQ(wheelset_cli.exit_code, 0) << wheelset_cli.err;
  const nlohmann::json w = nlohmann::json::parse(wheelset_cli.out);
  rc_wheelset* wheelset = nullptr;
  ASSERT_EQ(rc_wheelset_create(&wheelset), RC_OK);
  ASSERT_EQ(rc_wheelset_set_default_track(wheelset), RC_OK);
  rc_wheelset_options o;
  rc_wheelset_options_default(&o);
  o.element_size_m = 0.5e-3;
  ASSERT_EQ(rc_wheelset_set_options(wheelset, &o), RC_OK);
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  s.y_m = 0.0013;  // the CLI's --y-m 0.0013 and --yaw-rad 0.0005: the same doubles
  s.yaw_rad = 0.0005;
  rc_wheelset_result r{};
  ASSERT_EQ(rc_wheelset_evaluate(wheelset, &s, &r), RC_OK);
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 3; ++i)
      EXPECT_EQ(r.wheel_force_track_N[k][i], w["wheels"][k]["force_track_N"][i].get<double>())
          << k << " " << i << " difference " << r.wheel_force_track_N[k][i] - w["wheels"][k]["force_track_N"][i].get<double>();
  rc_wheelset_destroy(wheelset);
}

}  // namespace
}  // namespace railcontact

// Issue 28: ranges of every number of the single-patch C API, before any work, naming the field.
namespace railcontact {
namespace {

TEST(CApiRanges, EllipseAndCurvaturesOutsideTheirPhysicalRangeAreInvalidInput) {
  Solver s;
  // 1e-300 m made Hertz's closed form overflow (RC_INTERNAL); 1e-9 m at 98 kN gave 4.7e16 MPa.
  EXPECT_EQ(rc_solver_set_ellipse(s.h, 1e-300, kB, kF3), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_patch.a_m = 1e-300 m must lie in [1e-05, 0.1] m"), std::string::npos) << s.error();
  EXPECT_EQ(rc_solver_set_ellipse(s.h, 1e-9, 1e-9, 98100.0), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_patch.a_m = 1e-09 m"), std::string::npos) << s.error();
  // Each semi-axis in range, the pair too small for the load: the pressure, naming a_m and b_m.
  EXPECT_EQ(rc_solver_set_ellipse(s.h, 2e-5, 2e-5, 98100.0), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_patch.a_m = 2e-05 m and rc_patch.b_m = 2e-05 m under F3 = 98100 N give a maximum "
                           "pressure"),
            std::string::npos)
      << s.error();
  EXPECT_EQ(rc_solver_set_hertz(s.h, 1e-300, 1e-300, kF3), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_patch.A_per_m = 1e-300 1/m must lie in [0.001, 10000] 1/m"), std::string::npos)
      << s.error();
  EXPECT_EQ(rc_solver_set_hertz(s.h, 1e300, 1e300, kF3), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_patch.A_per_m = 1e+300 1/m"), std::string::npos) << s.error();
  // In range, the solver's patch: a 98 kN wheel-rail ellipse and its curvatures.
  EXPECT_EQ(rc_solver_set_ellipse(s.h, kA, kB, kF3), RC_OK) << s.error();
  EXPECT_EQ(rc_solver_set_hertz(s.h, 1.1, 5.0, kF3), RC_OK) << s.error();
}

TEST(CApiRanges, CreepagesBeyondTheRangeOfAContactNameTheField) {
  Solver s;
  ASSERT_EQ(rc_solver_set_ellipse(s.h, kA, kB, kF3), RC_OK) << s.error();
  rc_forces f{};
  // xi = 1e200 blamed the flexibilities; the exact solver said "not converged".
  const rc_creepage huge{1e200, 0, 0};
  EXPECT_EQ(rc_solver_solve(s.h, &huge, &f), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_creepage.xi = 1e+200 must lie in [-0.5, 0.5]"), std::string::npos) << s.error();
  const rc_creepage eta{0, -0.6, 0};
  double J[9];
  EXPECT_EQ(rc_solver_jacobian(s.h, &eta, &f, J), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_creepage.eta = -0.6"), std::string::npos) << s.error();
  const rc_creepage spin{0, 0, 150.0};
  EXPECT_EQ(rc_solver_solve(s.h, &spin, &f), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_creepage.phi_per_m = 150 1/m must lie in [-100, 100] 1/m"), std::string::npos)
      << s.error();
  Solver exact(RC_METHOD_EXACT, 300);
  ASSERT_EQ(rc_solver_set_ellipse(exact.h, kA, kB, kF3), RC_OK) << exact.error();
  EXPECT_EQ(rc_solver_solve(exact.h, &huge, &f), RC_INVALID_INPUT);
  EXPECT_NE(exact.error().find("rc_creepage.xi"), std::string::npos) << exact.error();
  // The limits themselves are creepages (the Jacobian steps past them by its step).
  const rc_creepage edge{0.5, -0.5, 100.0};
  EXPECT_EQ(rc_solver_solve(s.h, &edge, &f), RC_OK) << s.error();
  EXPECT_EQ(rc_solver_jacobian(s.h, &edge, &f, J), RC_OK) << s.error();
}

TEST(CApiRanges, CountsAreCheckedBeforeAnyAllocation) {
  Solver s;
  rc_patch patch{};
  patch.kind = RC_GEOMETRY_ELLIPSE;
  patch.a_m = kA;
  patch.b_m = kB;
  patch.normal_force_N = kF3;
  const rc_creepage c{1e-3, 0, 0};
  rc_forces f{};
  // (size_t)-1 made std::vector throw "cannot create std::vector larger than max_size()" (RC_INTERNAL).
  EXPECT_EQ(rc_batch_creep_forces(s.h, SIZE_MAX, &patch, 1, &c, 1, &f, nullptr, nullptr, nullptr), RC_INVALID_INPUT);
  EXPECT_NE(s.error().find("rc_batch_creep_forces: count = 18446744073709551615 states; at most RC_MAX_BATCH_STATES"),
            std::string::npos)
      << s.error();
  rc_flextable* table = nullptr;
  ASSERT_EQ(rc_flextable_create(&table), RC_OK);
  const double y = 0.0, load = 1e5;
  EXPECT_EQ(rc_flextable_build(table, nullptr, &y, SIZE_MAX, &load, 1, 300, 2.1e11, 0.3, nullptr, nullptr),
            RC_INVALID_INPUT);
  std::string message(512, '\0');
  std::size_t length = 0;
  rc_flextable_last_error(table, message.data(), message.size(), &length);
  message.resize(std::min(length, message.size() - 1));
  EXPECT_NE(message.find("rc_flextable_build: y_count = 18446744073709551615: 1 to 10000 values"), std::string::npos)
      << message;
  EXPECT_EQ(rc_flextable_build(table, nullptr, &y, 1, &load, SIZE_MAX, 300, 2.1e11, 0.3, nullptr, nullptr),
            RC_INVALID_INPUT);
  message.assign(512, '\0');
  rc_flextable_last_error(table, message.data(), message.size(), &length);
  message.resize(std::min(length, message.size() - 1));
  EXPECT_NE(message.find("rc_flextable_build: load_count = 18446744073709551615: 1 to 100 values"), std::string::npos)
      << message;
  rc_flextable_destroy(table);
}

}  // namespace
}  // namespace railcontact
