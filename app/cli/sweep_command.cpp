// `railcontact sweep FILE.toml` and `railcontact merge`: a sweep of wheelset states on threads, MPI
// ranks or shards, resumable (docs/CASE_FILES.md "Sweep files", docs/SCALING.md).
#include <fmt/core.h>
#include <fmt/ostream.h>

#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "case/sweep_file.hpp"
#include "cli/commands.hpp"
#include "cli/flextable_shards.hpp"
#include "railcontact/error.hpp"
#include "study/case_pool.hpp"
#include "study/mpi_cases.hpp"
#include "study/sweep_journal.hpp"
#include "study/sweep_run.hpp"

namespace railcontact::cli {
namespace {

struct SweepArguments {
  std::string file;
  std::string out = "railcontact-out/sweep";
  std::string threads;
  std::string shard;
  bool restart = false;
};

struct MergeArguments {
  std::vector<std::string> shards;
  std::string out;
};

// The exit status of a finished sweep: 0, or the first failed case's kind (the outputs are written).
int report(const study::SweepSummary& s) {
  if (s.failed == 0) return 0;
  fmt::print(std::cerr, "railcontact: error: {} of {} cases failed (rows with status failed in the output); the first, "
             "case {}: {}\n",
             s.failed, s.in_run, s.first_failed_case, s.first_failed_message);
  return exit_code(s.first_failed_kind);
}

int run_sweep_command(const SweepArguments& a) {
  const SweepFile sweep = read_sweep_file(a.file);
  study::SweepRunOptions options;
  options.out = a.out;
  options.restart = a.restart;
  // Default: every core; under mpirun one thread per rank (start one rank per core).
  options.threads = a.threads.empty() ? (study::MpiWorld::several() ? 1 : study::available_cores())
                                      : study::parse_threads(a.threads);
  if (!a.shard.empty()) options.shard = study::parse_shard(a.shard);
  if (study::MpiWorld::rank() == 0)
    fmt::print(std::cerr, "sweep {}: {} cases{} on {} thread(s){}\n", a.file, sweep.size(),
               options.shard.whole() ? "" : fmt::format(", shard {}/{}", options.shard.index, options.shard.count),
               options.threads,
               study::MpiWorld::several() ? fmt::format(" and {} MPI ranks", study::MpiWorld::size()) : "");
  const study::SweepSummary s = study::run_sweep(sweep, options, std::cerr);
  if (s.worker_rank) return 0;
  fmt::print("Wrote {} ({} cases of {}: {} computed, {} from an earlier run, {} failed)\n", s.written.string(), s.in_run,
             s.cases, s.computed, s.resumed, s.failed);
  return report(s);
}

int run_merge_command(const MergeArguments& a) {
  const std::vector<std::filesystem::path> paths(a.shards.begin(), a.shards.end());
  const std::vector<study::NamedSweepJournal> journals = study::read_shard_journals(paths);
  study::SweepJournalHeader header;
  const std::map<std::size_t, study::CaseResult> done = study::combine_shard_journals(journals, header);
  // A flexibility table's shards (flextable build --shard) or a sweep's.
  if (study::journal_command(header, journals.front().file) == study::JournalCommand::flextable_build)
    return merge_flextable_shards(header, journals.front().file, done, a.out);
  const study::SweepSummary s = study::merge_sweep_journals(header, done, a.out, std::cerr);
  fmt::print("Wrote {} ({} cases from {} shard file(s), {} failed)\n", s.written.string(), s.cases, journals.size(),
             s.failed);
  return report(s);
}

}  // namespace

void add_sweep_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<SweepArguments>();
  CLI::App* sub = app.add_subcommand(
      "sweep", "A sweep of wheelset states from a TOML file (a grid or a list of cases): one CSV, JSON metadata and "
               "figures in --out; resumable; on threads, MPI ranks (mpirun) or shards (docs/CASE_FILES.md, "
               "docs/SCALING.md)");
  sub->add_option("file", args->file, "sweep file (TOML: wheelset-case sections plus [grid] or [[case]])")->required();
  sub->add_option("--out", args->out, "output directory (sweep.csv, sweep.json, figures)")->capture_default_str();
  sub->add_option("--threads", args->threads, "threads (a whole number >= 1; default: all cores, 1 per MPI rank)");
  sub->add_option("--shard", args->shard,
                  "compute shard i of N only (cases k with k mod N = i), written as a journal for `railcontact merge`");
  sub->add_flag("--restart", args->restart, "discard the completed cases of an earlier run in --out");
  sub->callback([&action, args] { action = [args] { return run_sweep_command(*args); }; });

  auto merge = std::make_shared<MergeArguments>();
  CLI::App* m = app.add_subcommand(
      "merge", "Combine the shard journals of `railcontact sweep --shard i/N` (into --out DIR: sweep.csv, sweep.json, "
               "figures) or of `railcontact flextable build --shard i/N` (into the table file --out): the same bytes as "
               "the run on one machine");
  m->add_option("shards", merge->shards, "the shards' journal files or their --out directories")->required();
  m->add_option("--out", merge->out, "output directory of a sweep, or the table file of a flexibility table")->required();
  m->callback([&action, merge] { action = [merge] { return run_merge_command(*merge); }; });
}

}  // namespace railcontact::cli
