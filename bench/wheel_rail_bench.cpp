// Wheel–rail normal contact timing (docs/WHEEL_RAIL.md §7): S1002 on UIC60 1:40, Fz = 98.1 kN,
// about 3000 elements in contact, at y = 0 (the paper's worst case) and y = −2 mm.
//   BM_WheelRailNormalSolve       the normal solve only, on the prepared potential area and h
//                                 (plan reused: influence operator and FFT plans built once)
//   BM_WheelRailNormalWithSetup   the same with the plan built per call (solve_normal_contact)
//   BM_WheelRailGeometry          contact point + potential area with h (the final mesh size)
//   BM_WheelRailPatch             everything: solve_wheel_rail_patch (geometry, Hertz estimate,
//                                 mesh passes, normal solves, regions)
//   BM_LoadDefaultPair            reading and smoothing the two profiles (once per simulation)
// The argument is y in micrometres.
#include <benchmark/benchmark.h>

#include <vector>

#include "railcontact/normal.hpp"
#include "railcontact/wheel_rail.hpp"

namespace {

using namespace railcontact;

const WheelRailPair& pair() {
  static const WheelRailPair p = default_wheel_rail_pair();
  return p;
}

double y_of(const benchmark::State& state) { return static_cast<double>(state.range(0)) * 1e-6; }

void report(benchmark::State& state, const WheelRailPatch& p) {
  state.counters["contact_elements"] = static_cast<double>(p.elements_in_contact);
  state.counters["mesh_elements"] = static_cast<double>(p.potential_area.size());
  state.counters["iterations"] = p.iterations;
  state.counters["solves"] = p.mesh_passes;
}

void BM_WheelRailNormalSolve(benchmark::State& state) {
  const WheelRailPatch p = solve_wheel_rail_patch(pair(), y_of(state));
  NormalContactSolver solver(p.potential_area, WheelRailPatchOptions{}.material);
  NormalSolution s;
  for (auto _ : state) {
    s = solver.solve(p.potential_h_m, p.normal_force_N);
    benchmark::DoNotOptimize(s.pressure_Pa.data());
  }
  report(state, p);
  state.counters["iterations"] = s.iterations;
}
BENCHMARK(BM_WheelRailNormalSolve)->Arg(0)->Arg(-2000)->Unit(benchmark::kMillisecond);

void BM_WheelRailNormalWithSetup(benchmark::State& state) {
  const WheelRailPatch p = solve_wheel_rail_patch(pair(), y_of(state));
  NormalSolution s;
  for (auto _ : state) {
    s = solve_normal_contact(p.potential_area, p.potential_h_m, p.normal_force_N, WheelRailPatchOptions{}.material);
    benchmark::DoNotOptimize(s.pressure_Pa.data());
  }
  report(state, p);
}
BENCHMARK(BM_WheelRailNormalWithSetup)->Arg(0)->Arg(-2000)->Unit(benchmark::kMillisecond);

void BM_WheelRailGeometry(benchmark::State& state) {
  const WheelRailPatch p = solve_wheel_rail_patch(pair(), y_of(state));
  PotentialAreaOptions options;
  options.dx1_m = p.potential_area.dx1_m;
  options.dx2_m = p.potential_area.dx2_m;
  for (auto _ : state) {
    const WheelRailContactPoint c = pair().contact_point(y_of(state));
    PotentialContactArea area = potential_contact_area(pair(), c, p.approach_m, options);
    benchmark::DoNotOptimize(area.h_m.data());
  }
  report(state, p);
}
BENCHMARK(BM_WheelRailGeometry)->Arg(0)->Arg(-2000)->Unit(benchmark::kMillisecond);

void BM_WheelRailPatch(benchmark::State& state) {
  WheelRailPatch p;
  for (auto _ : state) {
    p = solve_wheel_rail_patch(pair(), y_of(state));
    benchmark::DoNotOptimize(p.max_pressure_Pa);
  }
  report(state, p);
}
BENCHMARK(BM_WheelRailPatch)->Arg(0)->Arg(-2000)->Unit(benchmark::kMillisecond);

void BM_LoadDefaultPair(benchmark::State& state) {
  for (auto _ : state) {
    const WheelRailPair p = default_wheel_rail_pair();
    benchmark::DoNotOptimize(p.rail_top_z_m());
  }
}
BENCHMARK(BM_LoadDefaultPair)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
