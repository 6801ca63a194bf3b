#pragma once
// Independent cases (sweep states, table nodes) computed on threads (docs/SCALING.md): one worker
// per thread, made by the caller's factory (each worker owns its library objects: a Wheelset, a
// solver; nothing is shared between threads), the next case taken from an atomic counter, each
// result handed back with its case index. Results never depend on the number of threads: a case
// is computed from its index alone, and the caller files the results by index.
//
// Also here: the parsing of --threads and --shard, and the progress line with the time left.
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

namespace railcontact::study {

// The cores of this machine (std::thread::hardware_concurrency, at least 1).
int available_cores();

// "--threads" given as text: a whole number >= 1. Throws Error (invalid_input) naming the option,
// the value and what is allowed ("0", "-2", "1.5", "many" are refused).
int parse_threads(const std::string& text, const std::string& option = "--threads");

// Shard i of N (--shard i/N, 0 <= i < N): the cases whose index k has k mod N = i.
struct Shard {
  std::size_t index = 0;
  std::size_t count = 1;
  [[nodiscard]] bool contains(std::size_t k) const { return k % count == index; }
  [[nodiscard]] bool whole() const { return count == 1; }
};
// "i/N" with 0 <= i < N <= 100000. Throws Error (invalid_input) naming the value.
Shard parse_shard(const std::string& text, const std::string& option = "--shard");

// A case's result as bytes (e.g. its CSV rows) and whether it failed (the bytes then say why).
struct CaseResult {
  std::string text;
  bool failed = false;
};
// Computes case k. A worker is used by one thread only.
using CaseWorker = std::function<CaseResult(std::size_t k)>;
using CaseWorkerFactory = std::function<CaseWorker()>;
// Receives case k's result; called under a lock (one call at a time), in completion order.
using CaseSink = std::function<void(std::size_t k, CaseResult&& result)>;

// Computes the cases `todo` on `threads` threads (1: on the calling thread). An exception thrown by
// a worker (other than a case's own failure, which the worker returns as failed) stops the others
// after their current case and is rethrown here.
void run_cases_on_threads(const std::vector<std::size_t>& todo, int threads, const CaseWorkerFactory& make_worker,
                          const CaseSink& sink);

// "  [ 40 %] 40/100 cases, 12 s, about 18 s left": at every tenth of the cases, at most 10 s
// apart otherwise, and at the last one; the time left from the mean time per case so far.
class ProgressLine {
 public:
  ProgressLine(std::ostream& log, std::string unit, std::size_t total);
  void done(std::size_t completed);  // after each case (under the caller's lock)

 private:
  std::ostream& log_;
  std::string unit_;
  std::size_t total_;
  std::size_t next_report_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace railcontact::study
