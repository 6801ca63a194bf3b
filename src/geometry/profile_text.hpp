#pragma once
// Helpers shared by the profile readers: reading a file as numbered lines, parsing numbers,
// and uniform error messages "profile <file>:<line>: ...".
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace railcontact::geometry {

struct NumberedLine {
  std::size_t number = 0;  // 1-based
  std::string text;        // without the line terminator (\n, \r\n)
};

// All lines of a text file. Throws Error("profile <file>: cannot open ...") if unreadable.
std::vector<NumberedLine> read_lines(const std::filesystem::path& path);

// Error message prefix and exceptions naming the file (and line).
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message);
[[noreturn]] void fail(const std::filesystem::path& path, std::size_t line, const std::string& message);

// Removes everything from the first occurrence of any of the characters in comment_chars.
std::string_view strip_comment(std::string_view text, std::string_view comment_chars);
std::string_view trim(std::string_view text);

// Splits at blanks, tabs and commas and parses every field as a floating-point number; returns
// nothing if any field is not a (finite) number.
std::optional<std::vector<double>> parse_numbers(std::string_view text);

// One number (the whole string, trimmed); nothing if malformed.
std::optional<double> parse_number(std::string_view text);

std::string lower_case(std::string_view text);

}  // namespace railcontact::geometry
