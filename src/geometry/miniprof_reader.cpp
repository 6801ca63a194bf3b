// MiniProf profile reader (.ban rail, .whl wheel). The format (as written by the MiniProf
// instruments and by CONTACT's tools): a header of "Key=Value" lines — old-style files also have
// free-text lines such as "MINIPROF 2020" — then a blank line, then one point per line with the
// columns named by ColumnDef (default "X,Y"; X lateral, Y vertical, both in millimetres; other
// columns such as A angle, C curvature are ignored). Comments start with ", ! or %; fields may be
// separated by blanks, tabs or commas.
#include <fmt/core.h>

#include <algorithm>
#include <cstddef>

#include "geometry/profile_text.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

namespace {

using geometry::fail;

// Index of column `name` in a ColumnDef value such as "X,Y,A,C"; -1 if absent.
int column_index(std::string_view column_def, char name) {
  int index = 0;
  std::size_t pos = 0;
  while (pos <= column_def.size()) {
    const auto comma = column_def.find(',', pos);
    const auto field = geometry::trim(column_def.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos));
    if (field.size() == 1 && (field[0] == name || field[0] == name + ('a' - 'A'))) return index;
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
    ++index;
  }
  return -1;
}

// True when the shape shows the vertical axis pointing up: for a rail the highest point (the
// crown) is an interior maximum and the lowest point an end point; for a wheel the flange tip is
// an interior minimum and the highest point an end point.
bool vertical_axis_points_up(const Profile& profile) {
  const auto& z = profile.z_m;
  const auto n = z.size();
  const auto at_end = [n](std::size_t i) { return i == 0 || i + 1 == n; };
  const auto i_min = static_cast<std::size_t>(std::min_element(z.begin(), z.end()) - z.begin());
  const auto i_max = static_cast<std::size_t>(std::max_element(z.begin(), z.end()) - z.begin());
  if (profile.kind == ProfileKind::rail) return !at_end(i_max) && at_end(i_min);
  if (profile.kind == ProfileKind::wheel) return !at_end(i_min) && at_end(i_max);
  return false;
}

}  // namespace

Profile read_miniprof_profile(const std::filesystem::path& path, bool auto_vertical) {
  return geometry::parse_miniprof_profile(read_text_file(path, "profile", geometry::kMaxProfileFileBytes), path,
                                          auto_vertical);
}

Profile geometry::parse_miniprof_profile(std::string_view bytes, const std::filesystem::path& path, bool auto_vertical) {
  const auto lines = geometry::split_lines(bytes);
  Profile profile;
  profile.source = path.string();
  const std::string extension = geometry::lower_case(path.extension().string());
  if (extension == ".ban") profile.kind = ProfileKind::rail;
  if (extension == ".whl") profile.kind = ProfileKind::wheel;

  std::string column_def = "X,Y";
  std::size_t column_def_line = 0;
  bool in_data = false;
  std::size_t first_data_line = 0;
  for (const auto& line : lines) {
    if (!in_data && geometry::trim(line.text).empty()) {
      in_data = true;  // the blank line that ends the header
      continue;
    }
    const std::string_view text = geometry::trim(geometry::strip_comment(line.text, "\"!%"));
    if (text.empty()) continue;
    if (!in_data) {
      const auto eq = text.find('=');
      if (eq != std::string_view::npos &&
          geometry::lower_case(geometry::trim(text.substr(0, eq))) == "columndef") {
        column_def = std::string(geometry::trim(text.substr(eq + 1)));
        column_def_line = line.number;
      }
      continue;  // other header keys and old-style free-text header lines are not needed
    }
    if (text.find('=') != std::string_view::npos) {
      fail(path, line.number, fmt::format("a 'Key=Value' line inside the point list: '{}'", geometry::quoted(text)));
    }
    const int ix = column_index(column_def, 'X');
    const int iy = column_index(column_def, 'Y');
    if (ix < 0 || iy < 0) {
      fail(path, column_def_line, fmt::format("ColumnDef '{}' must name the columns X and Y", geometry::quoted(column_def)));
    }
    geometry::refuse_decimal_commas(path, line.number, text);
    const auto values = geometry::parse_numbers(text);
    const auto needed = static_cast<std::size_t>(std::max(ix, iy)) + 1;
    if (!values || values->size() < needed) {
      fail(path, line.number, fmt::format("expected a point with columns '{}', got '{}'", geometry::quoted(column_def), geometry::quoted(text)));
    }
    if (first_data_line == 0) first_data_line = line.number;
    profile.y_m.push_back((*values)[static_cast<std::size_t>(ix)] * 1e-3);
    profile.z_m.push_back((*values)[static_cast<std::size_t>(iy)] * 1e-3);
  }
  if (!in_data) fail(path, "no blank line ending the header, so no point list");
  if (profile.size() < 4) {
    fail(path, fmt::format("{} points; at least 4 are needed", profile.size()));
  }
  if (auto_vertical && vertical_axis_points_up(profile)) {
    for (auto& v : profile.y_m) v = -v;
    for (auto& v : profile.z_m) v = -v;
  }
  geometry::check_profile(profile, "a MiniProf profile: the numbers are read as millimetres", geometry::ProfileCheckScope::points);
  return profile;
}

}  // namespace railcontact
