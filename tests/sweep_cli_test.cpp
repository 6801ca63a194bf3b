// `railcontact sweep` and `railcontact merge` (docs/CASE_FILES.md "Sweep files", docs/SCALING.md):
// the same bytes on one thread, two threads and from merged shards; an interrupted sweep resumes;
// a changed file is refused; failed cases are rows with their error and a non-zero exit; the
// numbers themselves are those of the wheelset.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"

namespace {

using railcontact::test::CommandResult;
using railcontact::test::run_cli;
using railcontact::test::ScratchDirectory;

const std::string kNoFigures = "RAILCONTACT_SCRIPTS=/nonexistent-railcontact-scripts ";

// 2 yaws × 5 y on a coarse mesh (about 0.05 s a case), two solvers.
const char* kSweep =
    "[mesh]\nelement_size_mm = 1.0\n[solvers]\nrun = [\"nh-fastsim\", \"fastsim\"]\n"
    "[grid]\nyaw_mrad = [0, 2]\ny_mm = { from = -2, to = 2, step = 1 }\n";

std::string read(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// The CSV's rows as fields (no quoted commas in ok rows).
std::vector<std::vector<std::string>> rows_of(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::istringstream l(line);
    for (std::string f; std::getline(l, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

std::string fmt_shard(const std::string& file, int i, const ScratchDirectory& dir) {
  return "sweep " + file + " --threads 1 --shard " + std::to_string(i) + "/3 --out " + (dir / ("s" + std::to_string(i))).string();
}

TEST(SweepCli, TwoThreadsWriteTheBytesOfOneAndTheNumbersOfTheWheelset) {
  const ScratchDirectory dir("sweep_threads");
  write(dir / "s.toml", kSweep);
  const CommandResult one = run_cli("sweep " + (dir / "s.toml").string() + " --threads 1 --out " + (dir / "one").string(), kNoFigures);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.err.find("about"), std::string::npos) << "progress with the time left: " << one.err;
  const CommandResult two = run_cli("sweep " + (dir / "s.toml").string() + " --threads 2 --out " + (dir / "two").string(), kNoFigures);
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const std::string csv = read(dir / "one" / "sweep.csv");
  EXPECT_EQ(csv, read(dir / "two" / "sweep.csv"));
  EXPECT_EQ(read(dir / "one" / "sweep.json"), read(dir / "two" / "sweep.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "one" / "sweep.journal"));  // removed when complete

  const auto rows = rows_of(csv);
  ASSERT_EQ(rows.size(), 1u + 2 * 10);  // one patch per wheel on the tread at |y| <= 2 mm
  const auto& h = rows[0];
  // Case 2 is yaw 0, y = 0: symmetric, each wheel carrying its 98.1 kN.
  int checked = 0;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    EXPECT_EQ(rows[r][column(h, "status")], "ok");
    if (rows[r][column(h, "case")] != "2") continue;
    EXPECT_EQ(rows[r][column(h, "y_mm")], "0");
    EXPECT_NEAR(std::stod(rows[r][column(h, "wheel_Fz_N")]), 98100.0, 5.0);
    EXPECT_NEAR(std::abs(std::stod(rows[r][column(h, "wheel_Fy_N")])), 590.0, 150.0);  // the conicity's lateral force
    ++checked;
  }
  EXPECT_EQ(checked, 2);
  // The same state on its own (railcontact wheelset) gives the sweep's numbers.
  const CommandResult single = run_cli("wheelset --y-m 0.001 --yaw-rad 0.002 --element-size-m 0.001 --solver nh-fastsim --solver fastsim --json");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const nlohmann::json j = nlohmann::json::parse(single.out);
  for (std::size_t r = 1; r < rows.size(); ++r) {
    if (rows[r][column(h, "case")] != "8" || rows[r][column(h, "side")] != "right") continue;
    EXPECT_NEAR(std::stod(rows[r][column(h, "wheel_Fy_N")]), j["wheels"][0]["force_track_N"][1].get<double>(), 0.01);
    EXPECT_NEAR(std::stod(rows[r][column(h, "nh-fastsim_F1_N")]),
                j["wheels"][0]["patches"][0]["nh-fastsim"]["F1_N"].get<double>(), 0.01);
    ++checked;
  }
  EXPECT_EQ(checked, 3);
  const nlohmann::json meta = nlohmann::json::parse(read(dir / "one" / "sweep.json"));
  EXPECT_EQ(meta["cases"], 10);
  EXPECT_EQ(meta["failed_cases"], 0);
  EXPECT_EQ(meta["varied"], nlohmann::json::array({"yaw_mrad", "y_mm"}));
}

TEST(SweepCli, MergedShardsWriteTheBytesOfTheWholeSweepAndStrangersAreRefused) {
  const ScratchDirectory dir("sweep_shards");
  write(dir / "s.toml", kSweep);
  const std::string file = (dir / "s.toml").string();
  ASSERT_EQ(run_cli("sweep " + file + " --threads 1 --out " + (dir / "whole").string(), kNoFigures).exit_code, 0);
  for (int i = 0; i < 3; ++i) {
    const CommandResult r = run_cli(fmt_shard(file, i, dir), kNoFigures);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string s0 = (dir / "s0").string(), s1 = (dir / "s1").string(), s2 = (dir / "s2").string();
  const CommandResult merged = run_cli("merge " + s2 + " " + s0 + " " + s1 + " --out " + (dir / "merged").string(), kNoFigures);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(read(dir / "whole" / "sweep.csv"), read(dir / "merged" / "sweep.csv"));
  EXPECT_EQ(read(dir / "whole" / "sweep.json"), read(dir / "merged" / "sweep.json"));

  // A missing shard, a shard twice, a shard of another sweep.
  CommandResult r = run_cli("merge " + s0 + " " + s1 + " --out " + (dir / "m2").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("shard(s) 2 of 3 missing"), std::string::npos) << r.err;
  r = run_cli("merge " + s0 + " " + s0 + " " + s1 + " " + s2 + " --out " + (dir / "m2").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("shard 0/3 given twice"), std::string::npos) << r.err;
  write(dir / "t.toml", std::string(kSweep) + "# another sweep\n");
  ASSERT_EQ(run_cli("sweep " + (dir / "t.toml").string() + " --shard 1/3 --threads 1 --out " + (dir / "t1").string(),
                    kNoFigures).exit_code, 0);
  r = run_cli("merge " + s0 + " " + (dir / "t1").string() + " " + s2 + " --out " + (dir / "m2").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("are not shards of the same sweep"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "m2" / "sweep.csv"));
}

// A set-up file (gauge, rolling radius, the profiles) with the shipped profiles and the given gauge.
std::string setup_with_gauge(const std::string& gauge_m) {
  const std::string profiles = std::string(RAILCONTACT_DATA_DIR) + "/profiles/";
  return "{\"wheel_profile\": \"" + profiles + "MBench_S1002_v3.prw\", \"rail_profile\": \"" + profiles +
         "MBench_UIC60_v3.prr\", \"track\": {\"track_gauge_m\": " + gauge_m +
         ", \"gauge_measuring_depth_m\": 0.014, \"flange_back_distance_m\": 1.360, \"flange_back_y_m\": -0.070, "
         "\"taping_line_from_flange_back_m\": 0.070, \"nominal_rolling_radius_m\": 0.46}}\n";
}

// The journal's identity covers the [setup] file: shards of two gauges are not merged, and a shard
// rerun after the gauge changed is refused instead of resumed (the sweep file's bytes are the same).
TEST(SweepCli, ShardsOfAnotherSetUpFileAreNeitherMergedNorResumed) {
  const ScratchDirectory dir("sweep_setup_identity");
  write(dir / "s.toml", "[setup]\nfile = \"setup.json\"\n[mesh]\nelement_size_mm = 1.5\n[solvers]\nrun = [\"fastsim\"]\n"
                        "[grid]\ny_mm = [0, 1]\n");
  const std::string file = (dir / "s.toml").string();
  const auto shard = [&](int i) {
    return "sweep " + file + " --threads 1 --shard " + std::to_string(i) + "/2 --out " + (dir / ("s" + std::to_string(i))).string();
  };
  write(dir / "setup.json", setup_with_gauge("1.435"));
  CommandResult r = run_cli(shard(0), kNoFigures);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  write(dir / "setup.json", setup_with_gauge("1.437"));
  r = run_cli(shard(1), kNoFigures);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli("merge " + (dir / "s0").string() + " " + (dir / "s1").string() + " --out " + (dir / "m").string(), kNoFigures);
  railcontact::test::expect_one_error_line(r, "are not shards of the same sweep");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "m" / "sweep.csv"));
  // Shard 0 again with the new gauge: its journal is of another sweep.
  r = run_cli(shard(0), kNoFigures);
  EXPECT_NE(r.err.find("railcontact: error: " + (dir / "s0" / "sweep-shard-0-of-2.journal").string() +
                       " holds 1 completed cases of another sweep"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("its set-up file"), std::string::npos) << r.err;
  EXPECT_EQ(r.exit_code, 2);
  // Rebuilt with the new gauge, the shards merge; sweep.json records the set-up file and its track.
  ASSERT_EQ(run_cli(shard(0) + " --restart", kNoFigures).exit_code, 0);
  r = run_cli("merge " + (dir / "s0").string() + " " + (dir / "s1").string() + " --out " + (dir / "m").string(), kNoFigures);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json meta = nlohmann::json::parse(read(dir / "m" / "sweep.json"));
  EXPECT_EQ(meta["setup"]["file"], "setup.json");
  EXPECT_EQ(meta["setup"]["fnv1a64"].get<std::string>().size(), 16u);
  EXPECT_EQ(meta["track"]["track_gauge_m"], 1.437);  // the JSON number as written in the set-up file
}

// merge reads regular files only, refused at once (not read forever or waited on), and says what
// it expects when given something that is not a journal.
TEST(SweepCli, MergeRefusesDevicesFifosDirectoriesAndFilesThatAreNotJournals) {
  const ScratchDirectory dir("merge_not_journals");
  const std::string out = " --out " + (dir / "m").string();
  const std::string limits = railcontact::test::bounded_run_prefix(4000000, 60);  // without the checks: 20 GB, or a hang
  CommandResult r = run_cli("merge /dev/zero" + out, limits);
  railcontact::test::expect_one_error_line(r, "cannot read the journal /dev/zero: it is a character device");
  EXPECT_EQ(r.exit_code, 3);
  ASSERT_EQ(mkfifo((dir / "f.journal").c_str(), 0600), 0);
  r = run_cli("merge " + (dir / "f.journal").string() + out, limits);
  railcontact::test::expect_one_error_line(r, "f.journal: it is a FIFO (named pipe), not a regular file");
  EXPECT_EQ(r.exit_code, 3);
  // A directory of shards holding a FIFO or a directory by a journal's name.
  std::filesystem::create_directories(dir / "shards" / "sweep-shard-0-of-2.journal");
  r = run_cli("merge " + (dir / "shards").string() + out, limits);
  railcontact::test::expect_one_error_line(r, "sweep-shard-0-of-2.journal: it is a directory");
  EXPECT_EQ(r.exit_code, 3);
  std::filesystem::remove(dir / "shards" / "sweep-shard-0-of-2.journal");
  ASSERT_EQ(mkfifo((dir / "shards" / "sweep-shard-1-of-2.journal").c_str(), 0600), 0);
  r = run_cli("merge " + (dir / "shards").string() + out, limits);
  railcontact::test::expect_one_error_line(r, "sweep-shard-1-of-2.journal: it is a FIFO");
  EXPECT_EQ(r.exit_code, 3);
  // The sweep file itself: what merge got and what it expects; the user's file is not to be removed.
  write(dir / "s.toml", kSweep);
  r = run_cli("merge " + (dir / "s.toml").string() + out, limits);
  railcontact::test::expect_one_error_line(r, "s.toml is not a complete sweep or table journal (it begins with '[mesh]'");
  EXPECT_NE(r.err.find("merge expects the journals of `railcontact sweep --shard i/N`"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("remove"), std::string::npos) << r.err;
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(std::filesystem::exists(dir / "s.toml"));
}

// Starts `railcontact sweep` and kills it (SIGKILL) once its journal holds `records` cases.
void run_and_kill(const std::string& file, const std::filesystem::path& out, int records) {
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    setenv("RAILCONTACT_SCRIPTS", "/nonexistent-railcontact-scripts", 1);
    execl(RAILCONTACT_CLI, RAILCONTACT_CLI, "sweep", file.c_str(), "--threads", "1", "--out", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string journal = read(out / "sweep.journal");
    int n = 0;
    for (std::size_t at = 0; (at = journal.find("\ncase ", at)) != std::string::npos; ++at) ++n;
    if (n >= records) break;
    if (waitpid(pid, &status, WNOHANG) == pid) FAIL() << "the sweep ended before it was killed";
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
}

TEST(SweepCli, AKilledSweepResumesToTheSameBytesAndAChangedFileIsRefused) {
  const ScratchDirectory dir("sweep_resume");
  write(dir / "s.toml", kSweep);
  const std::string file = (dir / "s.toml").string();
  ASSERT_EQ(run_cli("sweep " + file + " --threads 1 --out " + (dir / "whole").string(), kNoFigures).exit_code, 0);
  run_and_kill(file, dir / "cut", 3);
  ASSERT_TRUE(std::filesystem::exists(dir / "cut" / "sweep.journal"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cut" / "sweep.csv"));
  // A record cut short by the kill (simulated: appended by hand) is dropped on the rerun.
  { std::ofstream(dir / "cut" / "sweep.journal", std::ios::app | std::ios::binary) << "case 9 ok 120 0123456789abcdef\n9,ok,"; }

  // The file changed: refused, the journal kept.
  write(dir / "s.toml", std::string(kSweep) + "# edited\n");
  CommandResult r = run_cli("sweep " + file + " --threads 1 --out " + (dir / "cut").string(), kNoFigures);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("completed cases of another sweep"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--restart"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "cut" / "sweep.journal"));

  // The same file again: resumes, computes the others only, the bytes of the whole sweep.
  write(dir / "s.toml", kSweep);
  r = run_cli("sweep " + file + " --threads 2 --out " + (dir / "cut").string(), kNoFigures);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("resuming: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("dropped an incomplete record"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("from an earlier run"), std::string::npos);
  EXPECT_EQ(r.out.find(" 0 from an earlier run"), std::string::npos) << r.out;
  EXPECT_EQ(read(dir / "whole" / "sweep.csv"), read(dir / "cut" / "sweep.csv"));
  EXPECT_EQ(read(dir / "whole" / "sweep.json"), read(dir / "cut" / "sweep.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cut" / "sweep.journal"));

  // --restart discards an earlier run's cases of another sweep.
  run_and_kill(file, dir / "again", 2);
  write(dir / "s.toml", std::string(kSweep) + "# edited\n");
  r = run_cli("sweep " + file + " --threads 1 --restart --out " + (dir / "again").string(), kNoFigures);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("10 computed, 0 from an earlier run"), std::string::npos) << r.out;
}

TEST(SweepCli, FailedCasesAreRowsWithTheirErrorAndTheExitCodeSaysSo) {
  const ScratchDirectory dir("sweep_failed");
  // y = 12 mm: the left flange climbs over its rail; the list form of a sweep.
  write(dir / "s.toml", "[mesh]\nelement_size_mm = 1.0\n[[case]]\ny_mm = 0\n[[case]]\ny_mm = 12\n[[case]]\ny_mm = 1\nmu = 0.2\n");
  const CommandResult r = run_cli("sweep " + (dir / "s.toml").string() + " --out " + (dir / "out").string(), kNoFigures);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("1 of 3 cases failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("case 1: contact search, left wheel at y = 12.000 mm"), std::string::npos) << r.err;
  const auto rows = rows_of(read(dir / "out" / "sweep.csv"));
  ASSERT_EQ(rows.size(), 1u + 2 + 1 + 2);
  const auto& h = rows[0];
  EXPECT_EQ(rows[3][column(h, "case")], "1");
  EXPECT_EQ(rows[3][column(h, "status")], "failed");
  EXPECT_EQ(rows[3][column(h, "y_mm")], "12");
  EXPECT_EQ(rows[3][column(h, "error_kind")], "invalid input");
  // Every column: the fields before the quoted message, then the message.
  const std::string failed_row = read(dir / "out" / "sweep.csv").substr(read(dir / "out" / "sweep.csv").find("\n1,failed,") + 1);
  const std::string before_message = failed_row.substr(0, failed_row.find(",\""));
  EXPECT_EQ(static_cast<std::size_t>(std::count(before_message.begin(), before_message.end(), ',')) + 2, h.size());
  EXPECT_EQ(rows[4][column(h, "mu")], "0.2");
  // A case of its own friction (a wheelset of its own in the worker) gives `railcontact wheelset`'s numbers.
  const CommandResult single = run_cli("wheelset --y-m 0.001 --mu 0.2 --element-size-m 0.001 --json");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const nlohmann::json j = nlohmann::json::parse(single.out);
  EXPECT_NEAR(std::stod(rows[4][column(h, "nh-fastsim_F1_N")]), j["wheels"][0]["patches"][0]["nh-fastsim"]["F1_N"].get<double>(),
              0.01);
  EXPECT_NEAR(std::stod(rows[4][column(h, "wheel_Fy_N")]), j["wheels"][0]["force_track_N"][1].get<double>(), 0.01);
  EXPECT_EQ(nlohmann::json::parse(read(dir / "out" / "sweep.json"))["failed_cases"], 1);
}

// flextable build and wheelset-table build: the same file on one thread and on two.
TEST(TableBuildThreads, TwoThreadsWriteTheBytesOfOne) {
  const ScratchDirectory dir("table_threads");
  const std::string epoch = "SOURCE_DATE_EPOCH=1700000000 ";
  for (const char* threads : {"1", "2"}) {
    CommandResult r = run_cli("flextable build --y-from-m -0.002 --y-to-m 0.002 --y-step-m 0.0005 --elements 300 --load-N 80000 "
                              "--load-N 100000 --threads " + std::string(threads) + " --out " +
                              (dir / ("f" + std::string(threads) + ".json")).string(), epoch);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_cli("wheelset-table build --y-m=-0.002:0.002:0.00025 --load-N 90000,110000 --element-size-m 0.001 --threads " + std::string(threads) +
                " --out " + (dir / ("w" + std::string(threads) + ".json")).string(), epoch);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string f1 = read(dir / "f1.json");
  EXPECT_EQ(f1, read(dir / "f2.json"));
  EXPECT_EQ(read(dir / "w1.json"), read(dir / "w2.json"));
  const nlohmann::json t = nlohmann::json::parse(f1);
  EXPECT_EQ(t["created_utc"], "2023-11-14T22:13:20Z");  // SOURCE_DATE_EPOCH
  const CommandResult bad = run_cli("flextable build --out " + (dir / "bad.json").string(), "SOURCE_DATE_EPOCH=soon ");
  railcontact::test::expect_one_error_line(bad, "SOURCE_DATE_EPOCH 'soon' must be a whole number of seconds");
  EXPECT_EQ(bad.exit_code, 2);
  ASSERT_GE(t["y_m"].size(), 9u);  // and the brackets of the contact jumps
  ASSERT_EQ(t["nodes"].size(), t["y_m"].size() * 2);
  for (std::size_t k = 0; k < t["nodes"].size(); k += 2) {
    const auto& light = t["nodes"][k];
    const auto& heavy = t["nodes"][k + 1];  // the same y at 100 kN: a larger patch, larger flexibilities
    EXPECT_EQ(light["status"], "solved");
    EXPECT_GT(light["L1_m_per_Pa"].get<double>(), 1e-14);  // about 8a / (3 G C11): 4e-14 ... 5e-14 here
    EXPECT_LT(light["L1_m_per_Pa"].get<double>(), 1e-12);
    EXPECT_GT(heavy["L1_m_per_Pa"].get<double>(), light["L1_m_per_Pa"].get<double>());
  }
}

}  // namespace

namespace {

// The CSV without one column (a timing, which differs from run to run even on one thread).
std::string without_column(const std::string& csv, const std::string& name) {
  const auto rows = rows_of(csv);
  const std::size_t drop = column(rows.at(0), name);
  std::string out;
  for (const auto& r : rows) {
    for (std::size_t i = 0; i < r.size(); ++i)
      if (i != drop) out += r[i] + ",";
    out += "\n";
  }
  return out;
}

// study paper (Fig 5, the heaviest part), study patches and study bound: the same files on one and two threads.
TEST(StudyThreads, PaperFig5PatchesAndBoundWriteTheSameFilesOnTwoThreads) {
  const ScratchDirectory dir("study_threads");
  for (const char* threads : {"1", "2"}) {
    const std::string t(threads);
    CommandResult r = run_cli("study paper --elements 300 --y-step-m 1.5e-3 --samples 1 --no-figures --threads " + t +
                              " --out " + (dir / ("paper" + t)).string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_cli("study patches --elements 300 --y-step-m 1e-3 --no-figures --threads " + t + " --out " +
                (dir / ("patches" + t)).string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_cli("study bound --elements 300 --y-step-m 1.5e-3 --threads " + t + " --out " + (dir / ("bound" + t)).string(),
                kNoFigures);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string bound = read(dir / "bound1" / "bound_sweep.csv");
  EXPECT_EQ(bound, read(dir / "bound2" / "bound_sweep.csv"));
  EXPECT_EQ(read(dir / "bound1" / "summary.md"), read(dir / "bound2" / "summary.md"));
  EXPECT_EQ(rows_of(bound).size(), 1u + (11 + 7) * 7);  // 11 ellipses and 7 positions, 7 skews each
  for (const char* f : {"fig5.csv", "fig5_patches.csv"})
    EXPECT_EQ(read(dir / "paper1" / f), read(dir / "paper2" / f)) << f;
  const std::string patches = read(dir / "patches1" / "patches.csv");
  EXPECT_EQ(without_column(patches, "solve_time_s"), without_column(read(dir / "patches2" / "patches.csv"), "solve_time_s"));
  for (const auto& entry : std::filesystem::directory_iterator(dir / "patches1"))
    if (entry.path().filename().string().rfind("patch_y", 0) == 0)
      EXPECT_EQ(read(entry.path()), read(dir / "patches2" / entry.path().filename())) << entry.path();

  // Real numbers: Fig 5 has 7 y values × 3 families × 5 levels × 4 solvers; nh-fastsim within 10 %
  // of exact at 300 elements; every patch of the patch study carries its 98.1 kN (F3 = Fz / cos γ).
  const auto fig5 = rows_of(read(dir / "paper1" / "fig5.csv"));
  ASSERT_EQ(fig5.size(), 1u + 7 * 3 * 5 * 4);
  for (std::size_t i = 1; i < fig5.size(); ++i)
    if (fig5[i][column(fig5[0], "solver")] == "nh-fastsim")
      EXPECT_LT(std::stod(fig5[i][column(fig5[0], "rel_error")]), 0.10) << i;
  const auto rows = rows_of(patches);
  ASSERT_EQ(rows.size(), 1u + 10);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double F3 = std::stod(rows[i][column(rows[0], "normal_force_N")]);
    const double gamma = std::stod(rows[i][column(rows[0], "contact_angle_rad")]);
    EXPECT_NEAR(F3 * std::cos(gamma), 98100.0, 100.0) << i;
  }
}

}  // namespace

namespace {

// flextable build --shard i/N and merge: the table file of the build on one machine; a shard
// rerun resumes; a missing shard is refused.
TEST(TableShards, FlexibilityTableShardsMergeToTheBytesOfOneBuild) {
  const ScratchDirectory dir("flextable_shards");
  const std::string epoch = "SOURCE_DATE_EPOCH=1700000000 ";
  const std::string build = "flextable build --y-from-m -0.003 --y-to-m 0.003 --y-step-m 0.0005 --elements 300 --load-N 80000 "
                            "--load-N 100000 --threads 1 ";
  ASSERT_EQ(run_cli(build + "--out " + (dir / "one.json").string(), epoch).exit_code, 0);
  const std::string part = (dir / "t.json").string();
  for (const char* i : {"0", "1", "2"}) {
    const CommandResult r = run_cli(build + "--shard " + std::string(i) + "/3 --out " + part, epoch);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("0 from an earlier run"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "t.json"));  // a shard writes its journal only
  CommandResult again = run_cli(build + "--shard 1/3 --out " + part, epoch);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("0 nodes computed"), std::string::npos) << again.out;
  const std::string j0 = part + ".shard-0-of-3.journal", j1 = part + ".shard-1-of-3.journal",
                    j2 = part + ".shard-2-of-3.journal";
  const CommandResult merged = run_cli("merge " + j1 + " " + j0 + " " + j2 + " --out " + (dir / "merged.json").string());
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  const std::string one = read(dir / "one.json");
  EXPECT_EQ(one, read(dir / "merged.json"));
  EXPECT_EQ(nlohmann::json::parse(one)["nodes"].size(), 26u);  // 13 y × 2 loads (the smooth reference: no jump)
  const CommandResult missing = run_cli("merge " + j0 + " " + j2 + " --out " + (dir / "m2.json").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("shard(s) 1 of 3 missing"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "m2.json"));
}

}  // namespace

namespace {

// study coefficients: Table 1's rows on two threads give the same three tables (Fig 3 and 4 stay
// on one thread: fig4.csv carries timings).
TEST(StudyThreads, CoefficientTablesAreTheSameOnTwoThreads) {
  const ScratchDirectory dir("coefficient_threads");
  for (const char* threads : {"1", "2"}) {
    const std::string t(threads);
    const CommandResult r = run_cli("study coefficients --elements 200 --fine-elements 400 --no-figures --threads " + t +
                                    " --out " + (dir / ("c" + t)).string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (const char* f : {"table1.csv", "table1_paper.csv", "table1_fine.csv", "fig3.csv"})
    EXPECT_EQ(read(dir / "c1" / f), read(dir / "c2" / f)) << f;
  // Kalker's 57 entries, within 7 % on this coarse mesh (0.1-0.4 % at the study's 2800 elements).
  const auto rows = rows_of(read(dir / "c1" / "table1.csv"));
  ASSERT_EQ(rows.size(), 1u + 57);
  for (std::size_t i = 1; i < rows.size(); ++i)
    for (const char* e : {"err_C11", "err_C22", "err_C23"}) EXPECT_LT(std::abs(std::stod(rows[i][column(rows[0], e)])), 0.07) << i;
}

}  // namespace
