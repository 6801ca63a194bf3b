// The curation of measured profiles (src/geometry/profile_curation.cpp, docs/GEOMETRY.md §8
// "Measured profiles"): a clean profile passes point for point; a stitched zig-zag is replaced by
// its mean; an undercut is replaced by the envelope the other body sees, which equals the profile
// without the fold; too much hidden is refused; a profile whose role is unknown keeps the
// undercut check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact {
namespace {

const std::filesystem::path kProfiles = std::filesystem::path(RAILCONTACT_DATA_DIR) / "profiles";
constexpr double kMm = 1e-3;

std::string error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// The shipped profiles have neither fault: unchanged, point for point.
TEST(ProfileCuration, CleanProfilesAreUnchanged) {
  for (const char* name : {"MBench_S1002_v3.prw", "MBench_UIC60_v3.prr"}) {
    ProfileReadOptions raw;
    raw.curation.repair_zigzags = false;
    raw.curation.hide_undercuts = false;
    const Profile as_read = read_profile(kProfiles / name, raw);
    const Profile p = read_profile(kProfiles / name);
    EXPECT_FALSE(p.curation.changed()) << name;
    EXPECT_EQ(p.y_m, as_read.y_m) << name;
    EXPECT_EQ(p.z_m, as_read.z_m) << name;
  }
}

// A point stitched twice on the tread (y = 10 mm: the section ends 0.02 mm further and the next
// one starts 0.02 mm back) is a zig-zag: the pair becomes its mean, and the smoothed tread is the
// clean one's within 0.1 µm.
TEST(ProfileCuration, ZigZagPairBecomesItsMean) {
  const Profile clean = read_profile(kProfiles / "MBench_S1002_v3.prw");
  Profile stitched = clean;
  std::size_t i = 0;
  while (i + 1 < stitched.size() && (stitched.y_m[i] - 10 * kMm) * (stitched.y_m[i + 1] - 10 * kMm) > 0.0) ++i;
  ASSERT_LT(i + 1, stitched.size());
  // Two points near the middle of segment i: a 0.02 mm beyond it, b 0.02 mm back (i, a, b, i+1).
  const double dy = stitched.y_m[i + 1] - stitched.y_m[i];
  const double ya = stitched.y_m[i] + 0.5 * dy + 0.02 * kMm * (dy > 0 ? 1 : -1);
  const double yb = stitched.y_m[i] + 0.5 * dy - 0.02 * kMm * (dy > 0 ? 1 : -1);
  const double zm = 0.5 * (stitched.z_m[i] + stitched.z_m[i + 1]);
  stitched.y_m.insert(stitched.y_m.begin() + static_cast<std::ptrdiff_t>(i) + 1, {ya, yb});
  stitched.z_m.insert(stitched.z_m.begin() + static_cast<std::ptrdiff_t>(i) + 1, {zm, zm});
  stitched.source = "stitched";
  EXPECT_NE(error_of([&] { validate(stitched); }).find("turn back"), std::string::npos);
  const Profile repaired = curated(stitched, ProfileKind::wheel);
  EXPECT_EQ(repaired.curation.zigzags_repaired, 1);
  EXPECT_EQ(repaired.curation.hidden_points, 0u);
  ASSERT_EQ(repaired.size(), clean.size() + 1);
  EXPECT_NEAR(repaired.y_m[i + 1], 0.5 * (ya + yb), 1e-15);
  EXPECT_NO_THROW(validate(repaired));
  const SmoothProfile a(clean), b(repaired);
  for (double y = -20 * kMm; y <= 40 * kMm; y += 0.5 * kMm) EXPECT_NEAR(b.z(y), a.z(y), 1e-7) << y;
}

// A rail whose gauge face leans back under the head below z = 20 mm (0.15 mm per mm, 2.76 mm at
// the bottom; tests/data/uic60_undercut.prr): seen from above, the part under the
// overhang is hidden. The envelope is the profile with the undercut points dropped, from the
// overhang's edge on; the head and the gauge corner are the shipped rail's.
TEST(ProfileCuration, UndercutRailKeepsWhatTheWheelSees) {
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  Profile undercut = rail;
  undercut.source = "undercut";
  const double y20 = -43.251229 * kMm;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < undercut.size(); ++i)
    if (undercut.y_m[i] < -40 * kMm && undercut.z_m[i] > 20 * kMm) {
      undercut.y_m[i] = y20 + 0.15 * (undercut.z_m[i] - 20 * kMm);
      ++moved;
    }
  ASSERT_GT(moved, 10u);
  const Profile seen = curated(undercut, ProfileKind::rail);
  EXPECT_NEAR(seen.curation.largest_overhang_m, 2.76 * kMm, 0.01 * kMm);
  // Every moved point lies under the overhang (at y > the overhang's edge) except the one at its edge.
  EXPECT_GE(seen.curation.hidden_points + 1, moved);
  EXPECT_LE(seen.curation.hidden_points, moved);
  EXPECT_GT(seen.curation.hidden_from_y_m, y20 - 0.01 * kMm);
  EXPECT_NO_THROW(validate(seen));
  // The head: the shipped rail's z(y) exactly where the points were not moved.
  const SmoothProfile a(rail), b(seen);
  for (double y = -35 * kMm; y <= 30 * kMm; y += 0.5 * kMm) EXPECT_NEAR(b.z(y), a.z(y), 1e-7) << y;
  // The same profile in the role of the wheel would be seen from below: there the lower, leaning
  // face is the nearer one and the face above it is hidden instead.
  const Profile from_below = curated(undercut, ProfileKind::wheel);
  EXPECT_GT(from_below.curation.hidden_points, 0u);
  EXPECT_LT(from_below.curation.hidden_to_y_m, -38 * kMm);  // the gauge corner's face, above the lean
  EXPECT_EQ(std::count(from_below.z_m.begin(), from_below.z_m.end(), undercut.z_m.front()), 1);
  // With the role unknown (a text file on its own) the undercut is refused as before, naming it.
  Profile unknown = undercut;
  unknown.kind = ProfileKind::unknown;
  EXPECT_EQ(curated(unknown).curation.hidden_points, 0u);
  EXPECT_NE(error_of([&] { validate(curated(unknown)); }).find("the profile is undercut"), std::string::npos);
}

