// Wheel–rail set-up files (docs/WHEEL_RAIL.md "Set-up files"): a profile pair and its track, as
// data. The shipped default is data/wheel_rail/s1002_uic60.json (the paper's test set).
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"
#include "railcontact/wheel_rail.hpp"
#include "wheel_rail/wheel_rail_setup.hpp"

namespace railcontact {
namespace {

using json = nlohmann::json;

// A set-up file is a few hundred bytes of JSON.
constexpr std::uintmax_t kMaxSetupFileBytes = 1u << 20;  // 1 MiB

std::filesystem::path data_directory() {
  if (const char* from_environment = std::getenv("RAILCONTACT_DATA")) return from_environment;
  return RAILCONTACT_DATA_DIR;
}

// A JSON value quoted in a message: a number, string, boolean or null as written, a list or an
// object by its kind only (dump() recurses once per level of nesting: a value nested a million
// levels deep, which the parser accepts, overflowed the stack).
std::string quoted_value(const json& value) {
  if (value.is_structured()) return value.is_array() ? "a list" : "an object";
  return printable_excerpt(value.dump());
}

// A length of the set-up file: a finite number.
double number(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) throw Error(fmt::format("{}: missing key '{}'", where, key));
  if (!it->is_number() || !std::isfinite(it->get<double>()))
    throw Error(fmt::format("{}: '{}' must be a finite number (got {})", where, key, quoted_value(*it)));
  return it->get<double>();
}

std::string text(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) throw Error(fmt::format("{}: missing key '{}'", where, key));
  if (!it->is_string()) throw Error(fmt::format("{}: '{}' must be a string (got {})", where, key, quoted_value(*it)));
  return it->get<std::string>();
}

void refuse_unknown_keys(const json& object, const std::set<std::string>& known, const std::string& where) {
  for (const auto& item : object.items())
    if (!known.contains(item.key()))
      throw Error(fmt::format("{}: unknown key '{}'", where, printable_excerpt(item.key())));
}

}  // namespace

std::filesystem::path default_wheel_rail_setup_path() { return data_directory() / "wheel_rail" / "s1002_uic60.json"; }

WheelRailSetup read_wheel_rail_setup(const std::filesystem::path& path) {
  return wheel_rail::parse_wheel_rail_setup(read_text_file(path, "wheel-rail set-up", kMaxSetupFileBytes), path);
}

WheelRailSetup wheel_rail::parse_wheel_rail_setup(std::string_view content, const std::filesystem::path& path) {
  const std::string where = "wheel-rail set-up " + path.string();
  json root;
  try {
    root = json::parse(content);
  } catch (const json::parse_error& e) {
    throw Error(fmt::format("{}: malformed JSON at byte {}", where, e.byte));
  } catch (const json::exception& e) {
    // A number beyond the range of a double (1e999): out_of_range.406, "number overflow parsing …".
    const std::string what = e.what();
    const std::size_t bracket = what.find("] ");
    throw Error(fmt::format("{}: malformed JSON: {} (a number beyond ±1.8e308 is not finite)", where,
                            printable_excerpt(bracket == std::string::npos ? what : what.substr(bracket + 2))));
  }
  if (!root.is_object()) throw Error(fmt::format("{}: expected a JSON object", where));
  refuse_unknown_keys(root, {"description", "wheel_profile", "rail_profile", "track"}, where);
  WheelRailSetup setup;
  if (root.contains("description")) setup.description = text(root, "description", where);
  // Profile paths are relative to the set-up file's own directory.
  const std::filesystem::path directory = path.parent_path();
  setup.wheel_profile = (directory / text(root, "wheel_profile", where)).lexically_normal();
  setup.rail_profile = (directory / text(root, "rail_profile", where)).lexically_normal();
  const auto track = root.find("track");
  if (track == root.end() || !track->is_object()) throw Error(fmt::format("{}: missing object 'track'", where));
  const std::string track_where = where + ": track";
  refuse_unknown_keys(*track,
                      {"track_gauge_m", "gauge_measuring_depth_m", "flange_back_distance_m", "flange_back_y_m",
                       "taping_line_from_flange_back_m", "nominal_rolling_radius_m", "nominal_radius_at", "rail_cant_rad"},
                      track_where);
  TrackWheelsetParameters& t = setup.track;
  t.track_gauge_m = number(*track, "track_gauge_m", track_where);
  t.gauge_measuring_depth_m = number(*track, "gauge_measuring_depth_m", track_where);
  t.flange_back_distance_m = number(*track, "flange_back_distance_m", track_where);
  t.flange_back_y_m = number(*track, "flange_back_y_m", track_where);
  t.taping_line_from_flange_back_m = number(*track, "taping_line_from_flange_back_m", track_where);
  t.nominal_rolling_radius_m = number(*track, "nominal_rolling_radius_m", track_where);
  // Optional: where r0 is measured (default: the profile's origin).
  if (const auto datum = track->find("nominal_radius_at"); datum != track->end()) {
    if (!datum->is_string())
      throw Error(fmt::format("{}: nominal_radius_at must be a string: \"profile-origin\" or \"taping-line\"", track_where));
    try {
      t.nominal_radius_at = parse_nominal_radius_datum(datum->get<std::string>());
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", track_where, e.what()));
    }
  }
  // Optional: the rail's inclination applied to the rail profile (default 0: the profile as given).
  if (track->contains("rail_cant_rad")) t.rail_cant_rad = number(*track, "rail_cant_rad", track_where);
  try {
    validate(t, "");
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", track_where, e.what()));
  }
  return setup;
}

std::filesystem::path default_wheel_profile_path() { return read_wheel_rail_setup(default_wheel_rail_setup_path()).wheel_profile; }

std::filesystem::path default_rail_profile_path() { return read_wheel_rail_setup(default_wheel_rail_setup_path()).rail_profile; }

WheelRailPair load_wheel_rail_pair(const WheelRailSetup& setup) {
  return WheelRailPair(read_profile(setup.wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}), read_profile(setup.rail_profile, ProfileReadOptions{.role = ProfileKind::rail}), setup.track);
}

WheelRailPair default_wheel_rail_pair() { return load_wheel_rail_pair(read_wheel_rail_setup(default_wheel_rail_setup_path())); }

WheelRailPair load_wheel_rail_pair(const std::filesystem::path& wheel_profile,
                                   const std::filesystem::path& rail_profile,
                                   const TrackWheelsetParameters& parameters) {
  return WheelRailPair(read_profile(wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}), read_profile(rail_profile, ProfileReadOptions{.role = ProfileKind::rail}), parameters);
}

}  // namespace railcontact
