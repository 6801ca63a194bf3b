#pragma once
// Strict reading of JSON files (the flexibility and wheelset tables): JSON parsed with the line of a
// syntax error, objects read key by key with the key's full path in every message, unknown keys
// refused. What the table files share beyond it: flexibility_table/table_json.hpp.
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>


namespace railcontact::detail {

// A JSON value quoted in a message: a number, string, boolean or null as written, a list or an
// object by its kind only (dump() recurses once per level of nesting: a value nested a million
// levels deep, which the parser accepts, overflowed the stack).
std::string quoted_json_value(const nlohmann::json& value);

// Parses text; throws Error("<kind> SOURCE:LINE: malformed JSON …") and refuses numbers beyond the
// range of a double.
nlohmann::json parse_strict_json(const std::string& text, const std::string& source, const std::string& kind);

// Strict access to one JSON object: typed getters naming the key, and a check for unknown keys.
// Messages read "<kind> SOURCE: <what>", e.g. "flexibility table t.json: missing key 'nodes[3].y_m'".
class StrictJsonReader {
 public:
  StrictJsonReader(const nlohmann::json& object, std::string path, const std::string& source, std::string kind);

  [[noreturn]] void fail(const std::string& what) const;
  const nlohmann::json& get(const std::string& key);
  [[nodiscard]] bool has(const std::string& key) const { return object_.is_object() && object_.contains(key); }
  double number(const std::string& key);  // finite
  std::string string(const std::string& key);
  std::size_t count(const std::string& key);  // a non-negative whole number
  std::vector<double> numbers(const std::string& key);
  const nlohmann::json& array(const std::string& key);
  [[nodiscard]] std::string qualified(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] const std::string& kind() const { return kind_; }
  // A reader of the object under `key` (or a list item), with the same source and kind.
  [[nodiscard]] StrictJsonReader child(const std::string& key);
  [[nodiscard]] StrictJsonReader item(const nlohmann::json& value, const std::string& path) const;
  void finish() const;  // throws for a key that was not read

 private:
  const nlohmann::json& object_;
  std::string path_;
  const std::string& source_;
  std::string kind_;
  std::set<std::string> used_;
};

// The time now as ISO 8601 UTC, e.g. 2024-05-01T12:00:00Z (a table's created_utc).
std::string utc_now();

}  // namespace railcontact::detail
