#pragma once
// Wheelset case files (TOML, docs/CASE_FILES.md "Wheelset cases"): the track and profiles, the
// wheelset's state, the load or the position, friction, material, mesh and solvers of one
// `railcontact wheelset CASE.toml` run. Every key is checked; errors name the file, line and key.
#include <toml++/toml.h>

#include <filesystem>
#include <set>
#include <string>
#include <string_view>

#include "railcontact/wheelset.hpp"

namespace railcontact {

struct WheelsetCase {
  std::string source;
  // Profiles: a set-up file, or a wheel and a rail profile per side (relative paths against the
  // case file's directory). All empty: the shipped S1002/UIC60 set-up.
  std::filesystem::path setup_file;
  std::filesystem::path right_wheel_profile, right_rail_profile, left_wheel_profile, left_rail_profile;
  WheelsetState state;
  WheelsetOptions options;
};

WheelsetCase parse_wheelset_case(std::string_view text, const std::string& source,
                                 const std::filesystem::path& base_directory);
WheelsetCase read_wheelset_case(const std::filesystem::path& path);

// The same, for a file that holds further top-level sections of its own (`caller_sections`, e.g. a
// sweep file's [grid]): the whole file is parsed into `root` (unknown sections refused) and the
// wheelset case read from its wheelset-case sections; the caller reads its own from `root`.
WheelsetCase parse_wheelset_case_with(std::string_view text, const std::string& source,
                                      const std::filesystem::path& base_directory,
                                      const std::set<std::string>& caller_sections, toml::table& root);
// The wheelset case of a parsed file (sections other than the wheelset case's are not looked at).
WheelsetCase wheelset_case_from_toml(const toml::table& root, const std::string& source,
                                     const std::filesystem::path& base_directory);

// The case's track: from its set-up file or profiles, or the default.
WheelsetTrack wheelset_track(const WheelsetCase& c);

}  // namespace railcontact
