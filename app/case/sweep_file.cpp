// Sweep files (see the header).
#include "case/sweep_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "case/count_text.hpp"
#include "case/toml_section.hpp"
#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact {
namespace {

constexpr std::uintmax_t kMaxSweepFileBytes = 4u << 20;  // 4 MiB: room for a long [[case]] list
constexpr double kMaximumAxisValues = 100000;

bool is_sweep_key(const std::string& key) {
  return std::find_if(std::begin(kSweepKeys), std::end(kSweepKeys), [&](const char* k) { return key == k; }) !=
         std::end(kSweepKeys);
}

std::string allowed_keys() {
  std::string s;
  for (const char* k : kSweepKeys) s += (s.empty() ? "" : ", ") + std::string(k);
  return s;
}

double number_of(const toml::node& node, const std::string& what, const std::string& source) {
  double value;
  if (const auto* i = node.as_integer()) value = static_cast<double>(i->get());
  else if (const auto* f = node.as_floating_point()) value = f->get();
  else throw Error(fmt::format("{}: {} must be a number", where(source, node.source()), what));
  if (!std::isfinite(value))
    throw Error(fmt::format("{}: {} must be a finite number (got {})", where(source, node.source()), what, value));
  return value;
}

// A list [a, b, ...] or a range {from = , to = , step = } (to reached within 1e-9 of a step; from
// > to runs downwards).
std::vector<double> axis_values(const toml::node& node, const std::string& key, const std::string& source) {
  const std::string what = fmt::format("[grid] {}", key);
  std::vector<double> values;
  if (const toml::array* list = node.as_array()) {
    if (list->empty()) throw Error(fmt::format("{}: {} is an empty list; give at least one value", where(source, node.source()), what));
    if (static_cast<double>(list->size()) > kMaximumAxisValues)
      throw Error(fmt::format("{}: {} holds {} values; at most {:g}", where(source, node.source()), what, list->size(), kMaximumAxisValues));
    for (const toml::node& item : *list) values.push_back(number_of(item, what + " value", source));
    return values;
  }
  const toml::table* range = node.as_table();
  if (range == nullptr)
    throw Error(fmt::format("{}: {} must be a list of numbers [a, b, ...] or a range {{from = A, to = B, step = S}}",
                            where(source, node.source()), what));
  Section s(*range, "grid." + key, source);
  const double from = s.number("from");
  const double to = s.number("to");
  const double step = s.number("step");
  s.finish();
  if (!(step > 0))
    throw Error(fmt::format("{}: {} step = {} must be positive (from > to runs downwards)", s.location("step"), what, step));
  const double count = std::floor(std::abs(to - from) / step + 1e-9) + 1.0;
  if (count > kMaximumAxisValues)
    throw Error(fmt::format("{}: {} from {} to {} in steps of {} gives {} values; at most {:g}",
                            where(source, node.source()), what, from, to, step, count_text(count), kMaximumAxisValues));
  const double direction = to < from ? -1.0 : 1.0;
  for (int k = 0; k < static_cast<int>(count); ++k) {
    const double v = from + direction * k * step;
    values.push_back(std::abs(v) < 1e-12 * std::max(1.0, std::abs(step)) ? 0.0 : v);
  }
  return values;
}

void check_key(const std::string& key, const SweepFile& f, const toml::node& node, const std::string& section) {
  if (!is_sweep_key(key))
    throw Error(fmt::format("{}: unknown key '{}' in {} (allowed: {})", where(f.source, node.source()),
                            printable_excerpt(key), section, allowed_keys()));
  const bool by_load = f.base.options.loads.has_value();
  if (!by_load && (key == "wheel_load_N" || key == "right_wheel_N" || key == "left_wheel_N"))
    throw Error(fmt::format("{}: {} {} needs the wheelset by load, but the file gives the height ([position] z_mm "
                            "without [load])",
                            where(f.source, node.source()), section, key));
  if (by_load && key == "z_mm")
    throw Error(fmt::format("{}: {} z_mm needs the wheelset by position (give [position] z_mm and no [load]); by load "
                            "the height is solved",
                            where(f.source, node.source()), section));
  if (key == "extra_longitudinal_creepage" && !std::isnan(f.base.state.velocity.wheel_angular_velocity_rad_per_s))
    throw Error(fmt::format("{}: {} extra_longitudinal_creepage cannot be swept with [velocity] "
                            "wheel_angular_velocity_rad_per_s given",
                            where(f.source, node.source()), section));
}

// wheel_load_N sets both wheel loads: with right_wheel_N or left_wheel_N in the same table, one
// wheel's load would be given two ways.
void check_conflicting_keys(const toml::table& table, const std::string& source, const std::string& section) {
  if (!table.contains("wheel_load_N")) return;
  for (const char* key : {"right_wheel_N", "left_wheel_N"})
    if (const toml::node* node = table.get(key))
      throw Error(fmt::format("{}: {} wheel_load_N and {} both give the {} wheel's load (wheel_load_N: both wheels); "
                              "give one of them",
                              where(source, node->source()), section, key, key[0] == 'r' ? "right" : "left"));
}

void check_value(const std::string& key, double value, const std::string& location) {
  const bool positive = key == "mu" || key == "wheel_load_N" || key == "right_wheel_N" || key == "left_wheel_N" ||
                        key == "speed_m_per_s";
  if (positive && !(value > 0)) throw Error(fmt::format("{}: {} = {} must be positive", location, key, value));
}

void apply(SweepCase& c, const std::string& key, double v) {
  WheelsetPosition& p = c.state.position;
  WheelsetVelocity& w = c.state.velocity;
  if (key == "mu") c.friction_coefficient = v;
  else if (key == "wheel_load_N") c.loads->right_N = c.loads->left_N = v;
  else if (key == "right_wheel_N") c.loads->right_N = v;
  else if (key == "left_wheel_N") c.loads->left_N = v;
  else if (key == "speed_m_per_s") w.forward_speed_m_per_s = v;
  else if (key == "lateral_velocity_m_per_s") w.lateral_velocity_m_per_s = v;
  else if (key == "vertical_velocity_m_per_s") w.vertical_velocity_m_per_s = v;
  else if (key == "roll_rate_rad_per_s") w.roll_rate_rad_per_s = v;
  else if (key == "yaw_rate_rad_per_s") w.yaw_rate_rad_per_s = v;
  else if (key == "extra_longitudinal_creepage") w.extra_longitudinal_creepage = v;
  else if (key == "roll_mrad") p.roll_rad = v * 1e-3;
  else if (key == "z_mm") p.vertical_displacement_m = v * 1e-3;
  else if (key == "yaw_mrad") p.yaw_rad = v * 1e-3;
  else if (key == "y_mm") p.lateral_displacement_m = v * 1e-3;
}

std::size_t key_rank(const std::string& key) {
  return static_cast<std::size_t>(
      std::find_if(std::begin(kSweepKeys), std::end(kSweepKeys), [&](const char* k) { return key == k; }) -
      std::begin(kSweepKeys));
}

}  // namespace

