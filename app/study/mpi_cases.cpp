// Cases spread over MPI ranks (see the header). The only file of railcontact that calls MPI.
#include "study/mpi_cases.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <cstring>
#include <exception>
#include <mutex>
#include <thread>

#include "railcontact/error.hpp"

#ifdef RAILCONTACT_HAVE_MPI
// The C interface only (MPI::C): OpenMPI's mpi.h would pull in its deprecated C++ bindings.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace railcontact::study {
namespace {
int g_rank = 0;
int g_size = 1;
bool g_initialised = false;
int g_unsupported_ranks = 0;  // a build without MPI started by mpirun with this many ranks

#ifdef RAILCONTACT_HAVE_MPI
bool started_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

// Messages of one call of run_cases_on_ranks (a round): every rank makes the same calls in the same
// order, and each round has its own pair of tags, so that a rank that is done with a round and
// already asks for work of the next (a study with several tables) is not answered by the round
// rank 0 is still finishing.
int g_round = 0;
int tag_result() { return 10 + 2 * (g_round % 10000); }  // worker -> rank 0: [int64 case or -1 (ready)][uint8 failed][text]
int tag_work() { return 11 + 2 * (g_round % 10000); }    // rank 0 -> worker: int64 case, or -1: stop

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw Error(ErrorKind::internal, std::string("MPI: ") + what + " failed");
}

void worker_loop(const CaseWorkerFactory& make_worker) {
  CaseWorker worker = make_worker();
  std::vector<char> message(9, 0);
  const std::int64_t ready = -1;
  std::memcpy(message.data(), &ready, 8);
  for (;;) {
    check(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, tag_result(), MPI_COMM_WORLD), "send");
    std::int64_t k = -1;
    check(MPI_Recv(&k, 1, MPI_INT64_T, 0, tag_work(), MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
    if (k < 0) return;
    const CaseResult r = worker(static_cast<std::size_t>(k));
    message.assign(9 + r.text.size(), 0);
    std::memcpy(message.data(), &k, 8);
    message[8] = r.failed ? 1 : 0;
    std::memcpy(message.data() + 9, r.text.data(), r.text.size());
  }
}

void dispatch(const std::vector<std::size_t>& todo, int threads, const CaseWorkerFactory& make_worker,
              const CaseSink& sink) {
  std::mutex lock;  // guards next, sink and failure
  std::size_t next = 0;
  std::exception_ptr failure;
  const auto take = [&]() -> std::int64_t {
    const std::lock_guard<std::mutex> guard(lock);
    if (failure || next >= todo.size()) return -1;
    return static_cast<std::int64_t>(todo[next++]);
  };
  // Rank 0's own compute threads take cases from the same list.
  std::vector<std::thread> local;
  for (int t = 0; t < threads; ++t) {
    local.emplace_back([&] {
      try {
        CaseWorker worker = make_worker();
        for (std::int64_t k = take(); k >= 0; k = take()) {
          CaseResult r = worker(static_cast<std::size_t>(k));
          const std::lock_guard<std::mutex> guard(lock);
          sink(static_cast<std::size_t>(k), std::move(r));
        }
      } catch (...) {
        const std::lock_guard<std::mutex> guard(lock);
        if (!failure) failure = std::current_exception();
      }
    });
  }
  // The other ranks: each asks (with its last result), gets the next case or stop. Polled with
  // short sleeps so that the dispatcher does not take a core from rank 0's compute threads.
  int running = g_size - 1;
  std::vector<char> message;
  try {
    while (running > 0) {
      int arrived = 0;
      MPI_Status status;
      check(MPI_Iprobe(MPI_ANY_SOURCE, tag_result(), MPI_COMM_WORLD, &arrived, &status), "probe");
      if (!arrived) {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        continue;
      }
      int bytes = 0;
      check(MPI_Get_count(&status, MPI_BYTE, &bytes), "count");
      message.resize(static_cast<std::size_t>(bytes));
      check(MPI_Recv(message.data(), bytes, MPI_BYTE, status.MPI_SOURCE, tag_result(), MPI_COMM_WORLD, MPI_STATUS_IGNORE),
            "receive");
      std::int64_t k = -1;
      std::memcpy(&k, message.data(), 8);
      if (k >= 0) {
        CaseResult r{std::string(message.data() + 9, message.size() - 9), message[8] != 0};
        const std::lock_guard<std::mutex> guard(lock);
        sink(static_cast<std::size_t>(k), std::move(r));
      }
      const std::int64_t work = take();
      check(MPI_Send(&work, 1, MPI_INT64_T, status.MPI_SOURCE, tag_work(), MPI_COMM_WORLD), "send");
      if (work < 0) --running;
    }
  } catch (...) {
    // The sink (e.g. a full disk) or MPI failed: rank 0's threads stop after their case, then the
    // error goes up (and main() ends the other ranks with MPI_Abort).
    {
      const std::lock_guard<std::mutex> guard(lock);
      if (!failure) failure = std::current_exception();
    }
    for (std::thread& t : local) t.join();
    throw;
  }
  for (std::thread& t : local) t.join();
  if (failure) std::rethrow_exception(failure);
}
#endif
}  // namespace

