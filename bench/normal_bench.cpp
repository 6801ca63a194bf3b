// Normal contact solver timing (docs/NORMAL.md): Hertzian h of a wheel (R = 0.46 m) on a rail
// crown (0.3 m), F3 = 98.1 kN, steel, on an n1 x n2 mesh covering 1.1 a x 1.1 b (about 2/3 of
// the elements in contact: ~3100 at 80 x 60, cf. CONTACT's ~0.1 s for ~3100 elements).
#include <benchmark/benchmark.h>

#include <vector>

#include "railcontact/hertz.hpp"
#include "railcontact/normal.hpp"

namespace {

using namespace railcontact;

constexpr double kA = 1.0 / (2 * 0.46), kB = 1.0 / (2 * 0.3), kLoad_N = 98.1e3;
const Material kSteel{2.1e11, 0.3};

struct Case {
  Mesh mesh;
  std::vector<double> h;
};

Case hertz_case(int n1, int n2) {
  const HertzContact hertz = hertz_from_curvatures(kA, kB, kLoad_N, kSteel);
  Case c{Mesh::covering(-1.1 * hertz.a_m, 1.1 * hertz.a_m, -1.1 * hertz.b_m, 1.1 * hertz.b_m, n1, n2), {}};
  c.h.resize(c.mesh.size());
  for (int i2 = 0; i2 < n2; ++i2)
    for (int i1 = 0; i1 < n1; ++i1) {
      const double x1 = c.mesh.x1(i1), x2 = c.mesh.x2(i2);
      c.h[c.mesh.index(i1, i2)] = kA * x1 * x1 + kB * x2 * x2;
    }
  return c;
}

void report(benchmark::State& state, const NormalSolution& s) {
  state.counters["contact_elements"] = static_cast<double>(s.elements_in_contact);
  state.counters["iterations"] = s.iterations;
  state.counters["converged"] = s.converged ? 1 : 0;
}

// Solve only: the plan (influence operator, FFT plans, workspace) is built once and reused.
void BM_NormalSolve(benchmark::State& state) {
  const Case c = hertz_case(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  NormalContactSolver solver(c.mesh, kSteel);
  NormalSolution s;
  for (auto _ : state) {
    s = solver.solve(c.h, kLoad_N);
    benchmark::DoNotOptimize(s.pressure_Pa.data());
  }
  report(state, s);
}
BENCHMARK(BM_NormalSolve)->Args({40, 30})->Args({80, 60})->Args({160, 120})->Unit(benchmark::kMillisecond);

// Everything: influence coefficients, FFT plans and the solve (solve_normal_contact).
void BM_NormalSolveWithSetup(benchmark::State& state) {
  const Case c = hertz_case(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  NormalSolution s;
  for (auto _ : state) {
    s = solve_normal_contact(c.mesh, c.h, kLoad_N, kSteel);
    benchmark::DoNotOptimize(s.pressure_Pa.data());
  }
  report(state, s);
}
BENCHMARK(BM_NormalSolveWithSetup)->Args({80, 60})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
