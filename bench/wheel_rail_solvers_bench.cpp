// The solvers on the issue-15 comparison patch (docs/BENCHMARKS.md "Speed on the S1002/UIC60
// patch"): S1002 on UIC60 1:40 at y = 0, Fz = 98.1 kN, mu = 0.3, the paper's creepages
// xi' = eta' = 0.5 with the spin of the conicity; the argument is the target number of elements in
// contact (4700: the reference exact program's patch, ~4656 in contact).
//   BM_NhFastSimOnTheFly          NhFastSim(patch) with its flexibilities + forces, in a process
//                                 that has solved before (FFT plans made; the same patch, so the
//                                 coarse K2 operator's kernels are kept from the last call; K2's
//                                 adjoint solves made, the thread's memo of them emptied before each)
//   BM_NhFastSimOnTheFlyRemembered  the same with the memo: K2 from the adjoint solutions of the
//                                 last call (a patch met before, docs/FASTSIM.md)
//   BM_NhFastSimOnTheFlyNewPatchEachCall  the same over 21 patches in turn (no kernels kept)
//   BM_NhFastSimOnTheFlyAfterExact  BM_NhFastSimOnTheFly interleaved with other work, as in a time
//                                 step: before each timed call (memo emptied) the exact solver solves
//                                 the same patch, untimed, and leaves the caches full of its own data
//   BM_NhFastSimOnTheFlyAfterCacheFlush  the same after writing N MB (the argument), untimed, before
//                                 each timed call (memo emptied): 1 and 8 MB evict the core's L1 and
//                                 L2, 64 MB the whole 32 MB L3 too
//   BM_NhFastSimStage_*           its stages one by one (the profile breakdown)
//   BM_NhFastSimStageAfterCacheFlush  each stage (the argument: 0 FastSim's set-up, 1 coarsening,
//                                 2 K2's force rows, 3 the coarse FastSim and the match, 4 the march,
//                                 5 all, as BM_NhFastSimOnTheFly) warm (second argument 0) or after
//                                 writing 64 MB before each timed call (1): where a cold cache costs
//   BM_FastSimWithKnownFlexibilities  the march alone (flexibilities known: the table's cost)
//   BM_Exact                      solve_rolling_exact, inexact Newton (the default)
//   BM_ExactFixedKrylovTolerance  the same with every GMRES solve to 1e-6 (the exact Newton's alternative)
// Counters: elements in contact, GMRES/Newton iterations.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

#include "elastic/influence_operator.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"
#include "tangential/adhesion_tuning.hpp"

namespace {

using namespace railcontact;

constexpr double kMu = 0.3;

struct Case {
  WheelRailPatch patch;
  Creepage creepage;
};

const Case& comparison_case(int target_elements) {
  static std::map<int, Case> cases;
  auto it = cases.find(target_elements);
  if (it != cases.end()) return it->second;
  WheelRailPatchOptions options;
  options.target_elements = target_elements;
  WheelRailPatch patch = solve_wheel_rail_patch(default_wheel_rail_pair(), 0.0, options);
  const NhFastSim nh(patch.patch);
  const Creepage creepage =
      nh.creepage_from_normalised(0.5, 0.5, patch.spin_per_m, kMu, patch.patch.normal_force_N());
  return cases.emplace(target_elements, Case{std::move(patch), creepage}).first->second;
}

void count_elements(benchmark::State& state, const Case& c) {
  state.counters["elements"] = static_cast<double>(c.patch.elements_in_contact);
}

void BM_NhFastSimOnTheFly(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    forget_remembered_adjoints();
    benchmark::DoNotOptimize(NhFastSim(c.patch.patch).forces(c.creepage, kMu));
  }
  count_elements(state, c);
  const CoarseBlocks blocks = NhFastSim::automatic_coarse_blocks(c.patch.patch);
  state.counters["blocks_along"] = blocks.along;
  state.counters["blocks_across"] = blocks.across;
}
BENCHMARK(BM_NhFastSimOnTheFly)->Arg(3000)->Arg(4700)->Arg(11000)->Unit(benchmark::kMicrosecond);

void BM_NhFastSimOnTheFlyRemembered(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(NhFastSim(c.patch.patch).forces(c.creepage, kMu));
  count_elements(state, c);
}
BENCHMARK(BM_NhFastSimOnTheFlyRemembered)->Arg(4700)->Unit(benchmark::kMicrosecond);

