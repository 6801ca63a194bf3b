#include "geometry/profile_text.hpp"

#include <fmt/core.h>

#include <cctype>
#include <charconv>
#include <cmath>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact::geometry {

std::vector<NumberedLine> split_lines(std::string_view bytes) {
  std::vector<NumberedLine> lines;
  std::size_t number = 0, begin = 0;
  while (begin < bytes.size()) {
    std::size_t end = bytes.find('\n', begin);
    if (end == std::string::npos) end = bytes.size();
    std::string text(bytes.substr(begin, end - begin));
    if (!text.empty() && text.back() == '\r') text.pop_back();
    lines.push_back({++number, std::move(text)});
    begin = end + 1;
  }
  return lines;
}

std::string quoted(std::string_view text) { return printable_excerpt(text); }

void fail(const std::filesystem::path& path, const std::string& message) {
  throw Error(fmt::format("profile {}: {}", path.string(), message));
}

void fail(const std::filesystem::path& path, std::size_t line, const std::string& message) {
  throw Error(fmt::format("profile {}:{}: {}", path.string(), line, message));
}

std::string_view strip_comment(std::string_view text, std::string_view comment_chars) {
  const auto pos = text.find_first_of(comment_chars);
  return pos == std::string_view::npos ? text : text.substr(0, pos);
}

std::string_view trim(std::string_view text) {
  const auto is_blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; };
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

std::optional<double> parse_number(std::string_view text) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<std::vector<double>> parse_numbers(std::string_view text) {
  std::vector<double> values;
  std::size_t pos = 0;
  const auto is_separator = [](char c) { return c == ' ' || c == '\t' || c == ',' || c == ';'; };
  while (pos < text.size()) {
    while (pos < text.size() && is_separator(text[pos])) ++pos;
    if (pos >= text.size()) break;
    std::size_t end = pos;
    while (end < text.size() && !is_separator(text[end])) ++end;
    const auto value = parse_number(text.substr(pos, end - pos));
    if (!value) return std::nullopt;
    values.push_back(*value);
    pos = end;
  }
  return values;
}

void refuse_decimal_commas(const std::filesystem::path& path, std::size_t line, std::string_view text) {
  if (text.find('.') != std::string_view::npos) return;
  const auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
  const auto is_separator = [](char c) { return c == ' ' || c == '\t' || c == ';'; };
  std::size_t fields = 0;
  std::string_view decimal;  // the first field with a comma between digits
  std::size_t pos = 0;
  while (pos < text.size()) {
    while (pos < text.size() && is_separator(text[pos])) ++pos;
    if (pos >= text.size()) break;
    std::size_t end = pos;
    while (end < text.size() && !is_separator(text[end])) ++end;
    const std::string_view field = text.substr(pos, end - pos);
    ++fields;
    for (std::size_t k = 1; decimal.empty() && k + 1 < field.size(); ++k)
      if (field[k] == ',' && is_digit(field[k - 1]) && is_digit(field[k + 1])) decimal = field;
    pos = end;
  }
  if (fields < 2 || decimal.empty()) return;
  std::string dotted(decimal);
  for (char& c : dotted) c = c == ',' ? '.' : c;
  fail(path, line,
       fmt::format("'{}' is written with decimal commas ({}); write the numbers with decimal points ({}): blanks, "
                   "tabs, commas and semicolons separate numbers",
                   printable_excerpt(text), printable_excerpt(decimal), printable_excerpt(dotted)));
}

std::string lower_case(std::string_view text) {
  std::string result(text);
  for (char& c : result) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return result;
}

}  // namespace railcontact::geometry
