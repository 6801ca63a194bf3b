// The shipped S1002 wheel against the key dimensions of its standard (EN 13715: flange height
// Sh = 28 mm, flange thickness Sd = 32.5 mm, flange slope qR = 10.8 mm), measured on the smoothed
// profile as the standard defines them: Sh from the running circle (the taping line, 70 mm from
// the flange back) to the flange tip; Sd from the flange back to the flank 10 mm below the running
// circle; qR from that point to the flank 2 mm above the flange tip.
#include <gtest/gtest.h>

#include <filesystem>

#include "railcontact/geometry.hpp"

namespace railcontact {
namespace {

constexpr double kMm = 1e-3;

// y in [a, b] where the profile's z(y) = z (z(y) − z changes sign once on [a, b]).
double y_at_height(const SmoothProfile& s, double a, double b, double z) {
  for (int i = 0; i < 100; ++i) {
    const double m = 0.5 * (a + b);
    if ((s.z(m) - z) * (s.z(a) - z) <= 0.0) b = m;
    else a = m;
  }
  return 0.5 * (a + b);
}

TEST(WheelKeyDimensions, ShippedS1002HasItsStandardsFlangeHeightThicknessAndSlope) {
  const Profile wheel = read_profile(std::filesystem::path(RAILCONTACT_DATA_DIR) / "profiles/MBench_S1002_v3.prw",
                                     ProfileReadOptions{.role = ProfileKind::wheel});
  const SmoothProfile s(wheel);
  const double flange_back_m = -70 * kMm, taping_m = 0.0;  // the shipped set-up's frame
  const double z_running = s.z(taping_m);
  double y_tip = 0.0, z_tip = -1.0;  // z points down: the flange tip is the largest z
  for (double y = flange_back_m + 1 * kMm; y < taping_m; y += 0.01 * kMm)
    if (s.z(y) > z_tip) z_tip = s.z(y), y_tip = y;
  const double y_sd = y_at_height(s, y_tip, taping_m, z_running + 10 * kMm);
  const double y_qr = y_at_height(s, y_tip, taping_m, z_tip - 2 * kMm);
  // Tolerances: the drawing's dimensions are given to 0.1 mm (qR 10.8) and 0.5 mm (Sd 32.5).
  EXPECT_NEAR((z_tip - z_running) / kMm, 28.0, 0.05);
  EXPECT_NEAR((y_sd - flange_back_m) / kMm, 32.5, 0.05);
  EXPECT_NEAR((y_sd - y_qr) / kMm, 10.8, 0.05);
}

}  // namespace
}  // namespace railcontact
