// The tangential solvers on Hertzian patches of ~700, ~2800 and ~11000 elements, in one run:
// FastSim evaluation alone, nH-FastSim including its flexibilities (K2 force rows, of the patch
// itself and of the automatically coarsened patch), the exact
// (semismooth Newton) and the regularised (paper Appendix) solvers. Report: docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include "railcontact/contact_patch.hpp"
#include "railcontact/tangential.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};
constexpr double kMu = 0.3;
const Creepage kCombined{5e-4, 5e-4, 0.5};  // xi' ~ eta' ~ 0.3 with spin: a large slip area

ContactPatch patch(int elements) {
  const double a = 6e-3, b = 4.5e-3;
  return hertzian_patch(elliptical_contact_with_count(a, b, elements, EllipseMeshLayout::rolling_resolved), a, b,
                        98100.0, kSteel);
}

void BM_FastSimEvaluation(benchmark::State& state, Creepage creepage) {
  const ContactPatch p = patch(static_cast<int>(state.range(0)));
  const FastSim fastsim(p);
  const Flexibility L = fastsim_flexibility(6e-3, 4.5e-3, kSteel);
  for (auto _ : state) benchmark::DoNotOptimize(fastsim.forces(creepage, L, kMu));
  state.counters["elements"] = static_cast<double>(p.elements().count());
  state.counters["ns_per_element"] =
      benchmark::Counter(static_cast<double>(p.elements().count()), benchmark::Counter::kIsIterationInvariantRate |
                                                                        benchmark::Counter::kInvert);
}
BENCHMARK_CAPTURE(BM_FastSimEvaluation, pure_creepage, Creepage{5e-4, 5e-4, 0})->Arg(700)->Arg(2800)->Arg(11000);
BENCHMARK_CAPTURE(BM_FastSimEvaluation, with_spin, kCombined)->Arg(700)->Arg(2800)->Arg(11000);

void BM_NhFastSimWithFlexibilities(benchmark::State& state) {
  const ContactPatch p = patch(static_cast<int>(state.range(0)));
  NhFastSimOptions full_resolution;  // K2 of the patch itself
  full_resolution.flexibility_coarsening = 1;
  for (auto _ : state) benchmark::DoNotOptimize(NhFastSim(p, full_resolution).forces(kCombined, kMu));
  state.counters["elements"] = static_cast<double>(p.elements().count());
}
BENCHMARK(BM_NhFastSimWithFlexibilities)->Arg(700)->Arg(2800)->Arg(11000)->Unit(benchmark::kMillisecond);

// As `railcontact run` computes it: flexibilities from K2 of the automatically coarsened patch.
void BM_NhFastSimWithDefaultFlexibilities(benchmark::State& state) {
  const ContactPatch p = patch(static_cast<int>(state.range(0)));
  const CoarseBlocks blocks = NhFastSim::automatic_coarse_blocks(p);
  for (auto _ : state) benchmark::DoNotOptimize(NhFastSim(p).forces(kCombined, kMu));
  state.counters["elements"] = static_cast<double>(p.elements().count());
  state.counters["blocks_along"] = blocks.along;
  state.counters["blocks_across"] = blocks.across;
}
BENCHMARK(BM_NhFastSimWithDefaultFlexibilities)->Arg(700)->Arg(2800)->Arg(11000)->Unit(benchmark::kMillisecond);

void BM_Exact(benchmark::State& state) {
  const ContactPatch p = patch(static_cast<int>(state.range(0)));
  int newton = 0;
  for (auto _ : state) {
    const RollingSolution s = solve_rolling_exact(p, kCombined, kMu);
    newton = s.newton_iterations;
    benchmark::DoNotOptimize(s.forces);
  }
  state.counters["elements"] = static_cast<double>(p.elements().count());
  state.counters["newton"] = newton;
}
BENCHMARK(BM_Exact)->Arg(700)->Arg(2800)->Arg(11000)->Unit(benchmark::kMillisecond);

void BM_ExactRegularised(benchmark::State& state) {
  const ContactPatch p = patch(static_cast<int>(state.range(0)));
  int newton = 0;
  for (auto _ : state) {
    const RollingSolution s = solve_rolling_regularised(p, kCombined, kMu);
    newton = s.newton_iterations;
    benchmark::DoNotOptimize(s.forces);
  }
  state.counters["elements"] = static_cast<double>(p.elements().count());
  state.counters["newton"] = newton;
}
BENCHMARK(BM_ExactRegularised)->Arg(700)->Arg(2800)->Arg(11000)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
}  // namespace railcontact

BENCHMARK_MAIN();
