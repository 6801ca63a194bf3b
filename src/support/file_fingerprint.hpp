#pragma once
// Content fingerprints of input files (e.g. the profile files a flexibility table was built
// from): the file name as given and the 64-bit FNV-1a hash of its bytes. The hash identifies the
// content, not the name: a copied or moved file keeps its fingerprint, an edited one does not.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace railcontact {

// 64-bit FNV-1a (offset basis 0xcbf29ce484222325, prime 0x100000001b3) of the bytes.
std::uint64_t fnv1a64(std::string_view bytes);

// The hash as 16 lower-case hexadecimal digits, and back (throws Error unless 16 hex digits).
std::string fnv1a64_hex(std::uint64_t hash);
std::uint64_t parse_fnv1a64_hex(std::string_view hex);

// FNV-1a 64 of a file's bytes. Throws Error("cannot read … to fingerprint it") when it cannot.
std::uint64_t file_fnv1a64(const std::filesystem::path& path);

}  // namespace railcontact
