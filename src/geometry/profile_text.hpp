#pragma once
// Helpers shared by the profile readers: reading a file as numbered lines, parsing numbers,
// and uniform error messages "profile <file>:<line>: ...".
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "railcontact/text_file.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact::geometry {

struct NumberedLine {
  std::size_t number = 0;  // 1-based
  std::string text;        // without the line terminator (\n, \r\n)
};

// The largest profile file read (read_text_file refuses larger ones before reading).
constexpr std::uintmax_t kMaxProfileFileBytes = 16u << 20;  // 16 MiB
// The lines of a file's text (\n or \r\n terminated), numbered from 1.
std::vector<NumberedLine> split_lines(std::string_view bytes);

// Error message prefix and exceptions naming the file (and line).
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message);
[[noreturn]] void fail(const std::filesystem::path& path, std::size_t line, const std::string& message);

// Removes everything from the first occurrence of any of the characters in comment_chars.
std::string_view strip_comment(std::string_view text, std::string_view comment_chars);
std::string_view trim(std::string_view text);

// Splits at blanks, tabs and commas and parses every field as a floating-point number; returns
// nothing if any field is not a (finite) number.
std::optional<std::vector<double>> parse_numbers(std::string_view text);

// Refuses a point line written with decimal commas ("0,5 1,25", "12,5;3,4": no decimal point, and
// fields separated by blanks, tabs or semicolons of which one holds a comma between digits), which
// parse_numbers would read as twice as many numbers: fail(path, line, ...) quoting the line. A
// single field "12,5" is a comma-separated pair and passes.
void refuse_decimal_commas(const std::filesystem::path& path, std::size_t line, std::string_view text);

// One number (the whole string, trimmed); nothing if malformed.
std::optional<double> parse_number(std::string_view text);

std::string lower_case(std::string_view text);

// File content for a message: escaped and shortened (printable_excerpt, railcontact/error.hpp).
std::string quoted(std::string_view text);

// The checks of validate (railcontact/geometry.hpp, ProfileLimits), all of them or those of the
// point list as read (the readers; read_profile curates and then checks all); a wrong extent adds
// unit_hint, the reader's statement of the length unit it applied (e.g. "units.len.f = 1 at
// line 37: the numbers are read as metres").
// What check_profile checks: the point list as read (count, finite, extent, gaps, length,
// crossings), or that and the shape the contact search needs (no turn back, no undercut), which the
// curation (curated) may repair in between.
enum class ProfileCheckScope { points, all };
// The cosine of the turn of the point list at interior point i (1 where a segment is empty).
double turn_cosine(const Profile& profile, std::size_t i);
// The largest lateral retreat of the points: max over j < i of (y_j − y_i), direction-adjusted
// (the first point to the last); positive where the profile is undercut.
double largest_lateral_retreat_m(const Profile& profile);
void check_profile(const Profile& profile, std::string_view unit_hint, ProfileCheckScope scope = ProfileCheckScope::all);
// "the numbers are read as millimetres" (1e-3), "... as metres" (1), "... in units of X m".
std::string length_unit_hint(double length_unit_m);

// The readers of railcontact/geometry.hpp from a file's text (read_*_profile = read_text_file,
// then parse_*_profile): `path` names the file in messages, and its extension gives a MiniProf
// profile's kind (.ban rail, .whl wheel). The same checks and errors as the file readers; used by
// the fuzz targets (fuzz/).
Profile parse_simpack_profile(std::string_view text, const std::filesystem::path& path);
Profile parse_miniprof_profile(std::string_view text, const std::filesystem::path& path, bool auto_vertical = true);
Profile parse_text_profile(std::string_view text, const std::filesystem::path& path, double length_unit_m = 1e-3);

}  // namespace railcontact::geometry