std::size_t SweepFile::size() const {
  if (!grid) return list.size();
  std::size_t n = 1;
  for (const SweepAxis& a : axes) n *= a.values.size();
  return n;
}

SweepCase SweepFile::at(std::size_t k) const {
  SweepCase c;
  c.state = base.state;
  c.loads = base.options.loads;
  c.friction_coefficient = base.options.friction_coefficient;
  if (grid) {
    for (std::size_t a = axes.size(); a-- > 0;) {
      const std::size_t n = axes[a].values.size();
      apply(c, axes[a].key, axes[a].values[k % n]);
      k /= n;
    }
  } else {
    for (const auto& [key, value] : list.at(k)) apply(c, key, value);
  }
  return c;
}

std::vector<std::string> SweepFile::varied_keys() const {
  std::vector<std::string> keys;
  if (grid) {
    for (const SweepAxis& a : axes) keys.push_back(a.key);
    return keys;
  }
  for (const auto& entry : list)
    for (const auto& kv : entry)
      if (std::find(keys.begin(), keys.end(), kv.first) == keys.end()) keys.push_back(kv.first);
  std::sort(keys.begin(), keys.end(), [](const std::string& a, const std::string& b) { return key_rank(a) < key_rank(b); });
  return keys;
}

SweepFile parse_sweep_file(std::string_view text, const std::string& source, const std::filesystem::path& base_directory) {
  SweepFile f;
  f.source = source;
  f.text = std::string(text);
  toml::table root;
  f.base = parse_wheelset_case_with(text, source, base_directory, {"grid", "case"}, root);
  const toml::node* grid = root.get("grid");
  const toml::node* cases = root.get("case");
  if ((grid == nullptr) == (cases == nullptr))
    throw Error(fmt::format("{}: a sweep file gives either a [grid] (lists or ranges of state values) or a list of "
                            "[[case]] tables, {}",
                            source, grid == nullptr ? "and it gives neither" : "not both"));
  if (grid != nullptr) {
    const toml::table* table = grid->as_table();
    if (table == nullptr) throw Error(fmt::format("{}: grid must be a section [grid]", where(source, grid->source())));
    if (table->empty())
      throw Error(fmt::format("{}: [grid] holds no axis; give at least one key ({}) with a list or a range",
                              where(source, grid->source()), allowed_keys()));
    for (const auto& [key, node] : *table) check_key(std::string(key.str()), f, node, "[grid]");
    check_conflicting_keys(*table, source, "[grid]");
    double product = 1;
    std::string sizes;
    for (const char* key : kSweepKeys) {
      const toml::node* node = table->get(key);
      if (node == nullptr) continue;
      SweepAxis axis{key, axis_values(*node, key, source)};
      for (double v : axis.values) check_value(key, v, where(source, node->source()));
      product *= static_cast<double>(axis.values.size());
      sizes += fmt::format("{}{} {}", sizes.empty() ? "" : " × ", key, axis.values.size());
      f.axes.push_back(std::move(axis));
    }
    if (product > kMaximumSweepCases)
      throw Error(fmt::format("{}: the grid holds {} cases ({}); a sweep may hold at most {:.0f} (split it into "
                              "several sweep files or use coarser steps)",
                              where(source, grid->source()), count_text(product), sizes, kMaximumSweepCases));
    f.grid = true;
  } else {
    const toml::array* list = cases->as_array();
    if (list == nullptr || !list->is_array_of_tables())
      throw Error(fmt::format("{}: case must be a list of [[case]] tables", where(source, cases->source())));
    if (list->empty()) throw Error(fmt::format("{}: the [[case]] list is empty", where(source, cases->source())));
    if (static_cast<double>(list->size()) > kMaximumSweepCases)
      throw Error(fmt::format("{}: {} cases; a sweep may hold at most {:.0f}", source, list->size(), kMaximumSweepCases));
    for (const toml::node& item : *list) {
      const toml::table& t = *item.as_table();
      check_conflicting_keys(t, source, "[[case]]");
      std::vector<std::pair<std::string, double>> values;
      for (const auto& [key, node] : t) {
        const std::string k(key.str());
        check_key(k, f, node, "[[case]]");
        const double v = number_of(node, "[[case]] " + k, source);
        check_value(k, v, where(source, node.source()));
        values.emplace_back(k, v);
      }
      std::sort(values.begin(), values.end(),
                [](const auto& a, const auto& b) { return key_rank(a.first) < key_rank(b.first); });
      f.list.push_back(std::move(values));
    }
    f.grid = false;
  }
  return f;
}

SweepFile read_sweep_file(const std::filesystem::path& path) {
  const std::string text = read_text_file(path, "sweep file", kMaxSweepFileBytes);
  return parse_sweep_file(text, path.string(), path.parent_path());
}

}  // namespace railcontact
