// Threads on a sweep (docs/SCALING.md): the cases of examples/sweep_yaw_y.toml (S1002/UIC60, 98.1 kN
// per wheel, 0.5 mm elements, nh-fastsim and fastsim; 2 yaws × 9 y from −4 to 4 mm, one and two
// patches per wheel) computed by the sweep's workers on 1 and 2 threads, as `railcontact sweep`
// does (every case cold, results filed by index; the journal and the files are left out).
//   BM_SweepThreads/T   the 18 cases on T threads; counter cases_per_s. Speed-up = time(1) / time(T)
//                       (real time: the wall clock of the whole sweep).
//   BM_SweepCase/k      case k alone on one thread (the spread of the per-case cost, for the cost
//                       model of docs/SCALING.md).
#include <benchmark/benchmark.h>

#include <numeric>
#include <vector>

#include "case/sweep_file.hpp"
#include "study/case_pool.hpp"
#include "study/sweep_run.hpp"

namespace {

using namespace railcontact;

const SweepFile& sweep() {
  static const SweepFile s = read_sweep_file(RAILCONTACT_EXAMPLES_DIR "/sweep_yaw_y.toml");
  return s;
}
const WheelsetTrack& track() {
  static const WheelsetTrack t = wheelset_track(sweep().base);
  return t;
}

void BM_SweepThreads(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<std::size_t> todo(sweep().size());
  std::iota(todo.begin(), todo.end(), std::size_t{0});
  const study::CaseWorkerFactory factory = study::sweep_worker_factory(sweep(), track());
  std::size_t bytes = 0;
  for (auto _ : state) {
    bytes = 0;
    study::run_cases_on_threads(todo, threads, factory,
                                [&](std::size_t, study::CaseResult&& r) { bytes += r.text.size(); });
  }
  state.counters["cases_per_s"] =
      benchmark::Counter(static_cast<double>(todo.size()) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["csv_bytes_per_case"] = static_cast<double>(bytes) / static_cast<double>(todo.size());
}
BENCHMARK(BM_SweepThreads)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_SweepCase(benchmark::State& state) {
  const study::CaseWorker worker = study::sweep_worker_factory(sweep(), track())();
  const auto k = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(worker(k));
}
BENCHMARK(BM_SweepCase)->DenseRange(0, 17, 1)->Unit(benchmark::kMillisecond)->MinTime(0.3);

}  // namespace

BENCHMARK_MAIN();
