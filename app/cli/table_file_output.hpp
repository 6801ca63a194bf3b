#pragma once
// Writing a table file (flexibility table, wheelset table) safely: the output is checked before
// the work, and written to a temporary file next to it that is renamed into place, so an
// interrupted or failed write leaves the previous file (or none), never a truncated one.
#include <filesystem>
#include <functional>
#include <string>

namespace railcontact::cli {

// Throws Error (io) naming `what` (e.g. "flexibility table") unless a file can be created in the
// directory of `out` and `out` is not a directory.
void check_table_writable(const std::filesystem::path& out, const std::string& what);

// Calls write(temporary path), then renames the temporary file over `out` with the mode of a new
// file. Throws Error (io) naming `what`; the temporary file is removed on every failure.
void write_table_atomically(const std::filesystem::path& out, const std::string& what,
                            const std::function<void(const std::filesystem::path&)>& write);

// The table's created_utc from the environment's SOURCE_DATE_EPOCH (seconds since 1970, the
// reproducible-builds convention), e.g. "2024-05-01T12:00:00Z"; empty (the build's time) when it is
// not set. Throws Error (invalid_input) naming the value unless it is a whole number >= 0.
std::string source_date_epoch_utc();

}  // namespace railcontact::cli
