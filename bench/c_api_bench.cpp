// The C API's overhead on one nH-FastSim single-patch evaluation (docs/C_API.md): rc_solver_solve
// against the C++ calls it wraps (NhFastSim::solve, which also fills the traction fields, and
// NhFastSim::forces), on a Hertzian ellipse of about 3000 elements, the patch prepared once.
#include <benchmark/benchmark.h>

#include "railcontact/contact_patch.hpp"
#include "railcontact/railcontact.h"
#include "railcontact/tangential.hpp"

namespace {

using namespace railcontact;

constexpr double kA = 6e-3, kB = 4e-3, kF3 = 8e4, kMu = 0.3;
const Creepage kCreepage{1e-3, 5e-4, 0.3};

NhFastSim prepared() {
  const ContactPatch patch = hertzian_patch(
      elliptical_contact_with_count(kA, kB, 3000, EllipseMeshLayout::rolling_resolved), kA, kB, kF3, Material{});
  return NhFastSim(patch);
}

void BM_CppNhFastSimForces(benchmark::State& state) {
  const NhFastSim nh = prepared();
  for (auto _ : state) benchmark::DoNotOptimize(nh.forces(kCreepage, kMu));
}
BENCHMARK(BM_CppNhFastSimForces)->Unit(benchmark::kMicrosecond);

void BM_CppNhFastSimSolve(benchmark::State& state) {
  const NhFastSim nh = prepared();
  for (auto _ : state) benchmark::DoNotOptimize(nh.solve(kCreepage, kMu));
}
BENCHMARK(BM_CppNhFastSimSolve)->Unit(benchmark::kMicrosecond);

void BM_CApiSolve(benchmark::State& state) {
  rc_solver* solver = nullptr;
  rc_solver_create(&solver);
  rc_settings settings;
  rc_settings_default(&settings);
  settings.mesh_value = 3000;
  rc_solver_set_settings(solver, &settings);
  if (rc_solver_set_ellipse(solver, kA, kB, kF3) != RC_OK) state.SkipWithError("rc_solver_set_ellipse failed");
  const rc_creepage c{kCreepage.xi, kCreepage.eta, kCreepage.phi};
  rc_forces f{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(rc_solver_solve(solver, &c, &f));
    benchmark::DoNotOptimize(f);
  }
  rc_solver_destroy(solver);
}
BENCHMARK(BM_CApiSolve)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
