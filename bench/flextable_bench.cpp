// nH-FastSim from a flexibility table against `exact` (docs/FLEXTABLE.md §7): S1002 on UIC60 1:40,
// Fz = 98.1 kN, about 3000 elements in contact, y = 0.125 mm (between the nodes 0 and 0.25 mm of a
// table built at start-up, next to the paper's worst case y = 0), mu = 0.3, the paper's creepages
// xi' = eta' = 0.5 with spin from conicity.
//   BM_TableLookup           interpolation of the table for the patch (lookup_for_patch)
//   BM_CachedPatchStep       (b) FastSim only on the cached patch (Patch::forces)
//   BM_CachedPatchWithLookup (b) lookup + FastSim: a step whose y, Fz moved within the patch
//   BM_CachedPatchStepFlexibilityWeighted  (b) with the flexibility-weighted slip direction
//                            (TractionBound::slip_direction; the wheelset's default) instead of Eq 8
//   BM_FullStep              (a) normal solve + FastSim preparation + lookup + FastSim
//   BM_OnTheFlyNhFastSim     on the same patch: K2's force rows + flexibilities + FastSim
//   BM_Exact                 on the same patch: solve_rolling_exact
// Every benchmark reports `exact_over_this`: the time of one `exact` solve (measured once at
// start-up, median of 5) divided by its own time per iteration (wall clock).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "railcontact/flexibility_table.hpp"
#include "railcontact/tangential.hpp"
#include "tangential/adhesion_tuning.hpp"

namespace {

using namespace railcontact;
using Clock = std::chrono::steady_clock;

constexpr double kY = 0.125e-3;
constexpr double kFz = 98100.0;
constexpr double kMu = 0.3;

struct Setup {
  FlexibilityTableFastSim nh;
  FlexibilityTableFastSim::Patch patch;
  Creepage creepage;
  double exact_s = 0.0;
};

Setup make_setup() {
  WheelRailPair pair = default_wheel_rail_pair();
  FlexibilityTable table = build_flexibility_table(pair, {0.0, 0.25e-3}, {kFz});
  FlexibilityTableFastSim nh(std::move(table), std::move(pair));
  FlexibilityTableFastSim::Patch patch = nh.prepare(kY, kFz);
  const Creepage creepage = patch.creepage_from_normalised(0.5, 0.5, patch.spin_per_m(), kMu);
  std::vector<double> times;
  for (int k = 0; k < 5; ++k) {
    const auto start = Clock::now();
    benchmark::DoNotOptimize(solve_rolling_exact(patch.wheel_rail_patch().patch, creepage, kMu).forces);
    times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return {std::move(nh), std::move(patch), creepage, times[2]};
}

const Setup& setup() {
  static const Setup s = make_setup();
  return s;
}

// Runs `step` in the benchmark loop and reports the ratio to `exact`.
template <class Step>
void measure(benchmark::State& state, Step step) {
  const Setup& s = setup();
  const auto start = Clock::now();
  for (auto _ : state) step(s);
  const double per_iteration_s =
      std::chrono::duration<double>(Clock::now() - start).count() / static_cast<double>(state.iterations());
  state.counters["exact_over_this"] = s.exact_s / per_iteration_s;
  state.counters["exact_ms"] = 1e3 * s.exact_s;
  state.counters["elements"] = static_cast<double>(s.patch.wheel_rail_patch().elements_in_contact);
}

void BM_TableLookup(benchmark::State& state) {
  measure(state, [](const Setup& s) {
    benchmark::DoNotOptimize(s.nh.table().lookup_for_patch(kY, kFz, s.patch.wheel_rail_patch().area_m2));
  });
}
BENCHMARK(BM_TableLookup);

void BM_CachedPatchStep(benchmark::State& state) {
  measure(state, [](const Setup& s) { benchmark::DoNotOptimize(s.patch.forces(s.creepage, kMu)); });
}
BENCHMARK(BM_CachedPatchStep)->Unit(benchmark::kMicrosecond);

void BM_CachedPatchStepFlexibilityWeighted(benchmark::State& state) {
  const Setup& s0 = setup();
  const FastSim weighted(s0.patch.wheel_rail_patch().patch, TractionBound{TractionBound{}.skew,
                                                                        SlipDirection::flexibility_weighted});
  const Flexibility L = s0.patch.nh_fastsim().flexibility();
  measure(state, [&](const Setup& s) { benchmark::DoNotOptimize(weighted.forces(s.creepage, L, kMu)); });
}
BENCHMARK(BM_CachedPatchStepFlexibilityWeighted)->Unit(benchmark::kMicrosecond);

void BM_CachedPatchWithLookup(benchmark::State& state) {
  measure(state, [](const Setup& s) {
    const FlexibilityTableValues v = s.nh.table().lookup_for_patch(kY, kFz, s.patch.wheel_rail_patch().area_m2);
    benchmark::DoNotOptimize(s.patch.nh_fastsim().fastsim().forces(s.creepage, v.flexibility, kMu));
  });
}
BENCHMARK(BM_CachedPatchWithLookup)->Unit(benchmark::kMicrosecond);

void BM_FullStep(benchmark::State& state) {
  measure(state, [](const Setup& s) { benchmark::DoNotOptimize(s.nh.forces(kY, kFz, s.creepage, kMu)); });
}
BENCHMARK(BM_FullStep)->Unit(benchmark::kMillisecond);

void BM_OnTheFlyNhFastSim(benchmark::State& state) {
  measure(state, [](const Setup& s) {
    // The recipe of the table (and of `railcontact run`): K2 of the automatically coarsened patch,
    // solved (not from the thread's memo of a patch met before).
    forget_remembered_adjoints();
    benchmark::DoNotOptimize(NhFastSim(s.patch.wheel_rail_patch().patch).forces(s.creepage, kMu));
  });
}
BENCHMARK(BM_OnTheFlyNhFastSim)->Unit(benchmark::kMillisecond);

void BM_Exact(benchmark::State& state) {
  measure(state, [](const Setup& s) {
    benchmark::DoNotOptimize(solve_rolling_exact(s.patch.wheel_rail_patch().patch, s.creepage, kMu).forces);
  });
}
BENCHMARK(BM_Exact)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
