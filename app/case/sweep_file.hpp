#pragma once
// Sweep files (TOML, docs/CASE_FILES.md "Sweep files"; `railcontact sweep FILE`): the sections of a
// wheelset case (track and profiles, the base state, load or position, friction, material, mesh,
// solvers — the same keys) plus either a [grid] (the Cartesian product of lists or ranges of
// state values) or a list of [[case]] tables (each a set of state values). Case k of a grid is the
// mixed-radix number k over the axes in the order of kSweepKeys (the last key varies fastest).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "case/wheelset_case.hpp"

namespace railcontact {

// The keys a [grid] axis or a [[case]] may set, outermost first (in a grid the last varies
// fastest). wheel_load_N sets both wheels' loads; the three load keys need the wheelset by load,
// z_mm needs it by position.
inline constexpr const char* kSweepKeys[] = {
    "mu",          "wheel_load_N", "right_wheel_N", "left_wheel_N", "speed_m_per_s",
    "lateral_velocity_m_per_s",    "vertical_velocity_m_per_s",     "roll_rate_rad_per_s",
    "yaw_rate_rad_per_s",          "extra_longitudinal_creepage",   "roll_mrad",
    "z_mm",        "yaw_mrad",     "y_mm"};

// At most this many cases in a sweep (a grid's product is checked before anything is allocated).
inline constexpr double kMaximumSweepCases = 1e6;

struct SweepAxis {
  std::string key;
  std::vector<double> values;
};

// One case: the base case's state, loads and friction with the case's values set.
struct SweepCase {
  WheelsetState state;
  std::optional<WheelLoads> loads;
  double friction_coefficient = 0.3;
};

struct SweepFile {
  std::string source;  // the path as given
  std::string text;    // the file's bytes
  WheelsetCase base;
  bool grid = true;
  std::vector<SweepAxis> axes;                                      // grid: in the order of kSweepKeys
  std::vector<std::vector<std::pair<std::string, double>>> list;  // [[case]]: each case's values

  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] SweepCase at(std::size_t k) const;
  // The keys a case may differ in (the grid's axes, or every key of the list), in kSweepKeys order.
  [[nodiscard]] std::vector<std::string> varied_keys() const;
};

// Throws Error (invalid_input) naming the file, the line and the key: unknown sections and keys,
// neither or both of [grid] and [[case]], an empty grid or list, a range that is not
// {from, to, step} with a positive step, non-finite values, load keys on a wheelset by position
// and z_mm on one by load, more than kMaximumSweepCases cases (with the grid's size).
SweepFile parse_sweep_file(std::string_view text, const std::string& source, const std::filesystem::path& base_directory);
SweepFile read_sweep_file(const std::filesystem::path& path);

}  // namespace railcontact
