#pragma once
// Cases spread over MPI ranks (docs/SCALING.md): built with MPI (RAILCONTACT_MPI) and started by
// mpirun with several ranks, rank 0 hands out case indices one at a time to the ranks that ask
// (dynamic load balancing: a rank that finished a case sends its result and gets the next index),
// computes cases itself on `threads` threads meanwhile, and receives every result; the caller on
// rank 0 files them by index and writes the one output. The other ranks only compute.
//
// Without MPI in the build, or when not started by mpirun (or with one rank), the world has one
// rank and everything runs as before. All MPI calls of railcontact are in mpi_cases.cpp.
#include <cstddef>
#include <vector>

#include "railcontact/flexibility_table.hpp"
#include "study/case_pool.hpp"

namespace railcontact::study {

class MpiWorld {
 public:
  // Initialises MPI when built with it and started by mpirun (the environment of OpenMPI, PMI or
  // PMIx names a world size); finalises it in the destructor. One per process (main()).
  MpiWorld(int& argc, char**& argv);
  ~MpiWorld();
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  // The world of this process (a single rank when there is no MpiWorld).
  static int rank();
  static int size();
  static bool several() { return size() > 1; }
  // Ends every rank with this exit code (MPI_Abort) when there are several; returns otherwise.
  static void abort_all(int exit_code);
  // Whether this build has MPI.
  static bool built_with_mpi();
  // A build without MPI started by mpirun with several ranks: their number (else 0).
  static int ranks_without_mpi();
};

// With several ranks: rank 0 hands out `todo` (its own list; the other ranks' is not used),
// computes on `threads` threads too and calls `sink` with every result (under a lock); the other
// ranks compute what they are given until rank 0 says stop. With one rank:
// run_cases_on_threads(todo, threads, make_worker, sink).
void run_cases_on_ranks(const std::vector<std::size_t>& todo, int threads, const CaseWorkerFactory& make_worker,
                        const CaseSink& sink);

// Thrown on an MPI rank other than 0 when its share of a table build is done: the build on that
// rank holds no table; the command returns 0 there (rank 0 writes the table).
struct WorkerRankDone {};

// A table build's node runner (TableNodeRunner, railcontact/flexibility_table.hpp): the nodes on
// `threads` threads and, under mpirun with several ranks, over the ranks (run_cases_on_ranks).
TableNodeRunner table_node_runner(int threads);

}  // namespace railcontact::study
