#pragma once
// Runs the command-line tool (RAILCONTACT_CLI) as a user would and captures stdout, stderr and
// the exit code; shared by the CLI tests.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace railcontact::test {

struct CommandResult {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// A shell prefix that bounds a CLI run: at most `memory_kib` of address space and `seconds` of
// wall time, so a reader that reads an endless device or waits on a FIFO fails the test in
// seconds. Under AddressSanitizer only the time is bounded: its shadow memory reserves terabytes
// of address space, which any ulimit -v refuses.
inline std::string bounded_run_prefix(long memory_kib, int seconds) {
#if defined(__SANITIZE_ADDRESS__)
  (void)memory_kib;
  return "exec timeout " + std::to_string(seconds) + " ";
#else
  return "ulimit -v " + std::to_string(memory_kib) + "; exec timeout " + std::to_string(seconds) + " ";
#endif
}

// Runs `railcontact ARGUMENTS`, after `shell_prefix` (e.g. limits: "ulimit -v N; exec timeout S ").
inline CommandResult run_cli(const std::string& arguments, const std::string& shell_prefix = "") {
  // One file per call: ctest runs the tests in parallel processes.
  std::string err_file = ::testing::TempDir() + "railcontact_cli_stderr_XXXXXX";
  const int fd = mkstemp(err_file.data());
  if (fd >= 0) close(fd);
  const std::string command = shell_prefix + std::string(RAILCONTACT_CLI) + " " + arguments + " 2>" + err_file;
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) result.out += buffer.data();
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (FILE* f = fopen(err_file.c_str(), "r")) {
    while (fgets(buffer.data(), buffer.size(), f) != nullptr) result.err += buffer.data();
    fclose(f);
  }
  std::remove(err_file.c_str());
  return result;
}

// A fresh directory per test process and name (ctest runs the tests in parallel):
// <TempDir>/railcontact_<name>_<pid>. Prefer ScratchDirectory, which also removes it.
inline std::filesystem::path scratch_directory(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("railcontact_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A scratch directory (scratch_directory(name)) that is removed with everything in it when the
// object goes out of scope, whether the test passes, fails an ASSERT or throws: tests leave nothing
// in /tmp. Neither copied nor moved (one owner); use it as a path:
//   const ScratchDirectory dir("flextable_build");
//   write(dir / "case.toml", ...);  run_cli("... --out " + dir.string());
class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& name) : path_(scratch_directory(name)) {}
  ~ScratchDirectory() {
    std::error_code ignored;  // never throw from a destructor; a vanished directory is fine
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  ScratchDirectory(ScratchDirectory&&) = delete;
  ScratchDirectory& operator=(ScratchDirectory&&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  operator const std::filesystem::path&() const { return path_; }  // NOLINT: used as a path
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  [[nodiscard]] std::string string() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// The rows of a CSV file the tool wrote, split at commas (no quoting).
inline std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(file, line);) {
    std::vector<std::string> fields;
    std::stringstream stream(line);
    for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
    rows.push_back(fields);
  }
  return rows;
}

inline int count_lines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

// Bad input: a non-zero exit, one line "railcontact: error: ..." naming `expected`, no output.
inline void expect_one_error_line(const CommandResult& r, const std::string& expected) {
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("railcontact: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

}  // namespace railcontact::test
