// The command-line tool, run as a user would: JSON output, readable errors, exit codes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include <cmath>

#include "cli_run.hpp"

namespace {

using railcontact::test::CommandResult;
using railcontact::test::count_lines;
using railcontact::test::run_cli;
using railcontact::test::ScratchDirectory;

TEST(Cli, CoefficientsJsonIsOneObjectWithTheDocumentedKeys) {
  const CommandResult r = run_cli("coefficients --a-over-b 1 --nu 0.25 --elements 1500 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"a_over_b", "nu", "alpha", "solver", "elements_in_contact", "C11", "C22", "C23", "C33", "table",
                          "rel_error", "solve_time_s"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_NEAR(j["C11"].get<double>(), 4.12, 0.02 * 4.12);
  EXPECT_NEAR(j["C22"].get<double>(), 3.67, 0.02 * 3.67);
  EXPECT_NEAR(j["C23"].get<double>(), 1.47, 0.02 * 1.47);
  EXPECT_DOUBLE_EQ(j["table"]["C11"].get<double>(), 4.12);
  EXPECT_NEAR(j["rel_error"]["C11"].get<double>(), j["C11"].get<double>() / 4.12 - 1, 1e-12);
  EXPECT_GT(j["elements_in_contact"].get<int>(), 1300);
}

TEST(Cli, DenseSolverGivesTheSameCoefficients) {
  const auto krylov = nlohmann::json::parse(run_cli("coefficients --a-over-b 2 --nu 0.3 --elements 400 --json").out);
  const auto dense =
      nlohmann::json::parse(run_cli("coefficients --a-over-b 2 --nu 0.3 --elements 400 --solver dense --json").out);
  for (const char* key : {"C11", "C22", "C23", "C33"})
    EXPECT_NEAR(krylov[key].get<double>(), dense[key].get<double>(), 1e-6 * dense[key].get<double>()) << key;
}

class CliBadInput : public ::testing::TestWithParam<std::pair<const char*, const char*>> {};

TEST_P(CliBadInput, OneClearErrorLineAndNonZeroExit) {
  const auto [arguments, expected_word] = GetParam();
  const CommandResult r = run_cli(arguments);
  EXPECT_NE(r.exit_code, 0) << arguments;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(expected_word), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Coefficients, CliBadInput,
    ::testing::Values(std::pair{"coefficients --a-over-b 1 --nu 0.51", "--nu"},
                      std::pair{"coefficients --a-over-b 1 --nu -0.1", "--nu"},
                      std::pair{"coefficients --a-over-b 0 --nu 0.3", "--a-over-b"},
                      std::pair{"coefficients --a-over-b 1000 --nu 0.3", "--a-over-b"},
                      std::pair{"coefficients --a-over-b nan --nu 0.3", "a-over-b"},
                      std::pair{"coefficients --a-over-b 1 --nu 0.3 --elements 0", "--elements"},
                      std::pair{"coefficients --a-over-b 1 --nu 0.3 --elements 100000000", "--elements"},
                      std::pair{"coefficients --a-over-b 1 --nu 0.3 --alpha -1", "alpha"},
                      std::pair{"coefficients --a-over-b 1 --nu 0.3 --solver magic", "solver"},
                      std::pair{"coefficients --a-over-b 1 --nu 0.3 --bogus", "bogus"},
                      std::pair{"coefficients --nu 0.3", "a-over-b"},
                      std::pair{"frobnicate", "frobnicate"}));

}  // namespace

namespace {

TEST(CliRun, CaseFileJsonHasTheDocumentedShape) {
  const CommandResult r = run_cli(std::string("run ") + RAILCONTACT_SOURCE_DIR + "/examples/hertz_ellipse.toml --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("patch"));
  for (const char* solver : {"nh-fastsim", "fastsim", "exact", "exact-regularised"}) {
    ASSERT_TRUE(j["results"].contains(solver)) << solver;
    const auto& s = j["results"][solver];
    for (const char* key : {"F1", "F2", "M3", "time_s", "iterations"}) EXPECT_TRUE(s.contains(key)) << key;
    EXPECT_LT(s["F1"].get<double>(), 0.0);  // xi > 0: F1 < 0 (Kalker's convention)
  }
  EXPECT_EQ(j["results"]["nh-fastsim"]["flexibility"].size(), 3u);
  EXPECT_EQ(j["results"]["fastsim"]["flexibility"].size(), 3u);
  const double exact = j["results"]["exact"]["F1"].get<double>();
  EXPECT_NEAR(j["results"]["exact-regularised"]["F1"].get<double>(), exact, 1e-3 * std::fabs(exact));
  EXPECT_NEAR(j["results"]["nh-fastsim"]["F1"].get<double>(), exact, 0.05 * std::fabs(exact));
}

// The built-in default case (S1002/UIC60, ~2970 elements) coarsens automatically in 3 x 4 blocks
// (factor 3 along the rolling direction, one more across): the run names them.
TEST(CliRun, NamesTheAutomaticCoarseBlocks) {
  const ScratchDirectory dir("run_blocks");  // not the shared default railcontact-out/ (tests run in parallel)
  const CommandResult r = run_cli("run --json --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["results"]["nh-fastsim"]["flexibility_source"],
            "K2 of the patch coarsened in blocks of 3 elements along x1 by 4 across");
}

// --slip-direction reaches nh-fastsim (and only it): the JSON names it, and with the default case's
// partial slip with spin the flexibility-weighted traction moves nh-fastsim's forces, not fastsim's.
TEST(CliRun, SlipDirectionOption) {
  const ScratchDirectory dir("run_slip");  // not the shared default railcontact-out/ (tests run in parallel)
  const std::string out = " --out " + dir.string();
  const CommandResult radial = run_cli("run --json" + out);
  const CommandResult weighted = run_cli("run --json --slip-direction flexibility-weighted" + out);
  ASSERT_EQ(radial.exit_code, 0) << radial.err;
  ASSERT_EQ(weighted.exit_code, 0) << weighted.err;
  const nlohmann::json a = nlohmann::json::parse(radial.out)["results"];
  const nlohmann::json b = nlohmann::json::parse(weighted.out)["results"];
  EXPECT_EQ(a["nh-fastsim"]["slip_direction"], "radial");
  EXPECT_EQ(b["nh-fastsim"]["slip_direction"], "flexibility-weighted");
  EXPECT_NE(a["nh-fastsim"]["F1"].get<double>(), b["nh-fastsim"]["F1"].get<double>());
  EXPECT_EQ(a["fastsim"]["F1"].get<double>(), b["fastsim"]["F1"].get<double>());
  EXPECT_EQ(a["exact"]["F1"].get<double>(), b["exact"]["F1"].get<double>());
  // The report: the nh-fastsim flexibilities' line names a non-default slip direction, and only there.
  for (const bool weighted_run : {false, true}) {
    const CommandResult text = run_cli((weighted_run ? "run --slip-direction flexibility-weighted" : "run") + out);
    ASSERT_EQ(text.exit_code, 0) << text.err;
    const std::size_t at = text.out.find("nh-fastsim flexibilities:");
    ASSERT_NE(at, std::string::npos) << text.out;
    const std::string line = text.out.substr(at, text.out.find('\n', at) - at);
    EXPECT_EQ(line.find("Kalker"), std::string::npos) << line;
    EXPECT_EQ(line.find("; slip direction flexibility-weighted") != std::string::npos, weighted_run) << line;
  }
}

INSTANTIATE_TEST_SUITE_P(Run, CliBadInput,
                         ::testing::Values(std::pair{"run /nonexistent/case.toml", "cannot read"},
                                           std::pair{"run --slip-direction sideways",
                                                     "--slip-direction: unknown slip direction 'sideways' (radial, "
                                                     "flexibility-weighted, rigid-slip, elastic-slip)"},
                                           std::pair{"run --slip-direction ''",
                                                     "--slip-direction: unknown slip direction ''"},
                                           std::pair{"run " RAILCONTACT_SOURCE_DIR "/tests/data/unknown_key.toml",
                                                     "unknown key 'mue'"},
                                           std::pair{"run " RAILCONTACT_SOURCE_DIR "/tests/data/bad_solver.toml",
                                                     "unknown solver"}));

}  // namespace
