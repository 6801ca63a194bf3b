// Fuzz target: `railcontact merge` (app/cli/sweep_command.cpp, docs/SCALING.md "Shards and merge")
// past the journal reader: the input is split at form feeds ('\f') into up to three journals,
// read (parse_sweep_journal), checked together (combine_shard_journals: the same sweep or build,
// each shard once and complete, every case in its shard), told apart by their metadata
// (journal_command), then turned into what merge writes: a sweep's sweep.csv and sweep.json in
// memory (sweep_json, write_sweep_csv), or a table's recipe read back (table_shard_recipe) and the table built
// from the shards' nodes on the shipped profiles (merged_node_runner, build_flexibility_table:
// every node's text parsed). A combined set must hold every case of the sweep exactly once.
#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_target.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/wheel_rail.hpp"
#include "study/sweep_journal.hpp"
#include "study/sweep_run.hpp"

namespace {

using namespace railcontact;

void merge(std::string_view input) {
  std::vector<study::NamedSweepJournal> journals;
  std::size_t start = 0;
  while (journals.size() < 3) {
    const std::size_t end = journals.size() == 2 ? std::string_view::npos : input.find('\f', start);
    const std::string name = "shard" + std::to_string(journals.size()) + ".journal";
    journals.push_back(
        {name, study::parse_sweep_journal(std::string(input.substr(start, end == std::string_view::npos ? end : end - start)),
                                          name, "fuzz")});
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  study::SweepJournalHeader header;
  const std::map<std::size_t, study::CaseResult> done = study::combine_shard_journals(journals, header);
  if (done.size() != header.cases || (!done.empty() && done.rbegin()->first >= header.cases)) std::abort();
  if (study::journal_command(header, journals.front().file) == study::JournalCommand::sweep) {
    const std::string json = study::sweep_json(header.metadata, done);
    std::ostringstream csv;
    study::write_sweep_csv(csv, header.header, done);
    if (json.empty() || csv.str().compare(0, header.header.size(), header.header) != 0) std::abort();
    return;
  }
  const study::TableShardRecipe recipe = study::table_shard_recipe(header, journals.front().file);
  static const WheelRailPair pair = default_wheel_rail_pair();
  std::vector<double> loads = recipe.loads_N;
  std::sort(loads.begin(), loads.end());
  FlexibilityTableOptions options;
  options.patch.target_elements = recipe.elements;
  options.nh_fastsim.flexibility_coarsening = recipe.flexibility_coarsening;
  options.created_utc = recipe.created_utc;
  options.runner = study::merged_node_runner(done);
  const FlexibilityTable table = build_flexibility_table(
      pair, flexibility_table_y_grid(recipe.y_from_m, recipe.y_to_m, recipe.y_step_m), loads, options);
  if (table.nodes().size() != done.size()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  railcontact::fuzz::expect_clean_outcome([&] { merge(railcontact::fuzz::as_text(data, size)); });
  return 0;
}
