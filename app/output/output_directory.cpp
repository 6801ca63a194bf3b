#include "output/output_directory.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "railcontact/error.hpp"

namespace railcontact::output {
namespace {

constexpr const char* kLockFile = ".railcontact.lock";
constexpr const char* kStagingPrefix = ".staging-";

// What a SIGINT or SIGTERM handler says while an output directory is staged: formatted in
// advance (a handler may only call async-signal-safe functions such as write(2)).
char g_interrupt_message[2048];
std::size_t g_interrupt_message_length = 0;
struct sigaction g_previous_sigint {};
struct sigaction g_previous_sigterm {};
bool g_handlers_installed = false;

extern "C" void on_interrupt(int signal_number) {
  if (g_interrupt_message_length > 0) {
    const ssize_t ignored = ::write(STDERR_FILENO, g_interrupt_message, g_interrupt_message_length);
    (void)ignored;
  }
  // SA_RESETHAND restored the default action: die of the signal as without the handler.
  ::raise(signal_number);
}

bool install_handlers(const std::filesystem::path& directory) {
  if (g_handlers_installed) return false;
  const std::string message = fmt::format(
      "\nrailcontact: interrupted; the outputs in {} are unchanged (those of the last complete run, if any); the next "
      "run in it removes the unfinished ones\n",
      directory.string());
  g_interrupt_message_length = std::min(message.size(), sizeof g_interrupt_message);
  std::memcpy(g_interrupt_message, message.data(), g_interrupt_message_length);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  // A signal the caller ignores (e.g. a background job under a non-interactive shell) stays ignored.
  struct sigaction current {};
  sigaction(SIGINT, nullptr, &current);
  g_previous_sigint = current;
  if (current.sa_handler != SIG_IGN) sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, nullptr, &current);
  g_previous_sigterm = current;
  if (current.sa_handler != SIG_IGN) sigaction(SIGTERM, &action, nullptr);
  g_handlers_installed = true;
  return true;
}

void restore_handlers() {
  if (!g_handlers_installed) return;
  sigaction(SIGINT, &g_previous_sigint, nullptr);
  sigaction(SIGTERM, &g_previous_sigterm, nullptr);
  g_interrupt_message_length = 0;
  g_handlers_installed = false;
}

// Blocks SIGINT and SIGTERM for its lifetime (this thread; commit() runs on the caller's thread
// after the work is done).
class BlockInterrupts {
 public:
  BlockInterrupts() {
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &block, &previous_);
  }
  ~BlockInterrupts() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  BlockInterrupts(const BlockInterrupts&) = delete;
  BlockInterrupts& operator=(const BlockInterrupts&) = delete;

 private:
  sigset_t previous_{};
};

}  // namespace

std::filesystem::path named_for_user(const std::filesystem::path& path) {
  std::filesystem::path named;
  for (const std::filesystem::path& part : path)
    if (part.string().rfind(kStagingPrefix, 0) != 0) named /= part;
  return named;
}

Error write_error(const std::filesystem::path& path, int error) {
  return Error(ErrorKind::io, fmt::format("cannot write {}: {}", named_for_user(path).string(),
                                          error != 0 ? std::strerror(error) : "the write failed"));
}

std::ofstream open_output_file(const std::filesystem::path& path) {
  std::ofstream f(path);
  if (!f) throw write_error(path, errno);
  return f;
}

OutputDirectory::OutputDirectory(std::filesystem::path directory, std::ostream* log) : directory_(std::move(directory)) {
  if (directory_.empty()) directory_ = ".";
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec || !std::filesystem::is_directory(directory_))
    throw Error(ErrorKind::io, fmt::format("cannot create the output directory {}{}", directory_.string(),
                                           ec ? ": " + ec.message() : std::string(": not a directory")));
  const std::filesystem::path lock = directory_ / kLockFile;
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0)
    throw Error(ErrorKind::io, fmt::format("cannot write in the output directory {}: {}", directory_.string(),
                                           std::strerror(errno)));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (error == EWOULDBLOCK)
      throw Error(ErrorKind::io,
                  fmt::format("output directory {} is in use by another railcontact run", directory_.string()));
    throw Error(ErrorKind::io,
                fmt::format("cannot lock the output directory {}: {}", directory_.string(), std::strerror(error)));
  }
  try {
    // We hold the lock: every staging directory is the remainder of an interrupted run.
    std::vector<std::filesystem::path> stale;
    for (const auto& entry : std::filesystem::directory_iterator(directory_))
      if (entry.path().filename().string().rfind(kStagingPrefix, 0) == 0 && entry.is_directory())
        stale.push_back(entry.path());
    std::sort(stale.begin(), stale.end());
    for (const std::filesystem::path& s : stale) {
      std::filesystem::remove_all(s);
      stale_note_ += fmt::format(
          "note: removed the unfinished outputs of an interrupted run in {}; the outputs in {} are those of the last "
          "complete run\n",
          s.string(), directory_.string());
    }
    staging_ = directory_ / (kStagingPrefix + std::to_string(::getpid()));
    std::filesystem::create_directory(staging_);
  } catch (const std::filesystem::filesystem_error& e) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw Error(ErrorKind::io, fmt::format("cannot prepare the output directory {}: {}", directory_.string(),
                                           e.code().message()));
  }
  if (log != nullptr && !stale_note_.empty()) *log << stale_note_;
  handlers_installed_ = install_handlers(directory_);
}

OutputDirectory::~OutputDirectory() {
  if (handlers_installed_) restore_handlers();
  if (!committed_ && !staging_.empty()) {
    std::error_code ignored;  // never throw from a destructor
    std::filesystem::remove_all(staging_, ignored);
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void OutputDirectory::commit() {
  if (committed_) return;
  const BlockInterrupts blocked;
  std::vector<std::filesystem::path> staged;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(staging_, ec)) staged.push_back(entry.path());
  if (ec)
    throw Error(ErrorKind::io, fmt::format("cannot read the staged outputs {}: {}", staging_.string(), ec.message()));
  std::sort(staged.begin(), staged.end());
  for (const std::filesystem::path& from : staged) {
    const std::filesystem::path to = directory_ / from.filename();
    if (std::filesystem::is_directory(from) && std::filesystem::is_directory(to)) std::filesystem::remove_all(to, ec);
    std::filesystem::rename(from, to, ec);
    if (ec)
      throw Error(ErrorKind::io, fmt::format("cannot move {} into the output directory {}: {} (its outputs may be "
                                             "incomplete)",
                                             from.filename().string(), directory_.string(), ec.message()));
  }
  std::filesystem::remove_all(staging_, ec);
  committed_ = true;
  if (handlers_installed_) {
    restore_handlers();
    handlers_installed_ = false;
  }
}

}  // namespace railcontact::output
