// Content fingerprints of files: 64-bit FNV-1a over the bytes.
#include "support/file_fingerprint.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iterator>

#include "railcontact/error.hpp"

namespace railcontact {

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : bytes) {
    hash ^= static_cast<std::uint8_t>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

std::string fnv1a64_hex(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

std::uint64_t parse_fnv1a64_hex(std::string_view hex) {
  require(hex.size() == 16,
          [&] { return fmt::format("'{}' is not a 64-bit FNV-1a hash (16 hexadecimal digits)", hex); });
  std::uint64_t value = 0;
  for (const char c : hex) {
    int digit = -1;
    if (c >= '0' && c <= '9') digit = c - '0';
    else if (c >= 'a' && c <= 'f') digit = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F') digit = c - 'A' + 10;
    require(digit >= 0, [&] { return fmt::format("'{}' is not a 64-bit FNV-1a hash (16 hexadecimal digits)", hex); });
    value = value << 4 | static_cast<std::uint64_t>(digit);
  }
  return value;
}

std::uint64_t file_fnv1a64(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(ErrorKind::io, fmt::format("cannot read {} to fingerprint it", path.string()));
  const std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (file.bad()) throw Error(ErrorKind::io, fmt::format("cannot read {} to fingerprint it", path.string()));
  return fnv1a64(bytes);
}

}  // namespace railcontact
