// `railcontact coefficients`: Kalker's creepage coefficients of an ellipse from K2 (Eq 18).
#include <fmt/core.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "cli/commands.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/version.h"

namespace railcontact::cli {
namespace {

struct CoefficientsArguments {
  double a_over_b = 1.0;
  double nu = 0.25;
  int elements = 2800;
  std::optional<double> alpha;
  std::optional<double> alpha_spin;
  std::string solver = "krylov";
  std::string mesh = "rolling-resolved";
  bool c_from_area = false;
  bool json = false;
};

int run_coefficients(const CoefficientsArguments& args) {
  require(args.nu >= 0.0 && args.nu <= 0.5, [&] { return fmt::format("--nu {:g} must lie in [0, 0.5]", args.nu); });
  require(args.a_over_b >= 0.01 && args.a_over_b <= 100.0,
          [&] { return fmt::format("--a-over-b must lie in [0.01, 100] (got {})", args.a_over_b); });
  require(args.elements >= 4 && args.elements <= 1'000'000,
          [&] { return fmt::format("--elements must lie in [4, 1000000] (got {})", args.elements); });
  for (const auto& [option, value] : {std::pair{"--alpha", args.alpha}, std::pair{"--alpha-spin", args.alpha_spin}})
    require(!value || (*value >= kMinimumCollocationOffset && *value <= 1.0), [&] {
      return fmt::format("{} {:g} must lie in [{:g}, 1] (closer to -1 the steady-rolling operator is too "
                         "ill-conditioned for the Krylov solver)",
                         option, *value, kMinimumCollocationOffset);
    });
  // The dense solver's matrix and LU take 2 (2N)^2 doubles: 9 GB at N = 12000 (as the library checks).
  require(args.solver != "dense" || args.elements <= 12000, [&] {
    return fmt::format("--elements {} is too many for --solver dense (at most 12000: its matrix would not fit in "
                       "memory); use --solver krylov",
                       args.elements);
  });
  EllipseCoefficientOptions options;
  options.target_elements = args.elements;
  options.layout = args.mesh == "equal-counts" ? EllipseMeshLayout::equal_counts : EllipseMeshLayout::rolling_resolved;
  options.c_from_discrete_area = args.c_from_area;
  options.adhesion.solver = args.solver == "dense" ? LinearSolver::dense : LinearSolver::krylov;
  // --alpha sets every column; the default is alpha = 0 with 0.5 for the spin column.
  options.adhesion.collocation_offset = args.alpha.value_or(0.0);
  options.adhesion.spin_collocation_offset = args.alpha_spin ? args.alpha_spin : (args.alpha ? args.alpha : 0.5);
  const double alpha_spin = *options.adhesion.spin_collocation_offset;

  const EllipseCoefficientResult r = ellipse_creepage_coefficients(args.a_over_b, args.nu, options);
  const KalkerCoefficients table = kalker_coefficients(args.a_over_b, args.nu);
  const CreepageCoefficients& C = r.coefficients;
  const double e11 = C.C11 / table.C11 - 1, e22 = C.C22 / table.C22 - 1, e23 = C.C23 / table.C23 - 1;

  if (args.json) {
    nlohmann::json out = {
        {"railcontact_version", RC_VERSION_STRING},
        {"a_over_b", args.a_over_b},
        {"nu", args.nu},
        {"alpha", options.adhesion.collocation_offset},
        {"alpha_spin", alpha_spin},
        {"solver", args.solver},
        {"mesh", args.mesh},
        {"mesh_n1", r.n1},
        {"mesh_n2", r.n2},
        {"c_from_discrete_area", args.c_from_area},
        {"elements_in_contact", r.elements_in_contact},
        {"C11", C.C11},
        {"C22", C.C22},
        {"C23", C.C23},
        {"C33", C.C33},
        {"table", {{"C11", table.C11}, {"C22", table.C22}, {"C23", table.C23}}},
        {"rel_error", {{"C11", e11}, {"C22", e22}, {"C23", e23}}},
        {"iterations", r.iterations},
        {"solve_time_s", r.solve_time_s},
    };
    fmt::print("{}\n", out.dump(2));
    return 0;
  }
  fmt::print("Creepage coefficients of an ellipse, a/b = {:g}, nu = {:g} (K2 of the full-adhesion steady state, Eq 18)\n",
             args.a_over_b, args.nu);
  fmt::print("  mesh {} x {} ({}), {} elements in contact, alpha = {:g} (spin column {:g}), {} solver\n", r.n1, r.n2,
             args.mesh, r.elements_in_contact, options.adhesion.collocation_offset, alpha_spin, args.solver);
  fmt::print("  c = {}\n\n", args.c_from_area ? "sqrt(discrete area / pi)" : "sqrt(a b)");
  fmt::print("         computed   Kalker    rel. error\n");
  fmt::print("  C11  {:9.4f}  {:8.4f}   {:+7.2f}%\n", C.C11, table.C11, 100 * e11);
  fmt::print("  C22  {:9.4f}  {:8.4f}   {:+7.2f}%\n", C.C22, table.C22, 100 * e22);
  fmt::print("  C23  {:9.4f}  {:8.4f}   {:+7.2f}%\n", C.C23, table.C23, 100 * e23);
  fmt::print("  C33  {:9.4f}       -\n\n", C.C33);
  fmt::print("  Kalker: Table E.3 interpolated in a/b and nu (exact at the table's entries).\n");
  fmt::print("  solve time {:.1f} ms", 1e3 * r.solve_time_s);
  if (args.solver == "krylov") fmt::print(" ({} GMRES iterations)", r.iterations);
  fmt::print("\n");
  return 0;
}

}  // namespace

void add_coefficients_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<CoefficientsArguments>();
  CLI::App* cmd = app.add_subcommand("coefficients", "Kalker's creepage coefficients of an ellipse from K2 (Eq 18)");
  cmd->add_option("--a-over-b", args->a_over_b, "semi-axis ratio a/b, a along the rolling direction")->required();
  cmd->add_option("--nu", args->nu, "Poisson's ratio in [0, 0.5] (0.5: incompressible)")->required();
  cmd->add_option("--elements", args->elements, "about this many elements in contact")->capture_default_str();
  cmd->add_option("--alpha", args->alpha, "collocation offset alpha in [-0.95, 1] (all columns; default 0, spin 0.5)");
  cmd->add_option("--alpha-spin", args->alpha_spin, "collocation offset for the spin column, in [-0.95, 1]");
  cmd->add_option("--solver", args->solver, "linear solver")
      ->check(CLI::IsMember({"krylov", "dense"}))
      ->capture_default_str();
  cmd->add_option("--mesh", args->mesh, "mesh layout: equal-counts (n x n, the paper) or rolling-resolved")
      ->check(CLI::IsMember({"equal-counts", "rolling-resolved"}))
      ->capture_default_str();
  cmd->add_flag("--c-from-area", args->c_from_area, "c from the discrete patch area instead of sqrt(ab)");
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args, &action] { action = [args] { return run_coefficients(*args); }; });
}

}  // namespace railcontact::cli
