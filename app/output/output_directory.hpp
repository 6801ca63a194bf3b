#pragma once
// The output directory of one run (`--out DIR` of run, patch and the studies): locked against
// other runs, written through a staging directory and committed at the end (docs/RELIABILITY.md
// "Outputs").
//
// - The constructor creates DIR if needed and takes an exclusive lock (flock) on
//   DIR/.railcontact.lock; a directory locked by another run is refused with
//   Error(io, "output directory DIR is in use by another railcontact run"). flock locks die with
//   their process: a crashed or killed run leaves no stale lock.
// - Writers write into staging() = DIR/.staging-<pid>/ (path(name) = staging() / name).
// - commit() moves every staged entry into DIR (rename(2), atomic per file; SIGINT and SIGTERM
//   are blocked meanwhile, so Ctrl-C cannot stop it half-way) and removes the staging directory.
// - Destroyed without commit() (an exception), the staging directory is removed and DIR keeps
//   the outputs of the last complete run. A run stopped by SIGINT or SIGTERM says so on stderr and
//   leaves its staging directory; the next run in DIR removes it and reports it (stale_note()).
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

#include "railcontact/error.hpp"

namespace railcontact::output {

// A path inside a staging directory (DIR/.staging-<pid>/name) as the user knows it (DIR/name);
// any other path as it is. Messages name the file the user asked for, not the staged one.
std::filesystem::path named_for_user(const std::filesystem::path& path);

// Error(io) "cannot write FILE: REASON" for a file that could not be written: FILE named_for_user,
// REASON strerror(error), the errno of the failed call ("No space left on device"); error 0 (a
// stream that failed without one) gives "the write failed".
Error write_error(const std::filesystem::path& path, int error);

// A file opened for writing, or Error(io) (write_error) when it cannot be.
std::ofstream open_output_file(const std::filesystem::path& path);

class OutputDirectory {
 public:
  // log (optional) receives the note about removed unfinished outputs of an interrupted run.
  explicit OutputDirectory(std::filesystem::path directory, std::ostream* log = nullptr);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;
  OutputDirectory(OutputDirectory&&) = delete;
  OutputDirectory& operator=(OutputDirectory&&) = delete;

  [[nodiscard]] const std::filesystem::path& directory() const { return directory_; }
  [[nodiscard]] const std::filesystem::path& staging() const { return staging_; }
  [[nodiscard]] std::filesystem::path path(const std::string& name) const { return staging_ / name; }
  // "note: removed the unfinished outputs of an interrupted run in ...", or empty.
  [[nodiscard]] const std::string& stale_note() const { return stale_note_; }

  // Moves the staged outputs into the directory. Throws Error(io) when a rename fails.
  void commit();
  [[nodiscard]] bool committed() const { return committed_; }

 private:
  std::filesystem::path directory_;
  std::filesystem::path staging_;
  std::string stale_note_;
  int lock_fd_ = -1;
  bool committed_ = false;
  bool handlers_installed_ = false;
};

}  // namespace railcontact::output