// A different patch on every call: 21 patches of y = -0.5 ... 0.5 mm in steps of 0.05 mm, each with
// the element size that gives it ~4700 elements, so no two share a coarse mesh and the kept
// kernels of make_steady_rolling_operator never serve (the cost when each time step brings a new
// patch; FFT plans of known lengths are still kept).
void BM_NhFastSimOnTheFlyNewPatchEachCall(benchmark::State& state) {
  static const std::vector<Case> cases = [] {
    std::vector<Case> made;
    WheelRailPatchOptions options;
    options.target_elements = 4700;
    for (int i = -10; i <= 10; ++i) {
      WheelRailPatch patch = solve_wheel_rail_patch(default_wheel_rail_pair(), 0.05e-3 * i, options);
      const NhFastSim nh(patch.patch);
      const Creepage creepage =
          nh.creepage_from_normalised(0.5, 0.5, patch.spin_per_m, kMu, patch.patch.normal_force_N());
      made.push_back(Case{std::move(patch), creepage});
    }
    return made;
  }();
  std::size_t next = 0;
  for (auto _ : state) {
    const Case& c = cases[next];
    next = (next + 1) % cases.size();
    benchmark::DoNotOptimize(NhFastSim(c.patch.patch).forces(c.creepage, kMu));
  }
  state.counters["patches"] = static_cast<double>(cases.size());
}
BENCHMARK(BM_NhFastSimOnTheFlyNewPatchEachCall)->Unit(benchmark::kMicrosecond);

// The stages of NhFastSim's constructor (src/tangential/nh_fastsim.cpp), each on its own.
void BM_NhFastSimStage_FastSimSetUp(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(FastSim(c.patch.patch));
  count_elements(state, c);
}
BENCHMARK(BM_NhFastSimStage_FastSimSetUp)->Arg(4700)->Unit(benchmark::kMicrosecond);

void BM_NhFastSimStage_Coarsening(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  const CoarseBlocks blocks = NhFastSim::automatic_coarse_blocks(c.patch.patch);
  for (auto _ : state) benchmark::DoNotOptimize(coarsened(c.patch.patch, blocks));
  count_elements(state, c);
}
BENCHMARK(BM_NhFastSimStage_Coarsening)->Arg(4700)->Unit(benchmark::kMicrosecond);

ContactPatch coarse_patch(const Case& c) {
  return coarsened(c.patch.patch, NhFastSim::automatic_coarse_blocks(c.patch.patch));
}

void BM_NhFastSimStage_OperatorSetUp(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  const ContactPatch coarse = coarse_patch(c);
  for (auto _ : state)
    benchmark::DoNotOptimize(make_steady_rolling_operator(coarse.elements().mesh(), coarse.material(), 0.0));
  state.counters["coarse_elements"] = static_cast<double>(coarse.elements().count());
}
BENCHMARK(BM_NhFastSimStage_OperatorSetUp)->Arg(4700)->Unit(benchmark::kMicrosecond);

void BM_NhFastSimStage_OperatorProduct(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  const ContactPatch coarse = coarse_patch(c);
  InfluenceOperator R = make_steady_rolling_operator(coarse.elements().mesh(), coarse.material(), 0.0);
  const std::vector<double> x(2 * coarse.elements().count(), 1.0);
  std::vector<double> y(x.size());
  for (auto _ : state) {
    R.apply_transpose(coarse.elements().indices(), x, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["coarse_elements"] = static_cast<double>(coarse.elements().count());
}
BENCHMARK(BM_NhFastSimStage_OperatorProduct)->Arg(4700)->Unit(benchmark::kMicrosecond);

// K2's two force rows as NhFastSim solves them (operator set-up, preconditioner, two GMRES solves),
// with the options of its recipe (adhesion_options and kAdhesionTuning in nh_fastsim.cpp, internal
// there): the counter nh_fastsim_iterations is NhFastSim's own count, which gmres_iterations must equal.
void BM_NhFastSimStage_ForceRowsOfK2(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  const ContactPatch coarse = coarse_patch(c);
  AdhesionOptions options;
  options.part = CreepageMatrixPart::force_rows;
  options.tolerance = 3e-3;
  const AdhesionTuning tuning{AdhesionPreconditioner::marching_half_laplacian, 1.5};
  int iterations = 0;
  for (auto _ : state) {
    forget_remembered_adjoints();
    const AdhesionSolution K2 = solve_full_adhesion(coarse.elements(), coarse.material(), options, tuning);
    iterations = K2.iterations;
    benchmark::DoNotOptimize(K2.creepage_matrix.values.data());
  }
  state.counters["gmres_iterations"] = iterations;
  state.counters["nh_fastsim_iterations"] = NhFastSim(c.patch.patch).krylov_iterations();
  state.counters["coarse_elements"] = static_cast<double>(coarse.elements().count());
}
BENCHMARK(BM_NhFastSimStage_ForceRowsOfK2)->Arg(4700)->Unit(benchmark::kMicrosecond);

void BM_NhFastSimStage_CoarseFastSimAndMatch(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  const NhFastSim nh(c.patch.patch);
  const ContactPatch coarse = coarse_patch(c);
  for (auto _ : state) benchmark::DoNotOptimize(nh_fastsim_flexibility(FastSim(coarse), *nh.creepage_matrix()));
}
BENCHMARK(BM_NhFastSimStage_CoarseFastSimAndMatch)->Arg(4700)->Unit(benchmark::kMicrosecond);

void BM_FastSimWithKnownFlexibilities(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  const NhFastSim nh(c.patch.patch);
  for (auto _ : state) benchmark::DoNotOptimize(nh.forces(c.creepage, kMu));
  count_elements(state, c);
}
BENCHMARK(BM_FastSimWithKnownFlexibilities)->Arg(4700)->Unit(benchmark::kMicrosecond);

void BM_NhFastSimOnTheFlyAfterExact(benchmark::State& state) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    state.PauseTiming();
    benchmark::DoNotOptimize(solve_rolling_exact(c.patch.patch, c.creepage, kMu).forces);
    forget_remembered_adjoints();
    state.ResumeTiming();
    benchmark::DoNotOptimize(NhFastSim(c.patch.patch).forces(c.creepage, kMu));
  }
  count_elements(state, c);
}
// A fixed count: the untimed exact solves (tens of ms each) would otherwise run for minutes.
BENCHMARK(BM_NhFastSimOnTheFlyAfterExact)->Arg(4700)->Iterations(40)->Unit(benchmark::kMicrosecond);

