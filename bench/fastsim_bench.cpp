// FastSim marching cost per element in contact (target: <= 5 ns pure creepage, <= 10 ns with
// spin, single thread), on Hertzian patches of ~700, ~2800 and ~11000 elements.
// Run: build/bench/fastsim_bench [--benchmark_repetitions=5 --benchmark_report_aggregates_only=true]
#include <benchmark/benchmark.h>

#include <cstdint>

#include "railcontact/contact_patch.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/kalker.hpp"

namespace {

using namespace railcontact;

constexpr double kA_m = 6e-3, kB_m = 4.5e-3, kNormalForce_N = 98.1e3, kMu = 0.3;

ContactPatch bench_patch(std::int64_t elements) {
  return hertzian_patch(elliptical_contact_with_count(kA_m, kB_m, static_cast<int>(elements)), kA_m, kB_m,
                        kNormalForce_N, Material{});
}

// Creepages of the wheel-rail range with partial slip (about xi' ~ 0.4, eta' ~ 0.2; with spin
// phi ~ 2 sin(0.05 rad) / 0.92 m scaled up to make spin matter).
constexpr Creepage kPureCreepage{1.0e-3, 5e-4, 0.0};
constexpr Creepage kWithSpin{1.0e-3, 5e-4, 0.5};

void set_counters(benchmark::State& state, const FastSim& fastsim, double adhesion_fraction) {
  const auto n = static_cast<double>(fastsim.element_count());
  state.counters["elements"] = n;
  // seconds per (iteration x 1e-9 elements) = ns per element
  state.counters["ns_per_element"] =
      benchmark::Counter(n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["adhesion"] = adhesion_fraction;
}

void BM_FastSimForces(benchmark::State& state, Creepage creepage) {
  const ContactPatch patch = bench_patch(state.range(0));
  const FastSim fastsim(patch);
  const Flexibility L = fastsim_flexibility(kA_m, kB_m, patch.material());
  for (auto _ : state) {
    TangentialForces f = fastsim.forces(creepage, L, kMu);
    benchmark::DoNotOptimize(f);
  }
  set_counters(state, fastsim, fastsim.solve(creepage, L, kMu).adhesion_fraction);
}

void BM_FastSimSolve(benchmark::State& state, Creepage creepage) {
  const ContactPatch patch = bench_patch(state.range(0));
  const FastSim fastsim(patch);
  const Flexibility L = fastsim_flexibility(kA_m, kB_m, patch.material());
  double adhesion = 0.0;
  for (auto _ : state) {
    FastSimResult r = fastsim.solve(creepage, L, kMu);
    adhesion = r.adhesion_fraction;
    benchmark::DoNotOptimize(r);
  }
  set_counters(state, fastsim, adhesion);
}

// The slipping traction's direction (SlipDirection) on a patch in deep slip under spin, with a spin
// flexibility of 0.4 L1 (nH-FastSim's on flange patches): the cost of the weighted limitings against
// Eq 8's. Arg: the SlipDirection (0 radial, 1 flexibility-weighted, 2 rigid-slip), 2800 elements.
void BM_FastSimSlipDirection(benchmark::State& state) {
  const ContactPatch patch = bench_patch(2800);
  const FastSim fastsim(patch, TractionBound{TractionBound{}.skew, static_cast<SlipDirection>(state.range(0))});
  Flexibility L = fastsim_flexibility(kA_m, kB_m, patch.material());
  L.L3 = 0.4 * L.L1;
  const Creepage deep{2e-2, 2e-2, 3.0};
  for (auto _ : state) {
    TangentialForces f = fastsim.forces(deep, L, kMu);
    benchmark::DoNotOptimize(f);
  }
  set_counters(state, fastsim, fastsim.solve(deep, L, kMu).adhesion_fraction);
}

// The per-patch preparation (parabolic bound, lane layout, S D B), paid once per patch.
void BM_FastSimPrepare(benchmark::State& state) {
  const ContactPatch patch = bench_patch(state.range(0));
  for (auto _ : state) {
    FastSim fastsim(patch);
    benchmark::DoNotOptimize(fastsim);
  }
  set_counters(state, FastSim(patch), 1.0);
}

BENCHMARK_CAPTURE(BM_FastSimForces, pure_creepage, kPureCreepage)->Arg(700)->Arg(2800)->Arg(11000);
BENCHMARK_CAPTURE(BM_FastSimForces, with_spin, kWithSpin)->Arg(700)->Arg(2800)->Arg(11000);
BENCHMARK_CAPTURE(BM_FastSimSolve, pure_creepage, kPureCreepage)->Arg(700)->Arg(2800)->Arg(11000);
BENCHMARK_CAPTURE(BM_FastSimSolve, with_spin, kWithSpin)->Arg(700)->Arg(2800)->Arg(11000);
BENCHMARK(BM_FastSimPrepare)->Arg(700)->Arg(2800)->Arg(11000);
BENCHMARK(BM_FastSimSlipDirection)->Arg(0)->Arg(1)->Arg(2);

}  // namespace

BENCHMARK_MAIN();
