// The cost of the C API's calls (docs/INTEGRATION.md "Cost of each call") and its overhead on one
// nH-FastSim single-patch evaluation (docs/C_API.md): on a Hertzian ellipse a = 6 mm, b = 4 mm,
// F3 = 80 kN, about 3000 elements in contact, mu = 0.3, creepages (1e-3, 5e-4, 0.3 1/m).
//   BM_CppNhFastSimForces, BM_CppNhFastSimSolve  the C++ calls rc_solver_solve wraps
//                                   (NhFastSim::forces; NhFastSim::solve also fills the tractions)
//   BM_CApiSolve                    rc_solver_solve, nh-fastsim, the patch prepared once
//   BM_CApiSolveMethod/M            rc_solver_solve with rc_method M (0 nh-fastsim, 1 fastsim,
//                                   2 exact, 3 exact-regularised)
//   BM_CApiSetEllipse/M             rc_solver_set_ellipse: the normal problem and method M's
//                                   preparation (nh-fastsim: K2)
//   BM_CApiBatch/T                  rc_batch_creep_forces of kBatchStates states on one patch
//                                   (prepared once inside the call) on T threads; counter
//                                   us_per_state. bench/python_overhead.py compares
//                                   railcontact.Solver.batch with BM_CApiBatch/1.
//   BM_CApiFlextableLookup          rc_flextable_lookup in a table of S1002/UIC60 (built at the
//                                   first use: y = 0, 0.25 mm, 98.1 kN, 3000 elements)
//   BM_CApiSetPatchFlextable        rc_solver_set_patch_flextable at y = 0.125 mm: the patch's
//                                   normal problem with the table's flexibilities (no K2)
//   BM_CApiWheelsetStep/W           rc_wheelset_evaluate by position, S1002/UIC60, 0.2 mm elements,
//                                   y = 0 moving 1 um per call; W = 1 warm start, 0 cold
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

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

// A solver with method `method` (rc_method) and about 3000 elements in contact.
rc_solver* solver_with_method(int method) {
  rc_solver* solver = nullptr;
  rc_solver_create(&solver);
  rc_settings settings;
  rc_settings_default(&settings);
  settings.mesh_value = 3000;
  settings.method = method;
  settings.friction_coefficient = kMu;
  rc_solver_set_settings(solver, &settings);
  return solver;
}

void BM_CApiSolveMethod(benchmark::State& state) {
  rc_solver* solver = solver_with_method(static_cast<int>(state.range(0)));
  if (rc_solver_set_ellipse(solver, kA, kB, kF3) != RC_OK) state.SkipWithError("rc_solver_set_ellipse failed");
  const rc_creepage c{kCreepage.xi, kCreepage.eta, kCreepage.phi};
  rc_forces f{};
  for (auto _ : state) {
    if (rc_solver_solve(solver, &c, &f) != RC_OK) state.SkipWithError("rc_solver_solve failed");
    benchmark::DoNotOptimize(f);
  }
  rc_solver_destroy(solver);
}
BENCHMARK(BM_CApiSolveMethod)->DenseRange(RC_METHOD_NH_FASTSIM, RC_METHOD_EXACT_REGULARISED)->Unit(benchmark::kMicrosecond);

void BM_CApiSetEllipse(benchmark::State& state) {
  rc_solver* solver = solver_with_method(static_cast<int>(state.range(0)));
  int k = 0;
  for (auto _ : state) {
    // A slightly different semi-axis each time (a new mesh): the solver reuses an unchanged patch.
    if (rc_solver_set_ellipse(solver, kA * (1.0 + 1e-6 * (++k % 2)), kB, kF3) != RC_OK)
      state.SkipWithError("rc_solver_set_ellipse failed");
  }
  rc_solver_destroy(solver);
}
BENCHMARK(BM_CApiSetEllipse)->DenseRange(RC_METHOD_NH_FASTSIM, RC_METHOD_EXACT_REGULARISED)->Unit(benchmark::kMillisecond);

// The batch's states: creepage k of kBatchStates, the same formula as bench/python_overhead.py.
constexpr std::size_t kBatchStates = 10000;
std::vector<rc_creepage> batch_creepages() {
  std::vector<rc_creepage> c(kBatchStates);
  for (std::size_t k = 0; k < kBatchStates; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(kBatchStates - 1);  // 0 .. 1
    c[k] = rc_creepage{-3e-3 + 6e-3 * t, 1e-3 - 2e-3 * t, 0.3};
  }
  return c;
}

