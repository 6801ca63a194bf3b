// Fuzz target: plain-text profiles (two columns in millimetres, src/geometry/text_profile.cpp):
// comments, separators, numbers, the profile checks, then the smoothing spline.
#include "fuzz_target.hpp"
#include "geometry/profile_text.hpp"
#include "profile_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > railcontact::geometry::kMaxProfileFileBytes) return 0;  // refused before parsing
  railcontact::fuzz::expect_clean_outcome([&] {
    railcontact::fuzz::smooth(railcontact::geometry::parse_text_profile(railcontact::fuzz::as_text(data, size), "fuzz.txt"));
  });
  return 0;
}