MpiWorld::MpiWorld(int& argc, char**& argv) {
#ifdef RAILCONTACT_HAVE_MPI
  if (!started_by_mpirun()) return;
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) return;
  g_initialised = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
#else
  (void)argc;
  (void)argv;
  // Started by mpirun with several ranks, a build without MPI would run the whole job on every
  // rank (and all but one would find the output directory locked): main() refuses instead.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* value = std::getenv(name)) g_unsupported_ranks = std::max(g_unsupported_ranks, std::atoi(value));
#endif
}

MpiWorld::~MpiWorld() {
#ifdef RAILCONTACT_HAVE_MPI
  if (g_initialised) MPI_Finalize();
#endif
  g_initialised = false;
  g_rank = 0;
  g_size = 1;
}

int MpiWorld::ranks_without_mpi() { return g_unsupported_ranks > 1 ? g_unsupported_ranks : 0; }

int MpiWorld::rank() { return g_rank; }
int MpiWorld::size() { return g_size; }

void MpiWorld::abort_all(int exit_code) {
#ifdef RAILCONTACT_HAVE_MPI
  if (g_initialised && g_size > 1) MPI_Abort(MPI_COMM_WORLD, exit_code);
#else
  (void)exit_code;
#endif
}

bool MpiWorld::built_with_mpi() {
#ifdef RAILCONTACT_HAVE_MPI
  return true;
#else
  return false;
#endif
}

void run_cases_on_ranks(const std::vector<std::size_t>& todo, int threads, const CaseWorkerFactory& make_worker,
                        const CaseSink& sink) {
#ifdef RAILCONTACT_HAVE_MPI
  if (g_size > 1) {
    ++g_round;
    if (g_rank == 0) dispatch(todo, threads, make_worker, sink);
    else worker_loop(make_worker);
    return;
  }
#endif
  run_cases_on_threads(todo, threads, make_worker, sink);
}

TableNodeRunner table_node_runner(int threads) {
  return [threads](std::size_t count, const TableNodeSolver& solve, const TableNodeStore& store) {
    std::vector<std::size_t> todo(count);
    for (std::size_t k = 0; k < count; ++k) todo[k] = k;
    const CaseWorkerFactory factory = [&solve]() -> CaseWorker {
      return [&solve](std::size_t k) { return CaseResult{solve(k), false}; };
    };
    run_cases_on_ranks(todo, threads, factory, [&store](std::size_t k, CaseResult&& r) { store(k, r.text); });
    if (g_rank != 0) throw WorkerRankDone{};
  };
}

}  // namespace railcontact::study
