// Writing a table file safely (table_file_output.hpp).
#include "cli/table_file_output.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <ctime>
#include <string>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact::cli {
namespace {

// A temporary file in the directory of `out` (same file system: rename(2) moves it into place
// atomically); mkstemp creates it, the caller removes or renames it.
std::string temporary_next_to(const std::filesystem::path& out, int& fd) {
  const std::filesystem::path directory = out.parent_path().empty() ? std::filesystem::path(".") : out.parent_path();
  std::string file = ".";  // appended piece by piece: GCC 12 warns (-Wrestrict) on "." + s + "…"
  file += out.filename().string();
  file += ".tmp-XXXXXX";
  std::string name = (directory / file).string();
  fd = ::mkstemp(name.data());
  return name;
}

}  // namespace

void check_table_writable(const std::filesystem::path& out, const std::string& what) {
  const std::filesystem::path directory = out.parent_path().empty() ? std::filesystem::path(".") : out.parent_path();
  if (!std::filesystem::is_directory(directory))
    throw Error(ErrorKind::io,
                fmt::format("cannot write the {} {}: no directory {}", what, out.string(), directory.string()));
  require(!std::filesystem::is_directory(out),
          [&] { return fmt::format("cannot write the {} {}: it is a directory", what, out.string()); });
  int fd = -1;
  const std::string probe = temporary_next_to(out, fd);
  if (fd < 0)
    throw Error(ErrorKind::io, fmt::format("cannot write the {} {}: cannot create a file in {}: {}", what,
                                           out.string(), directory.string(), std::strerror(errno)));
  ::close(fd);
  ::unlink(probe.c_str());
}

void write_table_atomically(const std::filesystem::path& out, const std::string& what,
                            const std::function<void(const std::filesystem::path&)>& write) {
  int fd = -1;
  const std::string temporary = temporary_next_to(out, fd);
  if (fd < 0)
    throw Error(ErrorKind::io, fmt::format("cannot write the {} {}: {}", what, out.string(), std::strerror(errno)));
  ::close(fd);
  try {
    write(temporary);
  } catch (const Error& e) {
    // The writer names the temporary file; the user asked for `out`, and the reason is the errno
    // of the write that failed (a full disk: "No space left on device").
    const int error = errno;
    ::unlink(temporary.c_str());
    if (e.kind() != ErrorKind::io) throw;
    throw Error(ErrorKind::io, fmt::format("cannot write the {} {}: {}", what, out.string(),
                                           error != 0 ? std::strerror(error) : "the write failed"));
  } catch (...) {
    ::unlink(temporary.c_str());
    throw;
  }
  const mode_t mask = ::umask(0);  // mkstemp's 0600 would make the table private: the mode of a new file
  ::umask(mask);
  ::chmod(temporary.c_str(), 0666 & ~mask);
  if (::rename(temporary.c_str(), out.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    throw Error(ErrorKind::io, fmt::format("cannot write the {} {}: {}", what, out.string(), std::strerror(error)));
  }
}


std::string source_date_epoch_utc() {
  const char* text = std::getenv("SOURCE_DATE_EPOCH");
  if (text == nullptr || *text == '\0') return {};
  const std::string value(text);
  const bool digits = value.size() <= 12 && std::all_of(value.begin(), value.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digits)
    throw Error(fmt::format("SOURCE_DATE_EPOCH '{}' must be a whole number of seconds since 1970-01-01 (or unset)",
                            printable_excerpt(value)));
  const std::time_t t = static_cast<std::time_t>(std::stoll(value));
  std::tm utc{};
  gmtime_r(&t, &utc);
  char out[32];
  std::strftime(out, sizeof out, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return out;
}

}  // namespace railcontact::cli
