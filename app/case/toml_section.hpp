#pragma once
// Typed, checked access to the sections of a TOML input file (case files, wheelset cases): every
// error names the file, the line and the key; keys nobody asked for are refused (docs/CASE_FILES.md).
#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact {

inline std::string where(const std::string& source, const toml::source_region& region) {
  return fmt::format("{}:{}", source, region.begin.line);
}

// One [section] of the case file: typed access, and a check that no unknown key is left.
class Section {
 public:
  Section(const toml::table& table, std::string name, const std::string& source)
      : table_(table), name_(std::move(name)), source_(source) {}

  [[nodiscard]] bool has(const std::string& key) const { return table_.contains(key); }

  std::optional<double> optional_number(const std::string& key) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (node == nullptr) return std::nullopt;
    double value;
    if (const auto* i = node->as_integer()) value = static_cast<double>(i->get());
    else if (const auto* f = node->as_floating_point()) value = f->get();
    else throw Error(fmt::format("{}: [{}] {} must be a number", where(source_, node->source()), name_, key));
    if (!std::isfinite(value))
      throw Error(fmt::format("{}: [{}] {} must be a finite number (got {})", where(source_, node->source()), name_, key, value));
    return value;
  }

  double number(const std::string& key) {
    const std::optional<double> value = optional_number(key);
    if (!value) throw Error(fmt::format("{}: [{}] is missing the key '{}'", where(source_, table_.source()), name_, key));
    return *value;
  }

  double positive(const std::string& key) {
    const double value = number(key);
    check_positive(key, value);
    return value;
  }

  std::optional<double> optional_positive(const std::string& key) {
    const std::optional<double> value = optional_number(key);
    if (value) check_positive(key, *value);
    return value;
  }

  std::optional<std::string> optional_string(const std::string& key) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (node == nullptr) return std::nullopt;
    const auto* s = node->as_string();
    if (s == nullptr) throw Error(fmt::format("{}: [{}] {} must be a string", where(source_, node->source()), name_, key));
    return s->get();
  }

  [[nodiscard]] const toml::node* node(const std::string& key) {
    used_.insert(key);
    return table_.get(key);
  }

  [[nodiscard]] std::string location(const std::string& key) const {
    const toml::node* n = table_.get(key);
    return where(source_, n != nullptr ? n->source() : table_.source());
  }

  // "file:line" of a node of this section.
  [[nodiscard]] std::string location_of(const toml::node& n) const { return where(source_, n.source()); }

  [[nodiscard]] const std::string& source() const { return source_; }

  // Throws on the first key that was never asked for.
  void finish() const {
    for (const auto& [key, node] : table_) {
      if (!used_.contains(std::string(key.str())))
        throw Error(fmt::format("{}: unknown key '{}' in [{}]", where(source_, node.source()), printable_excerpt(key.str()), name_));
    }
  }

 private:
  void check_positive(const std::string& key, double value) const {
    if (!(value > 0))
      throw Error(fmt::format("{}: [{}] {} must be positive (got {})", location(key), name_, key, value));
  }
  const toml::table& table_;
  std::string name_;
  const std::string& source_;
  std::set<std::string> used_;
};

inline const toml::table& section_table(const toml::table& root, const std::string& name, const std::string& source,
                                 bool required, const toml::table& empty) {
  const toml::node* node = root.get(name);
  if (node == nullptr) {
    if (required) throw Error(fmt::format("{}: missing section [{}]", source, name));
    return empty;
  }
  const toml::table* table = node->as_table();
  if (table == nullptr) throw Error(fmt::format("{}: {} must be a section [{}]", where(source, node->source()), name, name));
  return *table;
}

// The text must be UTF-8 (TOML requires it): toml++ 3.3.0, Debian 12's, has undefined behaviour
// on some invalid UTF-8 (e.g. "x=1\xA7", a Latin-1 section sign), fixed upstream after 3.3.0; the
// bytes are therefore checked before toml++ sees them. The error names the line and column
// (characters, 1-based) of the first bad byte.
inline void check_utf8(std::string_view text, const std::string& source) {
  const std::size_t bad = valid_utf8_prefix(text);
  if (bad == text.size()) return;
  const std::string_view before = text.substr(0, bad);
  const std::size_t line_start = before.rfind('\n') == std::string_view::npos ? 0 : before.rfind('\n') + 1;
  const auto line = 1 + std::count(before.begin(), before.end(), '\n');
  // Characters (not continuation bytes) before the bad byte on its line: the prefix is valid UTF-8.
  const auto column = 1 + std::count_if(before.begin() + static_cast<std::ptrdiff_t>(line_start), before.end(),
                                         [](char c) { return (static_cast<unsigned char>(c) & 0xC0u) != 0x80u; });
  throw Error(fmt::format("{}:{}: the byte 0x{:02X} at column {} is not UTF-8; a case file must be UTF-8 text (save "
                          "it as UTF-8, not Latin-1 or another legacy encoding)",
                          source, line, static_cast<unsigned char>(text[bad]), column));
}

// The whole text as TOML (UTF-8 checked first), with only the given sections at the top level.
inline toml::table parse_toml_sections(std::string_view text, const std::string& source,
                                       const std::set<std::string>& sections) {
  check_utf8(text, source);
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}:{}: malformed TOML: {}", source, e.source().begin.line,
                            printable_excerpt(e.description(), 200)));
  }
  for (const auto& [key, node] : root)
    if (!sections.contains(std::string(key.str())))
      throw Error(fmt::format("{}: unknown section or key '{}'", where(source, node.source()), printable_excerpt(key.str())));
  return root;
}

}  // namespace railcontact
