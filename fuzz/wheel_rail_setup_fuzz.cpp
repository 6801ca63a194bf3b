// Fuzz target: wheel-rail set-up files (JSON, src/wheel_rail/wheel_rail_setup.cpp): the JSON parse,
// keys and types, the track and wheelset parameters (validate), then what a pair does with them:
// the shipped S1002/UIC60 profiles (read once) placed on the track of the set-up (WheelRailPair:
// taping line, flange, rail top and gauge point) and the contact point at y = 0. The profile paths
// of the set-up are not read (the profile targets cover profiles).
#include <optional>

#include "fuzz_target.hpp"
#include "railcontact/geometry.hpp"
#include "wheel_rail/wheel_rail_setup.hpp"

namespace {

struct ShippedProfiles {
  railcontact::Profile wheel, rail;
};

const ShippedProfiles& shipped_profiles() {
  static const ShippedProfiles profiles{railcontact::read_profile(railcontact::default_wheel_profile_path()),
                                        railcontact::read_profile(railcontact::default_rail_profile_path())};
  return profiles;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 20)) return 0;  // read_wheel_rail_setup refuses larger files before parsing
  const ShippedProfiles& profiles = shipped_profiles();
  railcontact::fuzz::expect_clean_outcome([&] {
    const railcontact::WheelRailSetup setup =
        railcontact::wheel_rail::parse_wheel_rail_setup(railcontact::fuzz::as_text(data, size), "/fuzz/setup.json");
    const railcontact::WheelRailPair pair(profiles.wheel, profiles.rail, setup.track);
    (void)pair.contact_point(0.0);
  });
  return 0;
}
