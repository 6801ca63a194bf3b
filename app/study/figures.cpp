#include "study/figures.hpp"

#include <cstdlib>

#include <fmt/format.h>

namespace railcontact::study {
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

}  // namespace

bool draw_figures(const std::string& script, const std::filesystem::path& directory, std::ostream& log) {
  const std::filesystem::path path = scripts_directory() / script;
  if (!std::filesystem::exists(path)) {
    log << fmt::format("warning: figure script {} not found; CSV files written, figures skipped\n", path.string());
    return false;
  }
  const std::string command =
      fmt::format("{} {} {} 2>&1", quoted(python()), quoted(path.string()), quoted(directory.string()));
  const int status = std::system(command.c_str());
  if (status != 0) {
    log << fmt::format("warning: {} failed (is python3-matplotlib installed?); CSV files written, figures skipped\n",
                       script);
    return false;
  }
  return true;
}

}  // namespace railcontact::study
