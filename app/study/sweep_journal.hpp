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
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

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

// Reads a journal. Throws Error (invalid_input) naming the file when its header is not a sweep
// journal's (a record cut short is not an error: see above).
SweepJournal read_sweep_journal(const std::filesystem::path& path);
// The same from the journal's text (`path` names it in messages).
SweepJournal parse_sweep_journal(const std::string& text, const std::filesystem::path& path);

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

// The cases of the shards 0 .. N-1 of one sweep or table build, by index, and their common header.
// Throws Error (invalid_input) naming the files unless they belong together (version, recipe,
// cases, N), each shard is given once and is complete, and no case lies outside its shard.
std::map<std::size_t, CaseResult> combine_shard_journals(const std::vector<std::filesystem::path>& paths,
                                                         SweepJournalHeader& header);

}  // namespace railcontact::study
