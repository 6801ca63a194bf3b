// Text input files (railcontact/error.hpp): one bounded, checked reader for every file the library
// and the applications read, UTF-8 validation, and the quoting of file content in messages.
//
// The UTF-8 decoder is our own (about 30 lines): none of the libraries railcontact uses from
// Debian (fmt, nlohmann/json, toml++, Boost headers, Eigen) exposes a validator that reports the
// position of the first bad byte (toml++ 3.3.0, the one that needs the guard, misbehaves on it).
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <system_error>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact {
namespace {

// One code point decoded at the start of `bytes`: its value and length, or nothing when the
// bytes there are not well-formed UTF-8 (RFC 3629, Table 3-7 of the Unicode standard).
struct CodePoint {
  char32_t value = 0;
  std::size_t length = 0;
};

std::optional<CodePoint> decode_utf8(std::string_view bytes) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(bytes[i]); };
  const unsigned char lead = byte(0);
  if (lead < 0x80) return CodePoint{lead, 1};
  std::size_t length = 0;
  char32_t value = 0;
  char32_t minimum = 0;  // the smallest value of this length: shorter forms are overlong
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2, value = lead & 0x1Fu, minimum = 0x80;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3, value = lead & 0x0Fu, minimum = 0x800;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4, value = lead & 0x07u, minimum = 0x10000;
  } else {
    return std::nullopt;  // a continuation byte, C0/C1 (overlong 2-byte leads) or F5..FF
  }
  if (bytes.size() < length) return std::nullopt;
  for (std::size_t i = 1; i < length; ++i) {
    if ((byte(i) & 0xC0u) != 0x80u) return std::nullopt;
    value = value << 6 | (byte(i) & 0x3Fu);
  }
  if (value < minimum || value > 0x10FFFF || (value >= 0xD800 && value <= 0xDFFF)) return std::nullopt;
  return CodePoint{value, length};
}

// Characters that would garble or hide parts of a one-line message on a terminal.
bool needs_escape(char32_t c) {
  return c < 0x20 || c == 0x7F || (c >= 0x80 && c <= 0x9F) ||  // C0, DEL, C1 controls
         (c >= 0x200B && c <= 0x200F) ||                       // zero-width, LRM, RLM
         (c >= 0x2028 && c <= 0x202E) ||                       // line/paragraph separators, bidi embeddings
         (c >= 0x2066 && c <= 0x2069) ||                       // bidi isolates
         c == 0xFEFF;                                          // zero-width no-break space (BOM)
}

std::string mebibytes(std::uintmax_t bytes) {
  return bytes % (1024 * 1024) == 0 ? fmt::format("{} MiB", bytes / (1024 * 1024))
                                    : fmt::format("{:.1f} MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
}

std::string file_type_name(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::directory: return "it is a directory, not a file";
    case std::filesystem::file_type::character: return "it is a character device, not a regular file";
    case std::filesystem::file_type::block: return "it is a block device, not a regular file";
    case std::filesystem::file_type::fifo: return "it is a FIFO (named pipe), not a regular file";
    case std::filesystem::file_type::socket: return "it is a socket, not a regular file";
    default: return "it is not a regular file";
  }
}

}  // namespace

std::string read_text_file(const std::filesystem::path& path, std::string_view what, std::uintmax_t max_bytes) {
  const auto cannot = [&](const std::string& why) {
    return Error(ErrorKind::io, fmt::format("cannot read the {} {}: {}", what, path.string(), why));
  };
  // Refused before opening: opening a FIFO blocks, reading /dev/zero never ends.
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found)
    throw cannot("cannot open it (no such file or directory)");
  if (ec) throw cannot(fmt::format("cannot open it ({})", ec.message()));
  if (status.type() != std::filesystem::file_type::regular) throw cannot(file_type_name(status.type()));
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw cannot(fmt::format("cannot open it ({})", ec.message()));
  if (size > max_bytes)
    throw Error(ErrorKind::invalid_input,
                fmt::format("the {} {} is too large: {} bytes ({}); at most {} bytes ({}) are read", what,
                            path.string(), size, mebibytes(size), max_bytes, mebibytes(max_bytes)));

  std::ifstream file(path, std::ios::binary);
  if (!file) throw cannot(fmt::format("cannot open it ({})", std::strerror(errno)));
  // At most max_bytes + 1 bytes, even if the file grows while it is read.
  std::string bytes(static_cast<std::size_t>(size) + 1, '\0');
  file.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (file.bad()) throw cannot("read error");
  bytes.resize(static_cast<std::size_t>(file.gcount()));
  if (bytes.size() > max_bytes)
    throw Error(ErrorKind::invalid_input, fmt::format("the {} {} is too large: more than {} bytes ({}) while it was read",
                                                      what, path.string(), max_bytes, mebibytes(max_bytes)));
  return bytes;
}

std::size_t valid_utf8_prefix(std::string_view bytes) {
  std::size_t pos = 0;
  while (pos < bytes.size()) {
    const auto c = decode_utf8(bytes.substr(pos));
    if (!c) return pos;
    pos += c->length;
  }
  return pos;
}

std::string printable_excerpt(std::string_view text, std::size_t max_characters) {
  std::string out;
  std::size_t characters = 0, pos = 0;
  while (pos < text.size()) {
    if (characters == max_characters) return out + "…";
    const auto c = decode_utf8(text.substr(pos));
    if (!c) {
      out += fmt::format("\\x{:02X}", static_cast<unsigned char>(text[pos]));
      pos += 1;
    } else {
      if (needs_escape(c->value)) {
        out += c->value < 0x80 ? fmt::format("\\x{:02X}", static_cast<unsigned>(c->value))
                                : fmt::format("\\u{:04X}", static_cast<unsigned>(c->value));
      } else {
        out.append(text.substr(pos, c->length));
      }
      pos += c->length;
    }
    ++characters;
  }
  return out;
}

}  // namespace railcontact