// The same undercut rail read from its file (tests/data/uic60_undercut.prr) in a wheel–rail pair:
// the flange contact at y = −7 mm, on the gauge corner above the lean, is the shipped rail's: the
// contact angle within 1e-6 rad and the approach within 1e-6 of it (the smoothing spline is global:
// the changed face below, several millimetres away, moves them by about 1e-8).
TEST(ProfileCuration, UndercutRailFileGivesTheShippedFlangeContact) {
  const std::filesystem::path undercut_file = std::filesystem::path(RAILCONTACT_SOURCE_DIR) / "tests/data/uic60_undercut.prr";
  const WheelRailPair shipped = default_wheel_rail_pair();
  const WheelRailPair undercut = load_wheel_rail_pair(default_wheel_profile_path(), undercut_file);
  EXPECT_GT(undercut.rail().source().size(), 0u);
  WheelRailPatchOptions options;
  options.target_elements = 800;
  const WheelRailPatch a = solve_wheel_rail_patch(shipped, -7e-3, options);
  const WheelRailPatch b = solve_wheel_rail_patch(undercut, -7e-3, options);
  EXPECT_NEAR(b.contact_angle_rad, a.contact_angle_rad, 1e-6);
  EXPECT_NEAR(b.normal.approach_m, a.normal.approach_m, 1e-6 * std::abs(a.normal.approach_m));
}

// A wheel whose field-side face curls back under the tread (y back by 1.5 mm over the last 10 mm
// of height): from below, the rail sees the tread; the curl is dropped, the tread is unchanged and
// the pair solves.
TEST(ProfileCuration, WheelFieldSideCurlIsHidden) {
  const Profile wheel = read_profile(kProfiles / "MBench_S1002_v3.prw");
  Profile curl = wheel;
  curl.source = "curl";
  // The profile's field-side end: extend it by a face going up (z decreasing) and back in y.
  const bool ascending = curl.y_m.back() > curl.y_m.front();
  const double y_end = ascending ? curl.y_m.back() : curl.y_m.front();
  const double z_end = ascending ? curl.z_m.back() : curl.z_m.front();
  std::vector<double> ys, zs;
  for (int k = 1; k <= 20; ++k) {
    ys.push_back(y_end - 1.5 * kMm * k / 20.0);
    zs.push_back(z_end - 10 * kMm * k / 20.0);
  }
  if (ascending) {
    curl.y_m.insert(curl.y_m.end(), ys.begin(), ys.end());
    curl.z_m.insert(curl.z_m.end(), zs.begin(), zs.end());
  } else {
    curl.y_m.insert(curl.y_m.begin(), ys.rbegin(), ys.rend());
    curl.z_m.insert(curl.z_m.begin(), zs.rbegin(), zs.rend());
  }
  EXPECT_NE(error_of([&] { validate(curl); }).find("undercut"), std::string::npos);
  const Profile seen = curated(curl, ProfileKind::wheel);
  EXPECT_EQ(seen.curation.hidden_points, 20u);
  EXPECT_NEAR(seen.curation.largest_overhang_m, 1.5 * kMm, 1e-9);
  EXPECT_GE(seen.curation.hidden_from_y_m, y_end - 1.5 * kMm - 1e-12);
  ASSERT_EQ(seen.size(), wheel.size());
  const WheelRailPair clean(wheel, read_profile(kProfiles / "MBench_UIC60_v3.prr"));
  const WheelRailPair curled(seen, read_profile(kProfiles / "MBench_UIC60_v3.prr"));
  EXPECT_NEAR(curled.wheel().z(0.0), clean.wheel().z(0.0), 1e-12);
}

