// The shipped S1002/UIC60 pair (METHOD.md §9) and pairs from profile files.
#include <cstdlib>

#include "railcontact/wheel_rail.hpp"

namespace railcontact {

namespace {

std::filesystem::path data_directory() {
  if (const char* from_environment = std::getenv("RAILCONTACT_DATA")) return from_environment;
  return RAILCONTACT_DATA_DIR;
}

}  // namespace

std::filesystem::path default_wheel_profile_path() { return data_directory() / "profiles" / "MBench_S1002_v3.prw"; }

std::filesystem::path default_rail_profile_path() { return data_directory() / "profiles" / "MBench_UIC60_v3.prr"; }

WheelRailPair default_wheel_rail_pair() {
  return load_wheel_rail_pair(default_wheel_profile_path(), default_rail_profile_path());
}

WheelRailPair load_wheel_rail_pair(const std::filesystem::path& wheel_profile,
                                   const std::filesystem::path& rail_profile,
                                   const TrackWheelsetParameters& parameters) {
  return WheelRailPair(read_profile(wheel_profile), read_profile(rail_profile), parameters);
}

}  // namespace railcontact
