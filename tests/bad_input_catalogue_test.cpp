// The bad-input catalogue (docs/RELIABILITY.md): every row of tests/data/bad_input_catalogue.tsv
// runs the railcontact command with a bad input and checks the exit code of the error's kind, one
// error line naming the input, and no output.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.hpp"

namespace railcontact {
namespace {

struct CatalogueRow {
  int line = 0;
  int exit_code = 0;
  std::string expected, arguments;
};

std::vector<CatalogueRow> catalogue() {
  std::ifstream file(std::string(RAILCONTACT_SOURCE_DIR) + "/tests/data/bad_input_catalogue.tsv");
  std::vector<CatalogueRow> rows;
  std::string text;
  for (int line = 1; std::getline(file, text); ++line) {
    if (text.empty() || text[0] == '#') continue;
    const std::size_t first = text.find('\t'), second = text.find('\t', first + 1);
    if (first == std::string::npos || second == std::string::npos) {
      ADD_FAILURE() << "catalogue line " << line << " has not three tab-separated columns: " << text;
      continue;
    }
    CatalogueRow row{line, std::stoi(text.substr(0, first)), text.substr(first + 1, second - first - 1),
                     text.substr(second + 1)};
    // {DATA}: the shipped data; {TESTDATA}: tests/data, whose bad_inputs/ holds the bad files.
    const std::pair<std::string, std::string> placeholders[] = {
        {"{DATA}", RAILCONTACT_DATA_DIR}, {"{TESTDATA}", std::string(RAILCONTACT_SOURCE_DIR) + "/tests/data"}};
    for (const auto& [name, value] : placeholders)
      for (std::size_t at; (at = row.arguments.find(name)) != std::string::npos;) row.arguments.replace(at, name.size(), value);
    rows.push_back(row);
  }
  return rows;
}

TEST(BadInputCatalogue, EveryRowGivesOneClearErrorAndItsExitCode) {
  const std::vector<CatalogueRow> rows = catalogue();
  ASSERT_GE(rows.size(), 20u);
  for (const CatalogueRow& row : rows) {
    SCOPED_TRACE("catalogue line " + std::to_string(row.line) + ": railcontact " + row.arguments);
    const test::CommandResult r = test::run_cli(row.arguments, "exec timeout 120 ");
    EXPECT_EQ(r.exit_code, row.exit_code) << r.err;
    test::expect_one_error_line(r, row.expected);
  }
}

}  // namespace
}  // namespace railcontact