// The shipped measured wheel (data/profiles/Car7358_0001r.whl, MiniProf, y from the flange back):
// its flange back face and field-side chamfer fold back (1.14 mm) and are hidden, 168 of its 657
// points; with its set-up (data/wheel_rail/car7358_uic60.json) the wheelset by load carries both
// loads on finite forces, one tread patch per wheel at y = 0, and the wheels are mirror images.
TEST(ProfileCuration, MeasuredWheelGivesAWheelset) {
  const Profile wheel = read_profile(kProfiles / "Car7358_0001r.whl", ProfileReadOptions{.role = ProfileKind::wheel});
  EXPECT_EQ(wheel.curation.zigzags_repaired, 0);
  EXPECT_EQ(wheel.curation.hidden_points, 168u);
  EXPECT_NEAR(wheel.curation.largest_overhang_m, 1.139 * kMm, 0.001 * kMm);
  // Car7216 folds back at its flange tip too (0.6 mm; the direction turns by 162 degrees there).
  const Profile other = read_profile(kProfiles / "Car7216_0001r.whl", ProfileReadOptions{.role = ProfileKind::wheel});
  EXPECT_EQ(other.curation.hidden_points, 109u);
  EXPECT_NEAR(other.curation.largest_overhang_m, 0.597 * kMm, 0.001 * kMm);
  const WheelRailSetup setup = read_wheel_rail_setup(std::filesystem::path(RAILCONTACT_DATA_DIR) / "wheel_rail/car7358_uic60.json");
  WheelsetOptions options;
  options.element_size_m = 0.5e-3;
  Wheelset wheelset(WheelsetTrack(read_profile(setup.wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}),
                                  read_profile(setup.rail_profile, ProfileReadOptions{.role = ProfileKind::rail}), setup.track),
                    options);
  const WheelsetResult r = wheelset.evaluate(WheelsetState{});
  for (const WheelResult& w : r.wheels) {
    EXPECT_EQ(w.patches.size(), 1u);
    EXPECT_NEAR(w.force_track_N[2], 98100.0, 0.001 * 98100.0);
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::isfinite(w.force_track_N[i]));
  }
  // Mirror images: Fx and Fz equal, Fy opposite (different code paths for the two sides' frames: 1e-6 of the load).
  EXPECT_NEAR(r.wheels[0].force_track_N[0], r.wheels[1].force_track_N[0], 1e-6 * 98100.0);
  EXPECT_NEAR(r.wheels[0].force_track_N[1], -r.wheels[1].force_track_N[1], 1e-6 * 98100.0);
}

// More than half of the points hidden: the head's outline given both ways (over the top and back
// underneath, 5 mm lower) is not a rail profile.
TEST(ProfileCuration, MostPointsHiddenIsRefused) {
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  Profile outline;
  outline.source = "outline";
  outline.kind = ProfileKind::rail;
  for (std::size_t i = 0; i < rail.size(); ++i)
    if (std::abs(rail.y_m[i]) < 30 * kMm) outline.y_m.push_back(rail.y_m[i]), outline.z_m.push_back(rail.z_m[i]);
  if (outline.y_m.front() > outline.y_m.back()) {
    std::reverse(outline.y_m.begin(), outline.y_m.end());
    std::reverse(outline.z_m.begin(), outline.z_m.end());
  }
  // Back underneath with twice as many points (each segment's end and middle): two thirds hidden.
  const std::size_t n = outline.size();
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const std::size_t a = n - 1 - k, b = n - 2 - k;
    outline.y_m.push_back(outline.y_m[a] - 0.01 * kMm);
    outline.z_m.push_back(outline.z_m[a] + 5 * kMm);
    outline.y_m.push_back(0.5 * (outline.y_m[a] + outline.y_m[b]) - 0.01 * kMm);
    outline.z_m.push_back(0.5 * (outline.z_m[a] + outline.z_m[b]) + 5 * kMm);
  }
  const std::string message = error_of([&] { (void)curated(outline, ProfileKind::rail); });
  EXPECT_NE(message.find("profile outline: "), std::string::npos) << message;
  EXPECT_NE(message.find("lie behind the part that faces the wheel"), std::string::npos) << message;
  EXPECT_NE(message.find("at most 50 % may be hidden"), std::string::npos) << message;
}

}  // namespace
}  // namespace railcontact
