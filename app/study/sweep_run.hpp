#pragma once
// `railcontact sweep FILE.toml` and `railcontact merge` (docs/CASE_FILES.md "Sweep files",
// docs/SCALING.md): the cases of a sweep file computed on threads, MPI ranks or shards, written to
// --out DIR as
//   sweep.csv   one row per case and contact patch (both wheels, gauge-side patch first), the
//               case's inputs, the patch, every solver's forces and the wheel's forces; a case that
//               failed (e.g. the flange climbing over the rail): one row with status "failed",
//               its error kind and message;
//   sweep.json  the metadata: railcontact_version, the sweep file (name, hash, text), the profiles'
//               fingerprints, the recipe, the axes, the columns, the counts;
//   sweep_*.png the figures of scripts/plot_sweep.py;
// the same bytes whatever the threads, ranks or shards. While it runs, the completed cases are
// kept in DIR/sweep.journal (study/sweep_journal.hpp): a rerun with the same file resumes.
#include <cstddef>
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "case/sweep_file.hpp"
#include "railcontact/error.hpp"
#include "study/case_pool.hpp"
#include "study/sweep_journal.hpp"

namespace railcontact::study {

struct SweepRunOptions {
  std::filesystem::path out = "railcontact-out/sweep";
  int threads = 1;
  Shard shard;           // a shard writes its journal only: DIR/sweep-shard-<i>-of-<N>.journal
  bool restart = false;  // discard the completed cases of an earlier run in DIR
};

struct SweepSummary {
  std::size_t cases = 0;     // of the whole sweep
  std::size_t in_run = 0;    // of this run (its shard)
  std::size_t resumed = 0;   // taken from the journal of an earlier run
  std::size_t computed = 0;  // computed now
  std::size_t failed = 0;    // of this run's cases
  std::size_t first_failed_case = 0;
  ErrorKind first_failed_kind = ErrorKind::invalid_input;
  std::string first_failed_message;
  bool worker_rank = false;  // an MPI rank other than 0: computed only, wrote nothing
  std::filesystem::path written;  // sweep.csv, or the shard's journal
};

// Runs the sweep (see the top). Throws Error for a bad output directory, a journal of another
// sweep in DIR (unless restart), or an I/O failure; failed cases are reported in the summary.
SweepSummary run_sweep(const SweepFile& sweep, const SweepRunOptions& options, std::ostream& log);

// sweep.json's text: the sweep's metadata (JSON, from its recipe or a journal) with the number of
// failed cases of `done`. Throws Error (invalid_input) when the metadata is not a JSON object (a
// damaged journal).
std::string sweep_json(const std::string& metadata, const std::map<std::size_t, CaseResult>& done);
// sweep.csv: the header, then each case's rows in the order of the cases.
void write_sweep_csv(std::ostream& out, const std::string& header, const std::map<std::size_t, CaseResult>& done);

// Writes the cases of shards 0 .. N-1 of one sweep, combined by combine_shard_journals (which
// checks that they belong together), into DIR's sweep.csv, sweep.json and figures,
// byte-identical to the serial run.
SweepSummary merge_sweep_journals(const SweepJournalHeader& header, const std::map<std::size_t, CaseResult>& done,
                                  const std::filesystem::path& out, std::ostream& log);

// The sweep's workers (one per thread; run_cases_on_threads): case k's CSV rows, or its failed row.
// The sweep and the track must outlive the workers. For bench/sweep_bench.cpp.
CaseWorkerFactory sweep_worker_factory(const SweepFile& sweep, const WheelsetTrack& track);

// The journal name of a shard: "sweep-shard-<i>-of-<N>.journal" ("sweep.journal" for the whole).
std::string sweep_journal_name(const Shard& shard);

}  // namespace railcontact::study