void BM_CApiBatch(benchmark::State& state) {
  rc_solver* solver = solver_with_method(RC_METHOD_NH_FASTSIM);
  rc_patch patch{};
  patch.kind = RC_GEOMETRY_ELLIPSE;
  patch.a_m = kA;
  patch.b_m = kB;
  patch.normal_force_N = kF3;
  const std::vector<rc_creepage> creepages = batch_creepages();
  std::vector<rc_forces> forces(kBatchStates);
  std::vector<int> statuses(kBatchStates);
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    if (rc_batch_creep_forces(solver, kBatchStates, &patch, 1, creepages.data(), threads, forces.data(), nullptr,
                              nullptr, statuses.data()) != RC_OK)
      state.SkipWithError("rc_batch_creep_forces failed");
    benchmark::DoNotOptimize(forces.data());
  }
  state.counters["states"] = static_cast<double>(kBatchStates);
  state.counters["us_per_state"] = benchmark::Counter(
      static_cast<double>(kBatchStates) * static_cast<double>(state.iterations()) * 1e-6,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  rc_solver_destroy(solver);
}
BENCHMARK(BM_CApiBatch)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

constexpr double kTableFz = 98100.0, kTableY = 0.125e-3;

// A table of the shipped S1002/UIC60 set-up, built once at the first use (a few seconds).
const rc_flextable* table() {
  static rc_flextable* t = [] {
    rc_flextable* built = nullptr;
    rc_flextable_create(&built);
    const double y[] = {0.0, 0.25e-3};
    const double loads[] = {kTableFz};
    if (rc_flextable_build(built, nullptr, y, 2, loads, 1, 3000, 2.1e11, 0.3, nullptr, nullptr) != RC_OK) {
      rc_flextable_destroy(built);
      return static_cast<rc_flextable*>(nullptr);
    }
    return built;
  }();
  return t;
}

void BM_CApiFlextableLookup(benchmark::State& state) {
  if (table() == nullptr) {
    state.SkipWithError("rc_flextable_build failed");
    return;
  }
  rc_flextable_values v{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(rc_flextable_lookup(table(), kTableY, kTableFz, &v));
    benchmark::DoNotOptimize(v);
  }
}
BENCHMARK(BM_CApiFlextableLookup);

void BM_CApiSetPatchFlextable(benchmark::State& state) {
  if (table() == nullptr) {
    state.SkipWithError("rc_flextable_build failed");
    return;
  }
  rc_solver* solver = solver_with_method(RC_METHOD_NH_FASTSIM);
  int k = 0;
  for (auto _ : state) {
    if (rc_solver_set_patch_flextable(solver, table(), kTableY * (1.0 + 1e-6 * (++k % 2)), kTableFz) != RC_OK) {
      char message[512];
      rc_solver_last_error(solver, message, sizeof message, nullptr);
      state.SkipWithError(message);
      break;
    }
  }
  rc_solver_destroy(solver);
}
BENCHMARK(BM_CApiSetPatchFlextable)->Unit(benchmark::kMillisecond);

// rc_wheelset_evaluate by position at the height and roll where the default loads are carried
// (found once by load with balance_roll), moving 1 um to the left per call.
void BM_CApiWheelsetStep(benchmark::State& state) {
  const bool warm = state.range(0) != 0;
  rc_wheelset* w = nullptr;
  rc_wheelset_create(&w);
  rc_wheelset_set_default_track(w);
  rc_wheelset_options options;
  rc_wheelset_options_default(&options);
  options.balance_roll = 1;
  rc_wheelset_set_options(w, &options);
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  rc_wheelset_result r{};
  if (rc_wheelset_evaluate(w, &s, &r) != RC_OK) state.SkipWithError("the balance by load failed");
  s.z_m = r.vertical_displacement_m;
  s.roll_rad = r.roll_rad;
  options.normal_mode = RC_WHEELSET_BY_POSITION;
  options.warm_start = warm ? 1 : 0;
  rc_wheelset_set_options(w, &options);
  rc_wheelset_evaluate(w, &s, &r);
  int patches = 0;
  for (auto _ : state) {
    s.y_m += 1e-6;
    if (rc_wheelset_evaluate(w, &s, &r) != RC_OK) state.SkipWithError("rc_wheelset_evaluate failed");
    patches = r.patch_count[0] + r.patch_count[1];
  }
  state.counters["patches"] = patches;
  rc_wheelset_destroy(w);
}
BENCHMARK(BM_CApiWheelsetStep)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
