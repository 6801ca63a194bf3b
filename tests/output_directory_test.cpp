// Output directories (docs/RELIABILITY.md "Outputs"): one run per directory (a lock), outputs
// staged and committed, leftovers of interrupted runs removed and reported; `flextable build`
// checks its output before the work.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"
#include "railcontact/error.hpp"
#include "output/output_directory.hpp"

namespace {

namespace fs = std::filesystem;
using railcontact::Error;
using railcontact::ErrorKind;
using railcontact::output::OutputDirectory;
using railcontact::test::CommandResult;
using railcontact::test::run_cli;
using railcontact::test::ScratchDirectory;

std::string read(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

int staging_directories(const fs::path& dir) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    count += entry.path().filename().string().rfind(".staging-", 0) == 0;
  return count;
}

TEST(OutputDirectory, SecondRunOnTheSameDirectoryIsRefused) {
  const ScratchDirectory dir("outdir_lock");
  const OutputDirectory first(dir.path());
  try {
    const OutputDirectory second(dir.path());
    FAIL() << "a second OutputDirectory on a locked directory was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::io);
    EXPECT_NE(std::string(e.what()).find(dir.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("in use by another railcontact run"), std::string::npos) << e.what();
  }
}

TEST(OutputDirectory, LockIsReleasedWithTheObject) {
  const ScratchDirectory dir("outdir_release");
  { const OutputDirectory first(dir.path()); }
  EXPECT_NO_THROW(OutputDirectory second(dir.path()));
}

TEST(OutputDirectory, CreatesAMissingDirectory) {
  const ScratchDirectory dir("outdir_create");
  const fs::path nested = dir / "a" / "b";
  OutputDirectory out(nested);
  write(out.path("x.csv"), "1\n");
  out.commit();
  EXPECT_EQ(read(nested / "x.csv"), "1\n");
}

TEST(OutputDirectory, CommitMovesTheFilesAndRemovesTheStaging) {
  const ScratchDirectory dir("outdir_commit");
  write(dir / "old.csv", "old\n");
  write(dir / "a.csv", "previous a\n");
  {
    OutputDirectory out(dir.path());
    EXPECT_EQ(out.path("a.csv").parent_path(), out.staging());
    EXPECT_NE(out.staging(), dir.path());
    write(out.path("a.csv"), "new a\n");
    write(out.path("b.csv"), "new b\n");
    EXPECT_EQ(read(dir / "a.csv"), "previous a\n");  // nothing visible before the commit
    EXPECT_FALSE(fs::exists(dir / "b.csv"));
    out.commit();
    EXPECT_TRUE(out.committed());
    EXPECT_FALSE(fs::exists(out.staging()));
  }
  EXPECT_EQ(read(dir / "a.csv"), "new a\n");
  EXPECT_EQ(read(dir / "b.csv"), "new b\n");
  EXPECT_EQ(read(dir / "old.csv"), "old\n");
  EXPECT_EQ(staging_directories(dir), 0);
}

TEST(OutputDirectory, WithoutCommitTheOldFilesStayUnchanged) {
  const ScratchDirectory dir("outdir_abandon");
  write(dir / "a.csv", "complete a\n");
  write(dir / "summary.md", "complete summary\n");
  try {
    OutputDirectory out(dir.path());
    write(out.path("a.csv"), "trunc");
    write(out.path("summary.md"), "new summary\n");
    throw Error(ErrorKind::not_converged, "the run failed half-way");
  } catch (const Error&) {
  }
  EXPECT_EQ(read(dir / "a.csv"), "complete a\n");
  EXPECT_EQ(read(dir / "summary.md"), "complete summary\n");
  EXPECT_EQ(staging_directories(dir), 0);
}

TEST(OutputDirectory, StaleStagingOfAnInterruptedRunIsRemovedAndReported) {
  const ScratchDirectory dir("outdir_stale");
  write(dir / "a.csv", "complete a\n");
  fs::create_directories(dir / ".staging-999999");
  write(dir / ".staging-999999" / "a.csv", "trunc");
  std::ostringstream log;
  const OutputDirectory out(dir.path(), &log);
  EXPECT_FALSE(fs::exists(dir / ".staging-999999"));
  EXPECT_EQ(staging_directories(dir), 1);  // our own
  EXPECT_EQ(log.str(), out.stale_note());
  EXPECT_NE(out.stale_note().find("removed the unfinished outputs of an interrupted run in " +
                                  (dir / ".staging-999999").string()),
            std::string::npos)
      << out.stale_note();
  EXPECT_EQ(read(dir / "a.csv"), "complete a\n");
}

TEST(OutputDirectory, NoNoteWithoutLeftovers) {
  const ScratchDirectory dir("outdir_clean");
  std::ostringstream log;
  const OutputDirectory out(dir.path(), &log);
  EXPECT_TRUE(out.stale_note().empty());
  EXPECT_TRUE(log.str().empty());
}

TEST(OutputDirectory, RunTwiceIntoTheSameDirectory) {
  const ScratchDirectory dir("outdir_run_twice");
  const fs::path out = dir / "out";
  const CommandResult first = run_cli("run --json --out " + out.string());
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::string patch = read(out / "patch.csv");
  EXPECT_FALSE(patch.empty());
  const CommandResult second = run_cli("run --json --out " + out.string());
  ASSERT_EQ(second.exit_code, 0) << second.err;
  for (const char* file : {"result.json", "patch.csv", "mesh.csv"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  EXPECT_EQ(read(out / "patch.csv"), patch);  // complete, the same case
  EXPECT_EQ(staging_directories(out), 0);
}

TEST(OutputDirectory, RunIntoALockedDirectoryFailsWithExitCode3) {
  const ScratchDirectory dir("outdir_run_locked");
  write(dir / "result.json", "{}\n");
  const int fd = ::open((dir / ".railcontact.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const CommandResult r = run_cli("run --json --out " + dir.string());
  ::close(fd);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("output directory " + dir.string() + " is in use by another railcontact run"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(read(dir / "result.json"), "{}\n");  // the other run's files untouched
}

TEST(OutputDirectory, RunReportsTheLeftoversOfAnInterruptedRun) {
  const ScratchDirectory dir("outdir_run_stale");
  fs::create_directories(dir / ".staging-999999");
  write(dir / ".staging-999999" / "patch.csv", "x1_m,x2");
  const CommandResult r = run_cli("run --json --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("note: removed the unfinished outputs of an interrupted run in " +
                       (dir / ".staging-999999").string()),
            std::string::npos)
      << r.err;
  EXPECT_EQ(staging_directories(dir), 0);
  EXPECT_TRUE(fs::exists(dir / "result.json"));
}

// Ctrl-C or SIGTERM during a study: the previous complete outputs stay, the run says so, and the
// next run in the directory removes the unfinished outputs and reports it.
TEST(OutputDirectory, InterruptedStudyLeavesTheOldOutputs) {
  const ScratchDirectory dir("outdir_interrupted");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  write(out / "summary.md", "complete summary\n");
  write(out / "creep_curves.csv", "complete csv\n");
  const std::string err_file = (dir / "stderr.txt").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> arguments = {RAILCONTACT_CLI, "study", "hertz", "--out", out.string()};
  std::vector<char*> argv;
  for (std::string& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  ASSERT_EQ(posix_spawn(&pid, RAILCONTACT_CLI, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Wait until it has written something into its staging directory, then stop it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool staged = false;
  while (!staged && std::chrono::steady_clock::now() < deadline) {
    for (const auto& entry : fs::directory_iterator(out))
      if (entry.path().filename().string().rfind(".staging-", 0) == 0 && fs::exists(entry.path() / "creep_curves.csv") &&
          fs::file_size(entry.path() / "creep_curves.csv") > 0)
        staged = true;
    if (!staged) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(staged);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the study finished before it was stopped";
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_NE(read(err_file).find("interrupted; the outputs in " + out.string() + " are unchanged"), std::string::npos)
      << read(err_file);
  EXPECT_EQ(read(out / "summary.md"), "complete summary\n");
  EXPECT_EQ(read(out / "creep_curves.csv"), "complete csv\n");
  EXPECT_EQ(staging_directories(out), 1);

  const CommandResult next = run_cli("run --json --out " + out.string());
  ASSERT_EQ(next.exit_code, 0) << next.err;
  EXPECT_NE(next.err.find("note: removed the unfinished outputs of an interrupted run in " + (out / ".staging-").string()),
            std::string::npos)
      << next.err;
  EXPECT_EQ(staging_directories(out), 0);
}

// `flextable build` fails on an unwritable output at once: before the first node (no "node" line,
// well under the time of one node).
void expect_fails_before_building(const std::string& out) {
  const auto start = std::chrono::steady_clock::now();
  const CommandResult r = run_cli("flextable build --out " + out + " --y-from-m 0 --y-to-m 0.001 --y-step-m 0.001");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 3) << r.err;  // io
  EXPECT_EQ(r.err.find("node"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot write the flexibility table " + out), std::string::npos) << r.err;
  EXPECT_LT(seconds, 5.0);
  EXPECT_FALSE(fs::exists(out));
}

TEST(OutputDirectory, FlextableBuildChecksAMissingDirectoryFirst) {
  expect_fails_before_building("/nonexistent-dir/t.json");
}

TEST(OutputDirectory, FlextableBuildChecksAReadOnlyDirectoryFirst) {
  const ScratchDirectory dir("outdir_flextable_ro");
  const fs::path read_only = dir / "ro";
  fs::create_directories(read_only);
  fs::permissions(read_only, fs::perms::owner_read | fs::perms::owner_exec);
  if (::access(read_only.c_str(), W_OK) != 0) expect_fails_before_building((read_only / "t.json").string());
  fs::permissions(read_only, fs::perms::owner_all);
  // root writes where permissions forbid it; /proc refuses new files to root too.
  if (fs::is_directory("/proc")) expect_fails_before_building("/proc/railcontact_t.json");
  for (const auto& entry : fs::directory_iterator(dir)) EXPECT_EQ(entry.path(), read_only);  // no temporary left
}

}  // namespace

// A write that fails for want of room (simulated portably by a file-size limit: `ulimit -f` with
// SIGXFSZ ignored makes write(2) fail with EFBIG, as a full disk fails with ENOSPC) names the file
// the user asked for, DIR/NAME or the table FILE, never the staged or temporary file, with the
// reason, in one line on stderr and nothing on stdout.
const std::string kFileSizeLimit = "trap '' XFSZ; ulimit -f 16; exec ";

// progress: the command reports its progress on stderr before the error line (flextable build).
void expect_one_write_error(const CommandResult& r, const std::string& expected, bool progress = false) {
  EXPECT_EQ(r.exit_code, 3) << r.err;  // io
  const std::string line = "railcontact: error: " + expected;
  if (progress) {
    EXPECT_NE(r.err.find("\n" + line), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("railcontact: error:"), r.err.rfind("railcontact: error:")) << r.err;
    EXPECT_EQ(r.err.back(), '\n');
    EXPECT_EQ(r.err.find('\n', r.err.rfind("railcontact: error:")), r.err.size() - 1) << r.err;
  } else {
    EXPECT_EQ(r.err.rfind(line, 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(r.err.find(".staging-"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(".tmp-"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(OutputDirectory, AFailedWriteNamesTheFileAndTheReason) {
  const ScratchDirectory dir("outdir_write_error");
  const fs::path out = dir / "patch";
  expect_one_write_error(run_cli("patch --elements 3000 --out " + out.string(), kFileSizeLimit),
                         "cannot write " + (out / "pressure.csv").string() + ": File too large");
  EXPECT_EQ(staging_directories(out), 0);
  const fs::path table = dir / "t.json";
  expect_one_write_error(
      run_cli("flextable build --out " + table.string() + " --y-from-m 0 --y-to-m 0.001 --y-step-m 0.001 --elements 3000",
              "trap '' XFSZ; ulimit -f 1; exec "),
      "cannot write the flexibility table " + table.string() + ": File too large", true);
  EXPECT_FALSE(fs::exists(table));
}

// A figure that cannot be written fails the run (a figure is an output the user asked for) with one
// line naming it and the reason, without the script's traceback.
// The CSV and JSON of 100 elements fit in the file-size limit, the PNG does not.
TEST(OutputDirectory, AFigureThatCannotBeWrittenFailsTheRunInOneLine) {
  const ScratchDirectory dir("outdir_figure_error");
  const fs::path out = dir / "patch";
  const CommandResult r = run_cli("patch --elements 100 --out " + out.string(), kFileSizeLimit);
  if (r.err.find("cannot import matplotlib") != std::string::npos) GTEST_SKIP() << "no matplotlib: " << r.err;
  expect_one_write_error(r, "cannot write the figure " + (out / "pressure.png").string() + ": File too large");
  EXPECT_EQ(r.err.find("Traceback"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "pressure.csv"));  // DIR keeps the last complete run's outputs: none
}

// A figure script that fails otherwise (a bug) warns with its error in one line; its traceback
// never reaches stdout, and the results are written.
TEST(OutputDirectory, AFailingFigureScriptWarnsInOneLine) {
  const ScratchDirectory dir("outdir_figure_bug");
  const fs::path scripts = dir / "scripts";
  fs::create_directories(scripts);
  fs::copy_file(fs::path(RAILCONTACT_SOURCE_DIR) / "scripts" / "figure_runner.py", scripts / "figure_runner.py");
  write(scripts / "plot_patch.py", "import sys\nprint('drawing')\n{}['dx1_m']\n");
  const fs::path out = dir / "patch";
  const CommandResult r =
      run_cli("patch --elements 100 --out " + out.string(), "RAILCONTACT_SCRIPTS=" + scripts.string() + " ");
  if (r.err.find("cannot import matplotlib") != std::string::npos) GTEST_SKIP() << "no matplotlib: " << r.err;
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the figure script plot_patch.py failed (KeyError: 'dx1_m'); CSV files written, "
                       "figures skipped\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out.find("Traceback"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("drawing"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out / "pressure.csv"));
}
