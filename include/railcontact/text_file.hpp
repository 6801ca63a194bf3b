#pragma once
// Stage: support. Reading text input files safely: a regular file of bounded size, UTF-8
// validation, and file content quoted in error messages without raw control bytes
// (docs/RELIABILITY.md "Input files").
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace railcontact {

// Text input files (src/support/text_file.cpp), shared by every reader of the library and the
// applications (profiles, case files, flexibility tables, wheel–rail set-ups).
//
// read_text_file: the bytes of a regular file of at most max_bytes, refused before anything is
// read otherwise. `what` names the input in the messages ("profile", "case file", ...). Throws
// Error(io) "cannot read the <what> <path>: ..." for a missing or unopenable file, a directory, a
// device, FIFO or socket (which could block or never end), and Error(invalid_input) "the <what>
// <path> is too large: ..." for a file larger than max_bytes (size and limit in the message).
std::string read_text_file(const std::filesystem::path& path, std::string_view what, std::uintmax_t max_bytes);

// Length of the longest prefix of `bytes` that is well-formed UTF-8 (RFC 3629: no overlong forms,
// surrogates or code points above U+10FFFF): bytes.size() when all of it is.
std::size_t valid_utf8_prefix(std::string_view bytes);

// File content quoted in an error message: printable characters as they are, control characters,
// invisible format characters (bidirectional overrides, zero-width) and bytes that are not UTF-8
// escaped (\xNN, \uNNNN), and at most max_characters characters, then "…".
std::string printable_excerpt(std::string_view text, std::size_t max_characters = 60);

}  // namespace railcontact
