#pragma once
// The journal of a sweep (docs/SCALING.md, docs/CASE_FILES.md "Sweep files"): the completed cases
// of a sweep, appended and flushed one case at a time, so that an interrupted sweep (Ctrl-C, kill,
// a lost node) keeps them and a rerun computes the others only. It is also the output of a shard
// (--shard i/N), which `railcontact merge` combines.
//
// Text with length-prefixed blocks:
//   railcontact sweep journal 1
//   version <railcontact version>
//   recipe <fnv1a64 of the metadata block>
//   cases <number of cases of the whole sweep>
//   shard <i>/<N>
//   metadata <bytes>\n<the metadata JSON>\n
//   header <bytes>\n<the CSV header line(s)>\n
//   case <k> <ok|failed> <bytes> <fnv1a64 of the bytes>\n<the case's CSV rows>\n   (repeated)
// A record cut short by an interruption (or with a wrong hash) ends the journal: it and whatever
// follows are dropped when the journal is read for a rerun.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "railcontact/flexibility_table.hpp"
#include "study/case_pool.hpp"

namespace railcontact::study {

// FNV-1a 64 of the bytes as 16 lower-case hexadecimal digits (the hash of the library's file
// fingerprints).
std::string hash_hex(std::string_view bytes);

struct SweepJournalHeader {
  std::string version;
  std::string recipe;  // 16 hex digits
  std::size_t cases = 0;
  Shard shard;
  std::string metadata;  // JSON
  std::string header;    // CSV header
};

struct SweepJournal {
  SweepJournalHeader header;
  std::map<std::size_t, CaseResult> done;  // by case index
  std::uintmax_t valid_bytes = 0;          // up to the last complete record
  bool dropped_tail = false;               // an incomplete record at the end was ignored
};

// At most this many bytes of a journal are read (the file is read whole, as a regular file, by
// read_text_file): about 4 KiB for each of a sweep's 1e6 cases (measured: 615 bytes a case with
// two solvers and one patch per wheel, 350 bytes per patch row with all four solvers), 2 KiB for
// each of a flexibility table's 2e6 nodes (measured: 479 bytes a node).
inline constexpr std::uintmax_t kMaximumJournalBytes = std::uintmax_t{4} << 30;  // 4 GiB

// Reads a journal (a regular file of at most kMaximumJournalBytes, refused at once otherwise).
// Throws Error naming the file: io when it cannot be read, invalid_input when its header is not a
// journal's, with what was found and `advice` (what the reader expects or what to do; a record cut
// short is not an error: see above). The header's recipe must be the hash of its metadata.
SweepJournal read_sweep_journal(const std::filesystem::path& path, std::string_view advice);
// The same from the journal's text (`path` names it in messages).
SweepJournal parse_sweep_journal(const std::string& text, const std::filesystem::path& path, std::string_view advice);

// The advice of a journal found in an output directory when a run resumes.
inline constexpr std::string_view kResumeAdvice = "remove it, or rerun with --restart";

// Appends records to a journal, creating it with the header when it does not exist (or cutting it
// to valid_bytes when it does). Each record is written with one write and flushed.
class SweepJournalWriter {
 public:
  SweepJournalWriter(const std::filesystem::path& path, const SweepJournalHeader& header, bool exists,
                     std::uintmax_t valid_bytes);
  ~SweepJournalWriter();
  SweepJournalWriter(const SweepJournalWriter&) = delete;
  SweepJournalWriter& operator=(const SweepJournalWriter&) = delete;
  void append(std::size_t k, const CaseResult& result);  // throws Error(io) when the write fails
  void close();

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
};

// The journal files of `paths` (files, or directories searched for *shard-<i>-of-<N>.journal),
// sorted. Throws Error naming a path that does not exist or a directory without a journal.
std::vector<std::filesystem::path> shard_journal_files(const std::vector<std::filesystem::path>& paths);

struct NamedSweepJournal {
  std::filesystem::path file;
  SweepJournal journal;
};

// The journals of `paths` for `railcontact merge` (shard_journal_files, read_sweep_journal with
// what merge expects as the advice).
std::vector<NamedSweepJournal> read_shard_journals(const std::vector<std::filesystem::path>& paths);

// What wrote a journal: the command its metadata names.
enum class JournalCommand { sweep, flextable_build };
// Throws Error (invalid_input) naming the file unless the metadata is a JSON object whose command
// is "sweep" or "flextable build".
JournalCommand journal_command(const SweepJournalHeader& header, const std::filesystem::path& file);

// The cases of the shards 0 .. N-1 of one sweep or table build, by index, and their common header.
// Throws Error (invalid_input) naming the files unless they belong together (version, recipe,
// cases, N), each shard is given once and is complete, and no case lies outside its shard.
std::map<std::size_t, CaseResult> combine_shard_journals(const std::vector<NamedSweepJournal>& journals,
                                                         SweepJournalHeader& header);

// The arguments of `railcontact flextable build --shard i/N` recorded in its journals' metadata,
// and the profiles' hashes: merge builds the table's grid from them again.
struct TableShardRecipe {
  double y_from_m = 0.0, y_to_m = 0.0, y_step_m = 0.0;
  std::vector<double> loads_N;
  std::optional<std::string> wheel, rail;  // as given (none: the shipped profiles)
  int elements = 0;
  int flexibility_coarsening = 0;
  std::string wheel_profile_fnv1a64, rail_profile_fnv1a64;
  std::string created_utc;
};
// The metadata JSON of a table shard's journal (its recipe is the hash of it).
std::string table_shard_metadata(const TableShardRecipe& recipe);
// Reads it back. Throws Error (invalid_input) naming the file and the key when the metadata does
// not hold every argument with its type (a damaged journal).
TableShardRecipe table_shard_recipe(const SweepJournalHeader& header, const std::filesystem::path& file);

// The runner of a table build (railcontact/flexibility_table.hpp) that stores the nodes of its
// shards' journals instead of solving them. Throws Error (invalid_input) when their number is not
// the build's.
TableNodeRunner merged_node_runner(const std::map<std::size_t, CaseResult>& nodes);

}  // namespace railcontact::study
