// Independent cases on threads (see the header).
#include "study/case_pool.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <exception>
#include <thread>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact::study {

int available_cores() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

namespace {
bool parse_whole(const std::string& text, long long& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end && !text.empty();
}
}  // namespace

int parse_threads(const std::string& text, const std::string& option) {
  long long n = 0;
  if (!parse_whole(text, n) || n < 1 || n > 4096)
    throw Error(fmt::format("{} '{}' must be a whole number of threads from 1 to 4096 (default: all {} cores)", option,
                            printable_excerpt(text), available_cores()));
  return static_cast<int>(n);
}

Shard parse_shard(const std::string& text, const std::string& option) {
  const std::size_t slash = text.find('/');
  long long i = -1, n = 0;
  if (slash == std::string::npos || !parse_whole(text.substr(0, slash), i) || !parse_whole(text.substr(slash + 1), n) ||
      n < 1 || n > 100000 || i < 0 || i >= n)
    throw Error(fmt::format("{} '{}' must be i/N with whole numbers 0 <= i < N <= 100000 (shard i of N computes the "
                            "cases k with k mod N = i), e.g. 0/4",
                            option, printable_excerpt(text)));
  return Shard{static_cast<std::size_t>(i), static_cast<std::size_t>(n)};
}

void run_cases_on_threads(const std::vector<std::size_t>& todo, int threads, const CaseWorkerFactory& make_worker,
                          const CaseSink& sink) {
  require(threads >= 1, "run_cases_on_threads: threads must be >= 1");
  const std::size_t used = std::min<std::size_t>(static_cast<std::size_t>(threads), std::max<std::size_t>(1, todo.size()));
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex lock;
  std::exception_ptr failure;
  const auto work = [&] {
    try {
      CaseWorker worker = make_worker();
      for (std::size_t i = next++; i < todo.size() && !stop; i = next++) {
        CaseResult r = worker(todo[i]);
        const std::lock_guard<std::mutex> guard(lock);
        sink(todo[i], std::move(r));
      }
    } catch (...) {
      const std::lock_guard<std::mutex> guard(lock);
      if (!failure) failure = std::current_exception();
      stop = true;
    }
  };
  if (used == 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(used);
    for (std::size_t t = 0; t < used; ++t) pool.emplace_back(work);
    for (std::thread& t : pool) t.join();
  }
  if (failure) std::rethrow_exception(failure);
}

ProgressLine::ProgressLine(std::ostream& log, std::string unit, std::size_t total)
    : log_(log), unit_(std::move(unit)), total_(total), start_(std::chrono::steady_clock::now()), last_(start_) {}

void ProgressLine::done(std::size_t completed) {
  const auto now = std::chrono::steady_clock::now();
  const bool due = completed >= next_report_ || completed == total_ || now - last_ > std::chrono::seconds(10);
  if (!due || total_ == 0) return;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double left = elapsed / static_cast<double>(completed) * static_cast<double>(total_ - completed);
  fmt::print(log_, "  [{:>3.0f} %] {}/{} {}, {:.0f} s, about {:.0f} s left\n",
             100.0 * static_cast<double>(completed) / static_cast<double>(total_), completed, total_, unit_, elapsed, left);
  log_.flush();
  next_report_ = completed + std::max<std::size_t>(1, total_ / 10);
  last_ = now;
}

}  // namespace railcontact::study
