// Fuzz target: SIMPACK profiles (.prw/.prr, src/geometry/simpack_reader.cpp): sections, keys, the
// point list, the processing flags (point distance, shift, bounds, mirroring, inversion, unit),
// the profile checks, then the smoothing spline.
#include "fuzz_target.hpp"
#include "geometry/profile_text.hpp"
#include "profile_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > railcontact::geometry::kMaxProfileFileBytes) return 0;  // refused before parsing
  railcontact::fuzz::expect_clean_outcome([&] {
    railcontact::fuzz::smooth(railcontact::geometry::parse_simpack_profile(railcontact::fuzz::as_text(data, size), "fuzz.prw"));
  });
  return 0;
}
