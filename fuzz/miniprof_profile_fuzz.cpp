// Fuzz target: MiniProf profiles (.ban rail, .whl wheel, src/geometry/miniprof_reader.cpp): the
// header, ColumnDef, the point list, the vertical-axis detection (which depends on the kind, so
// every input is read as both), the profile checks, then the smoothing spline.
#include "fuzz_target.hpp"
#include "geometry/profile_text.hpp"
#include "profile_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > railcontact::geometry::kMaxProfileFileBytes) return 0;  // refused before parsing
  for (const char* name : {"fuzz.ban", "fuzz.whl"}) {
    railcontact::fuzz::expect_clean_outcome([&] {
      railcontact::fuzz::smooth(railcontact::geometry::parse_miniprof_profile(railcontact::fuzz::as_text(data, size), name));
    });
  }
  return 0;
}
