// Every shipped set-up file under data/wheel_rail/ (docs/WHEEL_RAIL.md "Set-up files") loads and
// runs: the wheelset by load (98.1 kN per wheel, 0.5 mm elements for speed) centred and at
// y = -5 mm gives finite forces carrying each wheel's load, at least one patch per wheel, and,
// centred, the left wheel's forces the mirror image of the right's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "railcontact/railcontact.hpp"

namespace railcontact {
namespace {

std::vector<std::filesystem::path> shipped_setups() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(default_wheel_rail_setup_path().parent_path()))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ShippedSetUps, EverySetUpCarriesItsLoadsAndIsSymmetricWhenCentred) {
  const std::vector<std::filesystem::path> files = shipped_setups();
  ASSERT_GE(files.size(), 6u);  // the default pair and the five of docs/WHEEL_RAIL.md
  WheelsetOptions options;
  options.element_size_m = 0.5e-3;
  const double load_N = options.loads->right_N;
  for (const auto& file : files) {
    SCOPED_TRACE(file.filename().string());
    const WheelRailSetup setup = read_wheel_rail_setup(file);
    EXPECT_FALSE(setup.description.empty());
    Wheelset wheelset(WheelsetTrack(read_profile(setup.wheel_profile), read_profile(setup.rail_profile), setup.track),
                      options);
    for (const double y : {0.0, -5e-3}) {
      SCOPED_TRACE("y = " + std::to_string(y * 1e3) + " mm");
      WheelsetState state;
      state.position.lateral_displacement_m = y;
      state.velocity.forward_speed_m_per_s = 20.0;
      const WheelsetResult r = wheelset.evaluate(state);
      for (const WheelResult& w : r.wheels) {
        EXPECT_GE(w.patches.size(), 1u);
        for (const double f : w.force_track_N) EXPECT_TRUE(std::isfinite(f));
        // The load balance's tolerance is tighter; 0.1 % is what a user reads as "carried".
        EXPECT_NEAR(w.force_track_N[2], load_N, 1e-3 * load_N);
      }
      if (y == 0.0) {
        // Mirror symmetry: the two wheels are solved by the same code on mirrored geometry, within
        // the load balance's and the solvers' rounding: 1e-6 of the load.
        const Vector3& right = r.wheels[0].force_track_N;
        const Vector3& left = r.wheels[1].force_track_N;
        EXPECT_NEAR(left[0], right[0], 1e-6 * load_N);
        EXPECT_NEAR(left[1], -right[1], 1e-6 * load_N);
        EXPECT_NEAR(left[2], right[2], 1e-6 * load_N);
      }
    }
  }
}

}  // namespace
}  // namespace railcontact
