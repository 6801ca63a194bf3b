// The main job: a case from patch to creep forces with every requested solver.
#include "railcontact/case_run.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "railcontact/adhesion.hpp"
#include "railcontact/ellipse.hpp"
#include "railcontact/error.hpp"
#include "railcontact/fastsim.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/rolling.hpp"

namespace railcontact {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void summarise(const ContactPatch& patch, PatchSummary& s) {
  s.normal_force_N = patch.normal_force_N();
  s.area_m2 = patch.area_m2();
  s.elements_in_contact = patch.elements().count();
  s.n1 = patch.mesh().n1;
  s.n2 = patch.mesh().n2;
  s.dx1_m = patch.mesh().dx1_m;
  s.dx2_m = patch.mesh().dx2_m;
  double x1_min = 1e300, x1_max = -1e300, x2_min = 1e300, x2_max = -1e300;
  for (std::size_t e = 0; e < patch.elements().count(); ++e) {
    s.max_pressure_Pa = std::max(s.max_pressure_Pa, patch.pressure_Pa()[e]);
    x1_min = std::min(x1_min, patch.x1(e));
    x1_max = std::max(x1_max, patch.x1(e));
    x2_min = std::min(x2_min, patch.x2(e));
    x2_max = std::max(x2_max, patch.x2(e));
  }
  s.extent_x1_m = x1_max - x1_min + s.dx1_m;
  s.extent_x2_m = x2_max - x2_min + s.dx2_m;
}

// Elliptical Hertzian patch from the semi-axes or from the curvatures (Hertz).
ContactPatch elliptical_patch(const Case& c, PatchSummary& s) {
  double a = 0, b = 0;
  if (c.ellipse.a_m && c.ellipse.b_m) {
    a = *c.ellipse.a_m;
    b = *c.ellipse.b_m;
  } else {
    const HertzContact h = hertz_from_curvatures(*c.ellipse.A_per_m, *c.ellipse.B_per_m, c.normal_force_N, c.material);
    a = h.a_m;
    b = h.b_m;
  }
  require(a / b >= 0.01 && a / b <= 100, fmt::format("{}: the ellipse's a/b = {} lies outside [0.01, 100]", c.source, a / b));
  s.geometry = "ellipse";
  s.a_m = a;
  s.b_m = b;
  const ContactElements elements =
      elliptical_contact_with_count(a, b, c.target_elements, EllipseMeshLayout::rolling_resolved);
  return hertzian_patch(elements, a, b, c.normal_force_N, c.material);
}

void take_fastsim_result(const FastSimResult& r, SolverRun& run) {
  run.forces = r.forces;
  run.p1_Pa = r.p1_Pa;
  run.p2_Pa = r.p2_Pa;
  run.slip = r.slip;
  run.adhesion_fraction = r.adhesion_fraction;
}

}  // namespace

const SolverRun* CaseResult::find(SolverKind kind) const {
  for (const SolverRun& run : runs)
    if (run.kind == kind) return &run;
  return nullptr;
}

CaseResult run_case(const Case& input, std::ostream* progress) {
  validate(input.material);
  require(input.normal_force_N > 0 && std::isfinite(input.normal_force_N), "the normal force must be positive");
  require(input.mu > 0 && std::isfinite(input.mu), "the friction coefficient must be positive");
  require(input.geometry == GeometryKind::ellipse,
          fmt::format("{}: wheel-rail cases are not available in this version", input.source));
  CaseResult result{input, {}, {}, input.creepage.raw, std::nullopt, {}};
  result.patch = elliptical_patch(input, result.summary);
  summarise(result.patch, result.summary);
  const ContactPatch& patch = result.patch;
  const Creepage& creepage = result.creepage;
  const FastSim fastsim(patch);

  for (SolverKind kind : input.solvers) {
    if (progress) fmt::print(*progress, "  {} ...\n", solver_name(kind));
    SolverRun run;
    run.kind = kind;
    const auto start = Clock::now();
    switch (kind) {
      case SolverKind::nh_fastsim: {
        AdhesionOptions adhesion = nh_fastsim_adhesion_options();
        adhesion.collocation_offset = input.rolling.collocation_offset;
        const AdhesionSolution K2 = solve_full_adhesion(patch.elements(), patch.material(), adhesion);
        run.flexibility = nh_fastsim_flexibility(fastsim, K2.creepage_matrix);
        run.flexibility_time_s = seconds_since(start);
        run.iterations = K2.iterations;
        result.creepage_matrix = K2.creepage_matrix;
        take_fastsim_result(fastsim.solve(creepage, *run.flexibility, input.mu), run);
        break;
      }
      case SolverKind::fastsim: {
        run.flexibility = fastsim_flexibility(result.summary.a_m, result.summary.b_m, patch.material());
        run.flexibility_time_s = seconds_since(start);
        take_fastsim_result(fastsim.solve(creepage, *run.flexibility, input.mu), run);
        break;
      }
      case SolverKind::exact:
      case SolverKind::exact_regularised: {
        const RollingSolution r = kind == SolverKind::exact
                                      ? solve_rolling_exact(patch, creepage, input.mu, input.rolling)
                                      : solve_rolling_regularised(patch, creepage, input.mu, input.rolling);
        run.forces = r.forces;
        run.iterations = r.newton_iterations;
        run.krylov_iterations = r.krylov_iterations;
        run.converged = r.converged;
        run.p1_Pa = r.p1_Pa;
        run.p2_Pa = r.p2_Pa;
        run.slip = r.slip;
        run.adhesion_fraction = r.adhesion_fraction;
        break;
      }
    }
    run.time_s = seconds_since(start);
    result.runs.push_back(std::move(run));
  }
  return result;
}

Case default_case() {
  Case c;
  c.source = "built-in default case";
  c.geometry = GeometryKind::ellipse;
  c.ellipse.a_m = 0.006;
  c.ellipse.b_m = 0.004;
  c.material = Material{2.1e11, 0.3};
  c.normal_force_N = 98100.0;
  c.mu = 0.3;
  c.creepage.raw = Creepage{0.001, 0.0005, 0.5};
  return c;
}

}  // namespace railcontact
