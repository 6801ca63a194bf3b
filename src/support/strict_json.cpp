// Strict reading of the table files (strict_json.hpp).
#include "support/strict_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact::detail {

using nlohmann::json;

std::string quoted_json_value(const json& value) {
  if (value.is_structured()) return value.is_array() ? "a list" : "an object";
  return printable_excerpt(value.dump());
}

json parse_strict_json(const std::string& text, const std::string& source, const std::string& kind) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    const std::size_t end = std::min<std::size_t>(e.byte, text.size());
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(end), '\n');
    throw Error(fmt::format("{} {}:{}: malformed JSON (is it a {}?)", kind, source, line, kind));
  } catch (const json::exception& e) {
    // A number beyond the range of a double (1e999) is not a parse_error but out_of_range.406
    // ("number overflow parsing '1e999'"): no value of a table may be infinite.
    const std::string what = e.what();
    const std::size_t bracket = what.find("] ");
    throw Error(fmt::format("{} {}: malformed JSON: {} (a number beyond ±1.8e308 is not finite)", kind, source,
                            printable_excerpt(bracket == std::string::npos ? what : what.substr(bracket + 2))));
  }
}

StrictJsonReader::StrictJsonReader(const json& object, std::string path, const std::string& source, std::string kind)
    : object_(object), path_(std::move(path)), source_(source), kind_(std::move(kind)) {
  if (!object_.is_object()) fail(fmt::format("{} must be an object", path_.empty() ? "the file" : path_));
}

void StrictJsonReader::fail(const std::string& what) const { throw Error(fmt::format("{} {}: {}", kind_, source_, what)); }

const json& StrictJsonReader::get(const std::string& key) {
  used_.insert(key);
  const auto it = object_.find(key);
  if (it == object_.end()) fail(fmt::format("missing key '{}'", qualified(key)));
  return *it;
}

double StrictJsonReader::number(const std::string& key) {
  const json& v = get(key);
  if (!v.is_number()) fail(fmt::format("{} must be a number", qualified(key)));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(fmt::format("{} must be finite", qualified(key)));
  return x;
}

std::string StrictJsonReader::string(const std::string& key) {
  const json& v = get(key);
  if (!v.is_string()) fail(fmt::format("{} must be a string", qualified(key)));
  return v.get<std::string>();
}

std::size_t StrictJsonReader::count(const std::string& key) {
  const json& v = get(key);
  if (!v.is_number_unsigned()) fail(fmt::format("{} must be a non-negative whole number", qualified(key)));
  return v.get<std::size_t>();
}

std::vector<double> StrictJsonReader::numbers(const std::string& key) {
  const json& v = get(key);
  if (!v.is_array()) fail(fmt::format("{} must be a list of numbers", qualified(key)));
  std::vector<double> values;
  values.reserve(v.size());
  for (const json& item : v) {
    if (!item.is_number()) fail(fmt::format("{} must be a list of numbers", qualified(key)));
    values.push_back(item.get<double>());
  }
  return values;
}

const json& StrictJsonReader::array(const std::string& key) {
  const json& v = get(key);
  if (!v.is_array()) fail(fmt::format("{} must be a list", qualified(key)));
  return v;
}

StrictJsonReader StrictJsonReader::child(const std::string& key) {
  const json& v = get(key);
  return StrictJsonReader(v, qualified(key), source_, kind_);
}

StrictJsonReader StrictJsonReader::item(const json& value, const std::string& path) const {
  return StrictJsonReader(value, path, source_, kind_);
}

void StrictJsonReader::finish() const {
  for (const auto& item : object_.items())
    if (!used_.contains(item.key())) fail(fmt::format("unknown key '{}'", printable_excerpt(qualified(item.key()))));
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace railcontact::detail
