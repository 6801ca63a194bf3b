// K2 (three right-hand sides) on elliptical patches: Krylov (two preconditioners) and dense LU
// in the same run, plus one steady-rolling operator product by FFT. See docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <vector>

#include "elastic/influence_operator.hpp"
#include "tangential/adhesion_tuning.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/contact_patch.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};

ContactElements circle(int elements) { return elliptical_contact_with_count(6e-3, 6e-3, elements); }

void BM_SteadyRollingOperatorProduct(benchmark::State& state) {
  const ContactElements e = circle(static_cast<int>(state.range(0)));
  InfluenceOperator R = make_steady_rolling_operator(e.mesh(), kSteel, 0.0);
  std::vector<double> x(2 * e.count(), 1.0), y(2 * e.count());
  for (auto _ : state) {
    R.apply(e.indices(), x, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["elements"] = static_cast<double>(e.count());
}
BENCHMARK(BM_SteadyRollingOperatorProduct)->Arg(700)->Arg(2800)->Arg(11000)->Unit(benchmark::kMicrosecond);

void BM_NormalOperatorProductOnGrid(benchmark::State& state) {
  const ContactElements e = circle(static_cast<int>(state.range(0)));
  InfluenceOperator A = make_normal_operator(e.mesh(), kSteel);
  std::vector<double> x(e.mesh().size(), 1.0), y(e.mesh().size());
  for (auto _ : state) {
    A.apply_on_grid(x, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["elements"] = static_cast<double>(e.count());
}
BENCHMARK(BM_NormalOperatorProductOnGrid)->Arg(2800)->Unit(benchmark::kMicrosecond);

void run_K2(benchmark::State& state, AdhesionOptions options, const AdhesionTuning& tuning = {}) {
  const ContactElements e = circle(static_cast<int>(state.range(0)));
  options.tolerance = 1e-8;
  int iterations = 0;
  for (auto _ : state) {
    const AdhesionSolution s = solve_full_adhesion(e, kSteel, options, tuning);
    iterations = s.iterations;
    benchmark::DoNotOptimize(s.creepage_matrix.values.data());
  }
  state.counters["elements"] = static_cast<double>(e.count());
  state.counters["gmres_iterations"] = iterations;
}

void BM_K2_Krylov(benchmark::State& state) { run_K2(state, AdhesionOptions{}); }
BENCHMARK(BM_K2_Krylov)->Arg(700)->Arg(2800)->Arg(11000)->Unit(benchmark::kMillisecond);

void BM_K2_Krylov_MarchingOnly(benchmark::State& state) {
  run_K2(state, AdhesionOptions{}, AdhesionTuning{AdhesionPreconditioner::marching, 3.0});
}
BENCHMARK(BM_K2_Krylov_MarchingOnly)->Arg(700)->Arg(2800)->Arg(11000)->Unit(benchmark::kMillisecond);

void BM_K2_Krylov_SpinAlpha05(benchmark::State& state) {
  AdhesionOptions o;
  o.spin_collocation_offset = 0.5;
  run_K2(state, o);
}
BENCHMARK(BM_K2_Krylov_SpinAlpha05)->Arg(2800)->Unit(benchmark::kMillisecond);

void BM_K2_DenseLU(benchmark::State& state) {
  AdhesionOptions o;
  o.solver = LinearSolver::dense;
  run_K2(state, o);
}
BENCHMARK(BM_K2_DenseLU)->Arg(700)->Arg(2800)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_K2_DenseLU)->Arg(11000)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace railcontact

BENCHMARK_MAIN();
