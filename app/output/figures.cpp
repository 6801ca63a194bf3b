#include "output/figures.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"
#include "output/output_directory.hpp"

namespace railcontact::output {
namespace {

std::filesystem::path scripts_directory() {
  if (const char* from_environment = std::getenv("RAILCONTACT_SCRIPTS")) return from_environment;
  return RAILCONTACT_SCRIPTS_DIR;
}

// Debian's python3 carries python3-matplotlib; a pyenv python3 earlier on PATH may not.
std::string python() {
  if (const char* from_environment = std::getenv("RAILCONTACT_PYTHON")) return from_environment;
  return std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The runner's output (stdout and stderr of the script; its last 32-64 KiB): never shown as it is.
struct Finished {
  int exit_code = -1;  // -1: did not exit normally
  std::string output;
};

Finished run_captured(const std::string& command) {
  Finished f;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return f;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    f.output.append(buffer.data(), n);
    if (f.output.size() > (1u << 16)) f.output.erase(0, f.output.size() - (1u << 15));  // the end says why
  }
  const int status = ::pclose(pipe);
  if (status != -1 && WIFEXITED(status)) f.exit_code = WEXITSTATUS(status);
  return f;
}

// The last non-empty line of the output, split at tabs.
std::vector<std::string> last_line_fields(const std::string& output) {
  const std::size_t end = output.find_last_not_of("\r\n");
  if (end == std::string::npos) return {};
  const std::size_t newline = output.rfind('\n', end);
  const std::size_t begin = newline == std::string::npos ? 0 : newline + 1;
  const std::string line = output.substr(begin, end + 1 - begin);
  std::vector<std::string> fields;
  std::size_t pos = 0;
  while (true) {
    const std::size_t tab = line.find('\t', pos);
    fields.push_back(line.substr(pos, tab == std::string::npos ? std::string::npos : tab - pos));
    if (tab == std::string::npos) break;
    pos = tab + 1;
  }
  return fields;
}

}  // namespace

bool draw_figures(const std::string& script, const std::filesystem::path& directory, std::ostream& log) {
  const std::filesystem::path path = scripts_directory() / script;
  const std::filesystem::path runner = scripts_directory() / "figure_runner.py";
  if (!std::filesystem::exists(path) || !std::filesystem::exists(runner)) {
    log << fmt::format("warning: figure script {} not found; CSV files written, figures skipped\n",
                       (std::filesystem::exists(path) ? runner : path).string());
    return false;
  }
  // Everything the script prints goes into the pipe (stderr too): the user sees one line at most.
  const std::string command = fmt::format("{} {} {} {} 2>&1", quoted(python()), quoted(runner.string()),
                                          quoted(path.string()), quoted(directory.string()));
  const Finished f = run_captured(command);
  if (f.exit_code == 0) return true;
  const std::vector<std::string> fields = last_line_fields(f.output);
  const std::string tag = fields.empty() ? std::string() : fields[0];
  if (f.exit_code == 4 && tag == "write-failed" && fields.size() >= 3) {
    // A figure is an output the user asked for: a figure that cannot be written fails the run
    // (docs/RELIABILITY.md "Outputs"), named as in the output directory.
    throw Error(ErrorKind::io, fmt::format("cannot write the figure {}: {}",
                                           named_for_user(std::filesystem::path(fields[1])).string(),
                                           printable_excerpt(fields[2], 200)));
  }
  if (f.exit_code == 3 && tag == "matplotlib-missing") {
    log << fmt::format("warning: {} cannot import matplotlib (install python3-matplotlib); CSV files written, "
                       "figures skipped\n",
                       python());
  } else if (f.exit_code == 127) {
    log << fmt::format("warning: {} not found (install python3 and python3-matplotlib); CSV files written, figures "
                       "skipped\n",
                       python());
  } else {
    log << fmt::format("warning: the figure script {} failed ({}); CSV files written, figures skipped\n", script,
                       printable_excerpt(fields.size() >= 2 ? fields[1]
                                         : fields.empty() ? "exit status " + std::to_string(f.exit_code)
                                                          : fields[0],
                                         200));
  }
  return false;
}

}  // namespace railcontact::output