// Writes `megabytes` MB, one byte per cache line: the caches then hold this buffer, not the solver's
// code and data.
void flush_caches(std::size_t megabytes) {
  static std::vector<char> buffer;
  buffer.resize(std::max(buffer.size(), megabytes << 20));
  static char value = 0;
  ++value;
  for (std::size_t i = 0; i < (megabytes << 20); i += 64) buffer[i] = value;
  benchmark::ClobberMemory();
}

void BM_NhFastSimOnTheFlyAfterCacheFlush(benchmark::State& state) {
  const Case& c = comparison_case(4700);
  for (auto _ : state) {
    state.PauseTiming();
    flush_caches(static_cast<std::size_t>(state.range(0)));
    forget_remembered_adjoints();
    state.ResumeTiming();
    benchmark::DoNotOptimize(NhFastSim(c.patch.patch).forces(c.creepage, kMu));
  }
  count_elements(state, c);
}
BENCHMARK(BM_NhFastSimOnTheFlyAfterCacheFlush)->Arg(1)->Arg(8)->Arg(64)->Iterations(200)->Unit(benchmark::kMicrosecond);

void BM_NhFastSimStageAfterCacheFlush(benchmark::State& state) {
  const Case& c = comparison_case(4700);
  const ContactPatch& patch = c.patch.patch;
  const CoarseBlocks blocks = NhFastSim::automatic_coarse_blocks(patch);
  const ContactPatch coarse = coarsened(patch, blocks);
  AdhesionOptions options;  // K2's force rows as NhFastSim solves them (BM_NhFastSimStage_ForceRowsOfK2)
  options.part = CreepageMatrixPart::force_rows;
  options.tolerance = 3e-3;
  const AdhesionTuning tuning{AdhesionPreconditioner::marching_half_laplacian, 1.5};
  const NhFastSim nh(patch);
  const auto stage = [&] {
    switch (state.range(0)) {
      case 0: benchmark::DoNotOptimize(FastSim(patch)); break;
      case 1: benchmark::DoNotOptimize(coarsened(patch, blocks)); break;
      case 2:
        forget_remembered_adjoints();
        benchmark::DoNotOptimize(solve_full_adhesion(coarse.elements(), coarse.material(), options, tuning));
        break;
      case 3: benchmark::DoNotOptimize(nh_fastsim_flexibility(FastSim(coarse), *nh.creepage_matrix())); break;
      case 4: benchmark::DoNotOptimize(nh.forces(c.creepage, kMu)); break;
      default:
        forget_remembered_adjoints();
        benchmark::DoNotOptimize(NhFastSim(patch).forces(c.creepage, kMu));
    }
  };
  static const char* const kNames[] = {"FastSim set-up", "coarsening", "K2 force rows", "coarse FastSim + match",
                                       "march", "all"};
  state.SetLabel(kNames[std::clamp<std::int64_t>(state.range(0), 0, 5)]);
  for (auto _ : state) {
    state.PauseTiming();
    if (state.range(1) == 1) flush_caches(64);
    state.ResumeTiming();
    stage();
  }
}
BENCHMARK(BM_NhFastSimStageAfterCacheFlush)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0, 1}})
    ->Iterations(200)
    ->Unit(benchmark::kMicrosecond);

void run_exact(benchmark::State& state, bool inexact_newton) {
  const Case& c = comparison_case(static_cast<int>(state.range(0)));
  RollingOptions options;
  options.inexact_newton = inexact_newton;
  RollingSolution solution;
  for (auto _ : state) {
    solution = solve_rolling_exact(c.patch.patch, c.creepage, kMu, options);
    benchmark::DoNotOptimize(solution.forces);
  }
  count_elements(state, c);
  state.counters["newton"] = solution.newton_iterations;
  state.counters["gmres_iterations"] = solution.krylov_iterations;
}

void BM_Exact(benchmark::State& state) { run_exact(state, true); }
BENCHMARK(BM_Exact)->Arg(3000)->Arg(4700)->Arg(11000)->Unit(benchmark::kMillisecond);

void BM_ExactFixedKrylovTolerance(benchmark::State& state) { run_exact(state, false); }
BENCHMARK(BM_ExactFixedKrylovTolerance)->Arg(3000)->Arg(4700)->Arg(11000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
