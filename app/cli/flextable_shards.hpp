#pragma once
// `railcontact merge` of the shards of `railcontact flextable build --shard i/N` (docs/SCALING.md):
// the build again from the arguments recorded in the shards' journals, its nodes taken from them;
// the table file is the bytes of the build on one machine (with the same created_utc).
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

#include "study/case_pool.hpp"
#include "study/sweep_journal.hpp"

namespace railcontact::cli {

// The shards' header and nodes as combine_shard_journals gives them (`journal`: one of their
// files, named in messages). Throws Error when the metadata is damaged or the profiles here are not
// those of the shards.
int merge_flextable_shards(const study::SweepJournalHeader& header, const std::filesystem::path& journal,
                           const std::map<std::size_t, study::CaseResult>& nodes, const std::string& out);

}  // namespace railcontact::cli
