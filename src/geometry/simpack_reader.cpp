// SIMPACK rail/wheel profile reader (.prr/.prw). The format: '!' starts a comment; sections
// header.begin/header.end (type = 0 rail, 1 wheel) and spline.begin/spline.end with the
// processing flags "key = value" and the point list point.begin/point.end (y z [weight] per line,
// in the file's length unit). The flags are applied in the order numbered in the files' own
// comments: 1 point.dist.min, 2 shift.y/z, 3 rotate (only 0 supported), 4 bound.y/z (active when
// min < max), 5 mirror.y/z, 6 inversion, 7 units.len.f (length unit per metre).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "geometry/profile_text.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

namespace {

using geometry::fail;

struct KeyValue {
  std::string value;
  std::size_t line = 0;
};

double numeric_value(const std::filesystem::path& path, const std::map<std::string, KeyValue>& keys,
                     const std::string& key, double fallback) {
  const auto it = keys.find(key);
  if (it == keys.end()) return fallback;
  const auto value = geometry::parse_number(it->second.value);
  if (!value) fail(path, it->second.line, fmt::format("'{}' must be a number, got '{}'", key, geometry::quoted(it->second.value)));
  return *value;
}

bool flag_value(const std::filesystem::path& path, const std::map<std::string, KeyValue>& keys,
                const std::string& key) {
  const double value = numeric_value(path, keys, key, 0.0);
  if (value != 0.0 && value != 1.0) {
    fail(path, keys.at(key).line, fmt::format("'{}' must be 0 or 1, got '{}'", key, geometry::quoted(keys.at(key).value)));
  }
  return value == 1.0;
}

using KeyValues = std::map<std::string, KeyValue>;
using Path = std::filesystem::path;

enum class Section { none, header, spline, points };

// The file as read: the keys of header.begin/header.end and of spline.begin/spline.end, and the
// point list (in the file's length unit, flags not yet applied).
struct SimpackFile {
  KeyValues header_keys;
  KeyValues spline_keys;
  std::vector<double> y, z;
  std::size_t points_begin_line = 0;
  bool points_seen = false;
  bool points_closed = false;
};

// A line inside point.begin/point.end: "y z [weight]" (the weight is ignored), or point.end.
// Returns the section the next line is in.
Section read_point_line(const Path& path, const geometry::NumberedLine& line, std::string_view text,
                        const std::string& lower, SimpackFile& file) {
  if (lower == "point.end") {
    file.points_closed = true;
    return Section::spline;
  }
  geometry::refuse_decimal_commas(path, line.number, text);
  const auto values = geometry::parse_numbers(text);
  if (!values || values->size() < 2 || values->size() > 3) {
    fail(path, line.number, fmt::format("expected a point 'y z [weight]', got '{}'", geometry::quoted(text)));
  }
  file.y.push_back((*values)[0]);
  file.z.push_back((*values)[1]);
  return Section::points;
}

// A line outside the point list: a section keyword (header/spline/point .begin/.end) or
// "key = value", kept for the header or the spline section. Returns the section the next line is in.
Section read_section_line(const Path& path, const geometry::NumberedLine& line, std::string_view text,
                          const std::string& lower, Section section, SimpackFile& file) {
  if (lower == "header.begin") return Section::header;
  if (lower == "header.end") {
    if (section != Section::header) fail(path, line.number, "header.end without header.begin");
    return Section::none;
  }
  if (lower == "spline.begin") return Section::spline;
  if (lower == "spline.end") {
    if (section != Section::spline) fail(path, line.number, "spline.end without spline.begin");
    return Section::none;
  }
  if (lower == "point.begin") {
    if (section != Section::spline) fail(path, line.number, "point.begin outside spline.begin/spline.end");
    if (file.points_seen) fail(path, line.number, "a second point.begin (one point list per file)");
    file.points_seen = true;
    file.points_begin_line = line.number;
    return Section::points;
  }
  if (lower == "point.end") fail(path, line.number, "point.end without point.begin");
  const auto eq = text.find('=');
  if (eq == std::string_view::npos) {
    fail(path, line.number, fmt::format("expected 'key = value' or a section keyword, got '{}'", geometry::quoted(text)));
  }
  const std::string key = geometry::lower_case(geometry::trim(text.substr(0, eq)));
  KeyValue value{std::string(geometry::trim(text.substr(eq + 1))), line.number};
  if (section == Section::header) {
    file.header_keys[key] = value;
  } else if (section == Section::spline) {
    file.spline_keys[key] = value;
  }
  // Keys outside the sections are ignored.
  return section;
}

// The sections of the file ('!' starts a comment), with a point list of at least 4 points.
SimpackFile read_sections(const Path& path, std::string_view bytes) {
  const auto lines = geometry::split_lines(bytes);
  SimpackFile file;
  Section section = Section::none;
  for (const auto& line : lines) {
    const std::string_view text = geometry::trim(geometry::strip_comment(line.text, "!"));
    if (text.empty()) continue;
    const std::string lower = geometry::lower_case(text);
    section = section == Section::points ? read_point_line(path, line, text, lower, file)
                                         : read_section_line(path, line, text, lower, section, file);
  }
  if (!file.points_seen) fail(path, "no point list (point.begin ... point.end)");
  if (!file.points_closed) fail(path, file.points_begin_line, "point.begin without point.end");
  if (file.y.size() < 4) fail(path, file.points_begin_line, fmt::format("{} points; at least 4 are needed", file.y.size()));
  return file;
}

// Header 'type': 0 rail, 1 wheel; absent, the kind stays unknown.
void read_profile_kind(const Path& path, const KeyValues& header_keys, Profile& profile) {
  if (header_keys.count("type") == 0) return;
  const double type = numeric_value(path, header_keys, "type", -1.0);
  if (type == 0.0) {
    profile.kind = ProfileKind::rail;
  } else if (type == 1.0) {
    profile.kind = ProfileKind::wheel;
  } else {
    fail(path, header_keys.at("type").line, "header 'type' must be 0 (rail) or 1 (wheel)");
  }
}

// 1: minimum point distance (a point closer than point.dist.min to the last one kept is dropped).
void apply_point_distance(const Path& path, const KeyValues& keys, std::vector<double>& y, std::vector<double>& z) {
  const double dist_min = numeric_value(path, keys, "point.dist.min", 0.0);
  if (dist_min > 0.0) {
    std::vector<double> ky{y.front()}, kz{z.front()};
    for (std::size_t i = 1; i < y.size(); ++i) {
      if (std::hypot(y[i] - ky.back(), z[i] - kz.back()) >= dist_min) {
        ky.push_back(y[i]);
        kz.push_back(z[i]);
      }
    }
    y = std::move(ky);
    z = std::move(kz);
  }
}

// 2: shift.
void apply_shift(const Path& path, const KeyValues& keys, std::vector<double>& y, std::vector<double>& z) {
  const double shift_y = numeric_value(path, keys, "shift.y", 0.0);
  const double shift_z = numeric_value(path, keys, "shift.z", 0.0);
  for (auto& v : y) v += shift_y;
  for (auto& v : z) v += shift_z;
}

// 3: rotation (not supported).
void check_no_rotation(const Path& path, const KeyValues& keys) {
  if (numeric_value(path, keys, "rotate", 0.0) != 0.0) {
    fail(path, keys.at("rotate").line, "a non-zero 'rotate' is not supported");
  }
}

// 4: bounds, active when min < max.
void apply_bounds(const Path& path, const KeyValues& keys, std::vector<double>& y, std::vector<double>& z) {
  const double y_lo = numeric_value(path, keys, "bound.y.min", 1.0);
  const double y_hi = numeric_value(path, keys, "bound.y.max", 0.0);
  const double z_lo = numeric_value(path, keys, "bound.z.min", 1.0);
  const double z_hi = numeric_value(path, keys, "bound.z.max", 0.0);
  if (y_lo < y_hi || z_lo < z_hi) {
    std::vector<double> ky, kz;
    for (std::size_t i = 0; i < y.size(); ++i) {
      const bool inside_y = !(y_lo < y_hi) || (y[i] >= y_lo && y[i] <= y_hi);
      const bool inside_z = !(z_lo < z_hi) || (z[i] >= z_lo && z[i] <= z_hi);
      if (inside_y && inside_z) {
        ky.push_back(y[i]);
        kz.push_back(z[i]);
      }
    }
    y = std::move(ky);
    z = std::move(kz);
  }
}

// 5: mirroring, 6: inversion of the point order.
void apply_mirroring_and_inversion(const Path& path, const KeyValues& keys, std::vector<double>& y,
                                   std::vector<double>& z) {
  if (flag_value(path, keys, "mirror.y")) {
    for (auto& v : y) v = -v;
  }
  if (flag_value(path, keys, "mirror.z")) {
    for (auto& v : z) v = -v;
  }
  if (flag_value(path, keys, "inversion")) {
    std::reverse(y.begin(), y.end());
    std::reverse(z.begin(), z.end());
  }
}

// 7: length unit (file units per metre).
void apply_length_unit(const Path& path, const KeyValues& keys, std::vector<double>& y, std::vector<double>& z) {
  const double per_metre = numeric_value(path, keys, "units.len.f", 1.0);
  if (!(per_metre > 0.0)) {
    fail(path, keys.at("units.len.f").line,
         fmt::format("'units.len.f' must be positive (file units per metre: 1000 for millimetres), got '{}'",
                     geometry::quoted(keys.at("units.len.f").value)));
  }
  for (auto& v : y) v /= per_metre;
  for (auto& v : z) v /= per_metre;
}

// The spline section's processing flags, in the order numbered in the files' own comments.
void apply_processing_flags(const Path& path, const KeyValues& keys, std::vector<double>& y, std::vector<double>& z) {
  apply_point_distance(path, keys, y, z);
  apply_shift(path, keys, y, z);
  check_no_rotation(path, keys);
  apply_bounds(path, keys, y, z);
  apply_mirroring_and_inversion(path, keys, y, z);
  apply_length_unit(path, keys, y, z);
}

// The length unit as applied, for the messages of the extent check.
std::string unit_hint(const KeyValues& keys) {
  const auto it = keys.find("units.len.f");
  if (it == keys.end()) return "the file has no units.len.f: the numbers are read as metres (units.len.f = 1000: millimetres)";
  return fmt::format("units.len.f = {} at line {} is file units per metre: 1000 for millimetres, 1 for metres",
                     geometry::quoted(it->second.value), it->second.line);
}

}  // namespace

Profile read_simpack_profile(const std::filesystem::path& path) {
  return geometry::parse_simpack_profile(read_text_file(path, "profile", geometry::kMaxProfileFileBytes), path);
}

Profile geometry::parse_simpack_profile(std::string_view bytes, const std::filesystem::path& path) {
  SimpackFile file = read_sections(path, bytes);
  Profile profile;
  profile.source = path.string();
  read_profile_kind(path, file.header_keys, profile);
  apply_processing_flags(path, file.spline_keys, file.y, file.z);
  if (file.y.size() < 4)
    fail(path, fmt::format("{} points left after the bounds/point distance; at least 4 are needed", file.y.size()));
  profile.y_m = std::move(file.y);
  profile.z_m = std::move(file.z);
  geometry::check_profile(profile, unit_hint(file.spline_keys), geometry::ProfileCheckScope::points);
  return profile;
}

}  // namespace railcontact
