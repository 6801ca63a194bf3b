// Error kinds (railcontact/error.hpp): each failure of the library carries the kind a caller can
// act on, and the CLI turns the kind into its exit code (docs/ARCHITECTURE.md "Errors").
#include <gtest/gtest.h>

#include <functional>
#include <optional>

#include "cli_run.hpp"
#include "railcontact/error.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {
namespace {

std::optional<ErrorKind> kind_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.kind();
  }
  return std::nullopt;
}

ContactPatch small_ellipse() {
  const double a = 6e-3, b = 4e-3;
  return hertzian_patch(elliptical_contact_with_count(a, b, 400), a, b, 8e4, Material{2.1e11, 0.3});
}

TEST(ErrorKinds, BadValuesAreInvalidInput) {
  const ContactPatch patch = small_ellipse();
  EXPECT_EQ(kind_of([&] { (void)solve_rolling_exact(patch, {1e-3, 0, 0}, -0.3); }), ErrorKind::invalid_input);
  EXPECT_EQ(kind_of([&] { (void)NhFastSim(patch).forces({std::nan(""), 0, 0}, 0.3); }), ErrorKind::invalid_input);
  EXPECT_EQ(Error("plain").kind(), ErrorKind::invalid_input);
}

TEST(ErrorKinds, SolversThatStopShortAreNotConverged) {
  const ContactPatch patch = small_ellipse();
  RollingOptions rolling;
  rolling.max_newton_iterations = 1;  // partial slip needs several Newton steps
  EXPECT_EQ(kind_of([&] { (void)solve_rolling_exact(patch, {1e-3, 5e-4, 0.5}, 0.3, rolling); }),
            ErrorKind::not_converged);
  EXPECT_EQ(kind_of([&] { (void)solve_rolling_regularised(patch, {1e-3, 5e-4, 0.5}, 0.3, rolling); }),
            ErrorKind::not_converged);
  AdhesionOptions adhesion;
  adhesion.max_iterations = 2;
  EXPECT_EQ(kind_of([&] { (void)solve_full_adhesion(patch.elements(), patch.material(), adhesion); }),
            ErrorKind::not_converged);
  // A converged solution is returned with its residual within the tolerance.
  const RollingSolution ok = solve_rolling_exact(patch, {1e-3, 5e-4, 0.5}, 0.3);
  EXPECT_LE(ok.residual, RollingOptions{}.tolerance);
  EXPECT_GT(ok.newton_iterations, 1);
}

TEST(ErrorKinds, WheelRailContactKinds) {
  const WheelRailPair pair = default_wheel_rail_pair();
  // 0.2 m to the left: the profiles no longer overlap laterally.
  EXPECT_EQ(kind_of([&] { (void)pair.contact_point(0.2); }), ErrorKind::no_contact);
  WheelRailPatchOptions options;
  options.target_elements = 600;
  options.vertical_load_N = 10000.0;  // tread and flange root apart (at 98.1 kN their overlaps merge)
  EXPECT_EQ(kind_of([&] { (void)solve_wheel_rail_patch(pair, -5e-3, options); }), ErrorKind::several_patches);
  EXPECT_EQ(kind_of([&] { (void)solve_wheel_rail_patch(pair, 0.0, options); }), std::nullopt);
}

TEST(ErrorKinds, UnreadableFilesAreIo) {
  EXPECT_EQ(kind_of([] { (void)read_profile("/nonexistent/wheel.prw"); }), ErrorKind::io);
  EXPECT_EQ(kind_of([] { (void)load_flexibility_table("/nonexistent/table.json"); }), ErrorKind::io);
  EXPECT_EQ(error_kind_name(ErrorKind::several_patches), "several contact patches");
  EXPECT_EQ(error_kind_name(ErrorKind::not_converged), "not converged");
}

TEST(ErrorKinds, CliExitCodeNamesTheKind) {
  using test::run_cli;
  EXPECT_EQ(run_cli("run /nonexistent/case.toml").exit_code, 3);                 // io
  EXPECT_EQ(run_cli("patch --y-m -0.005 --load-N 10000 --elements 600 --json").exit_code, 5);  // several patches
  EXPECT_EQ(run_cli("patch --y-m 0.2 --json").exit_code, 4);                       // no contact
  EXPECT_EQ(run_cli("coefficients --a-over-b -2 --nu 0.3").exit_code, 2);        // invalid input
  EXPECT_EQ(run_cli("run --no-such-option").exit_code, 2);                       // command line
  EXPECT_EQ(run_cli("no-such-command").exit_code, 2);
}

}  // namespace
}  // namespace railcontact
