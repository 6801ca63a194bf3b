// `railcontact run`: the main job. Until the wheel-rail pipeline lands, the built-in default
// case is the coefficient demo on a few ellipses.
#include <fmt/core.h>

#include "cli/commands.hpp"
#include "railcontact/ellipse_coefficients.hpp"
#include "railcontact/kalker.hpp"

namespace railcontact::cli {
namespace {

int run_default_case() {
  fmt::print("railcontact: creepage coefficients from the full-adhesion steady state (K2, Eq 18)\n");
  fmt::print("against Kalker's table, nu = 0.25, about 2800 elements in contact\n\n");
  fmt::print("   a/b  elements     C11 (Kalker)  err      C22 (Kalker)  err      C23 (Kalker)  err     time\n");
  for (double ratio : {0.2, 0.5, 1.0, 2.0, 5.0}) {
    const EllipseCoefficientResult r = ellipse_creepage_coefficients(ratio, 0.25);
    const KalkerCoefficients k = kalker_coefficients(ratio, 0.25);
    const CreepageCoefficients& c = r.coefficients;
    fmt::print("  {:4.1f}  {:8}  {:6.3f} ({:5.3f}) {:+5.2f}%  {:6.3f} ({:5.3f}) {:+5.2f}%  {:6.3f} ({:5.3f}) {:+5.2f}%  {:4.0f} ms\n",
               ratio, r.elements_in_contact, c.C11, k.C11, 100 * (c.C11 / k.C11 - 1), c.C22, k.C22,
               100 * (c.C22 / k.C22 - 1), c.C23, k.C23, 100 * (c.C23 / k.C23 - 1), 1e3 * r.solve_time_s);
  }
  fmt::print("\nMore: railcontact coefficients --help, railcontact study coefficients --out DIR\n");
  return 0;
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  CLI::App* cmd = app.add_subcommand("run", "the main job on the built-in default case");
  cmd->callback([&action] { action = [] { return run_default_case(); }; });
}

}  // namespace railcontact::cli
