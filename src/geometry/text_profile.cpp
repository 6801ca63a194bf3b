// Plain two-column profile text: one point "y z" per line (blank/tab/comma separated, further
// columns ignored), in a given length unit; '#', '!' and '%' start comments.
#include <fmt/core.h>

#include <cmath>
#include <fstream>

#include "geometry/profile_text.hpp"
#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

Profile read_text_profile(const std::filesystem::path& path, double length_unit_m) {
  require(std::isfinite(length_unit_m) && length_unit_m > 0.0, "profile: the length unit must be positive");
  return geometry::parse_text_profile(read_text_file(path, "profile", geometry::kMaxProfileFileBytes), path,
                                      length_unit_m);
}

Profile geometry::parse_text_profile(std::string_view bytes, const std::filesystem::path& path, double length_unit_m) {
  require(std::isfinite(length_unit_m) && length_unit_m > 0.0, "profile: the length unit must be positive");
  const auto lines = geometry::split_lines(bytes);
  Profile profile;
  profile.source = path.string();
  for (const auto& line : lines) {
    const std::string_view text = geometry::trim(geometry::strip_comment(line.text, "#!%"));
    if (text.empty()) continue;
    geometry::refuse_decimal_commas(path, line.number, text);
    const auto values = geometry::parse_numbers(text);
    if (!values || values->size() < 2) {
      geometry::fail(path, line.number, fmt::format("expected two numbers 'y z', got '{}'", geometry::quoted(text)));
    }
    profile.y_m.push_back((*values)[0] * length_unit_m);
    profile.z_m.push_back((*values)[1] * length_unit_m);
  }
  if (profile.size() < 4) geometry::fail(path, fmt::format("{} points; at least 4 are needed", profile.size()));
  geometry::check_profile(profile, "a plain-text profile: " + geometry::length_unit_hint(length_unit_m), geometry::ProfileCheckScope::points);
  return profile;
}

void write_text_profile(const std::filesystem::path& path, const Profile& profile, double length_unit_m) {
  validate(profile);
  require(std::isfinite(length_unit_m) && length_unit_m > 0.0, "profile: the length unit must be positive");
  std::ofstream out(path);
  if (!out) throw Error(ErrorKind::io, fmt::format("profile {}: cannot open the file for writing", path.string()));
  out << fmt::format("# y z in units of {} m; profile frame: y lateral, z down\n", length_unit_m);
  for (std::size_t i = 0; i < profile.size(); ++i) {
    out << fmt::format("{:.17g} {:.17g}\n", profile.y_m[i] / length_unit_m, profile.z_m[i] / length_unit_m);
  }
  if (!out) geometry::fail(path, "write error");
}

}  // namespace railcontact
