// Profile readers (SIMPACK, MiniProf, text) against hand-checked points of the shipped files,
// malformed files, and the smoothing spline against circles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {
namespace {

const std::filesystem::path kProfiles = std::filesystem::path(RAILCONTACT_DATA_DIR) / "profiles";

// A temporary directory per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            (std::string("railcontact_profile_") + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] std::filesystem::path file(const std::string& name, const std::string& content) const {
    const auto p = path_ / name;
    std::ofstream(p) << content;
    return p;
  }

 private:
  std::filesystem::path path_;
};

// Runs fn, expects railcontact::Error whose message contains every one of `parts`.
void expect_error_containing(const std::function<void()>& fn, const std::vector<std::string>& parts) {
  try {
    fn();
    ADD_FAILURE() << "no railcontact::Error thrown";
  } catch (const Error& e) {
    for (const auto& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << "message: " << e.what() << "\nmissing: " << part;
    }
  }
}

constexpr double kMm = 1e-3;

TEST(SimpackReader, WheelFileAppliesMirrorInversionAndUnits) {
  // Raw file: y from +69.6 (flange back) to -60 (field side), mirror.y = 1, inversion = 1,
  // units.len.f = 1000. After the flags: y = -y_raw, order reversed, metres.
  const Profile p = read_profile(kProfiles / "MBench_S1002_v3.prw");
  ASSERT_EQ(p.size(), 399u);
  EXPECT_EQ(p.kind, ProfileKind::wheel);
  // First point: raw last line "-6.0000000E+01 -2.6356764E+00".
  EXPECT_DOUBLE_EQ(p.y_m.front(), 60.0 * kMm);
  EXPECT_DOUBLE_EQ(p.z_m.front(), -2.6356764 * kMm);
  // Last point: raw first (uncommented) line "6.9612628E+01 1.3485642E+01".
  EXPECT_DOUBLE_EQ(p.y_m.back(), -69.612628 * kMm);
  EXPECT_DOUBLE_EQ(p.z_m.back(), 13.485642 * kMm);
  // Raw line 283 "3.4825167E-01 1.1887234E-02" (point 240 of 399) becomes point 160.
  EXPECT_DOUBLE_EQ(p.y_m[159], -0.34825167 * kMm);
  EXPECT_DOUBLE_EQ(p.z_m[159], 0.011887234 * kMm);
  // The flange (largest z, z down) lies at negative y, its tip about 28 mm below the tread.
  const auto tip = std::max_element(p.z_m.begin(), p.z_m.end()) - p.z_m.begin();
  EXPECT_NEAR(p.y_m[static_cast<std::size_t>(tip)], -54.5 * kMm, 0.5 * kMm);
  EXPECT_NEAR(p.z_m[static_cast<std::size_t>(tip)], 28.0 * kMm, 0.1 * kMm);
}

TEST(SimpackReader, RailFileWithoutFlags) {
  const Profile p = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  ASSERT_EQ(p.size(), 495u);
  EXPECT_EQ(p.kind, ProfileKind::rail);
  EXPECT_DOUBLE_EQ(p.y_m.front(), -43.704898 * kMm);
  EXPECT_DOUBLE_EQ(p.z_m.front(), 38.510726 * kMm);
  EXPECT_DOUBLE_EQ(p.y_m.back(), 30.595912 * kMm);
  EXPECT_DOUBLE_EQ(p.z_m.back(), 36.653225 * kMm);
  // Line 302 "-1.8787617E+00 5.9202576E-03", point 260.
  EXPECT_DOUBLE_EQ(p.y_m[259], -1.8787617 * kMm);
  EXPECT_DOUBLE_EQ(p.z_m[259], 0.0059202576 * kMm);
}

TEST(SimpackReader, HonoursShiftMirrorZAndUnitFactor) {
  const TempDir dir;
  const auto path = dir.file("shifted.prr",
                             "header.begin\n type = 0\nheader.end\n"
                             "spline.begin\n"
                             "  shift.y = 1.0 ! cm\n  shift.z = -2.0\n  mirror.z = 1\n  units.len.f = 100\n"
                             "  point.begin\n   0 0\n 0.4 0.1 1.0\n 0.8 0.4\n 1.2 0.9\n  point.end\nspline.end\n");
  const Profile p = read_simpack_profile(path);
  ASSERT_EQ(p.size(), 4u);
  // y = (y_raw + 1) / 100, z = -(z_raw - 2) / 100 (a 12 mm wide profile, points 4 to 7 mm apart:
  // a plausible one, docs/GEOMETRY.md §8).
  EXPECT_DOUBLE_EQ(p.y_m[0], 0.01);
  EXPECT_DOUBLE_EQ(p.z_m[0], 0.02);
  EXPECT_DOUBLE_EQ(p.y_m[3], 0.022);
  EXPECT_DOUBLE_EQ(p.z_m[3], 0.011);
}

TEST(SimpackReader, MalformedFilesNameFileAndLine) {
  const TempDir dir;
  const std::string head = "header.begin\n type = 1\nheader.end\nspline.begin\n units.len.f = 1000\n point.begin\n";
  // Line 8 holds the bad point.
  const auto bad_point = dir.file("bad_point.prw", head + "1 2\n1 abc\n3 4\n5 6\n point.end\nspline.end\n");
  expect_error_containing([&] { (void)read_profile(bad_point); }, {"bad_point.prw:8:", "1 abc"});
  const auto no_end = dir.file("no_end.prw", head + "1 2\n2 3\n3 4\n5 6\nspline.end\n");
  expect_error_containing([&] { (void)read_profile(no_end); }, {"no_end.prw:"});
  const auto no_points = dir.file("no_points.prw", "header.begin\n type = 1\nheader.end\n");
  expect_error_containing([&] { (void)read_profile(no_points); }, {"no_points.prw", "no point list"});
  const auto bad_unit = dir.file("bad_unit.prw", "spline.begin\n units.len.f = 0\n point.begin\n1 2\n2 3\n3 4\n5 6\n point.end\n");
  expect_error_containing([&] { (void)read_profile(bad_unit); }, {"bad_unit.prw:2:", "units.len.f"});
  const auto bad_flag = dir.file("bad_flag.prw", "spline.begin\n mirror.y = 2\n point.begin\n1 2\n2 3\n3 4\n5 6\n point.end\n");
  expect_error_containing([&] { (void)read_profile(bad_flag); }, {"bad_flag.prw:2:", "mirror.y"});
  const auto rotated = dir.file("rotated.prw", "spline.begin\n rotate = 0.1\n point.begin\n1 2\n2 3\n3 4\n5 6\n point.end\n");
  expect_error_containing([&] { (void)read_profile(rotated); }, {"rotated.prw:2:", "rotate"});
  expect_error_containing([&] { (void)read_profile("/nonexistent_railcontact_dir/missing.prr"); }, {"missing.prr", "cannot open"});
}

TEST(TextReader, RoundTripThroughTempFile) {
  const TempDir dir;
  const Profile original = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  const auto path = dir.file("rail.txt", "");
  write_text_profile(path, original);
  const Profile back = read_profile(path);
  ASSERT_EQ(back.size(), original.size());
  for (std::size_t i = 0; i < original.size(); ++i) {
    EXPECT_DOUBLE_EQ(back.y_m[i], original.y_m[i]);
    EXPECT_DOUBLE_EQ(back.z_m[i], original.z_m[i]);
  }
  // Metres as the unit, commas, comments and extra columns (15 mm wide: a plausible extent).
  const auto metres = dir.file("metres.dat", "# y z\n0.010, 0.002, 7\n\n0.015 0.003\n! c\n0.020\t0.004\n0.025 0.005 % x\n");
  ProfileReadOptions options;
  options.text_length_unit_m = 1.0;
  const Profile m = read_profile(metres, options);
  ASSERT_EQ(m.size(), 4u);
  EXPECT_DOUBLE_EQ(m.y_m[0], 0.010);
  EXPECT_DOUBLE_EQ(m.z_m[3], 0.005);
}

TEST(TextReader, MalformedLinesNameFileAndLine) {
  const TempDir dir;
  const auto one_column = dir.file("one.txt", "1 2\n2 3\n# comment\n4\n5 6\n7 8\n");
  expect_error_containing([&] { (void)read_profile(one_column); }, {"one.txt:4:", "two numbers"});
  const auto garbage = dir.file("garbage.txt", "1 2\n2 3\n3 x4\n5 6\n");
  expect_error_containing([&] { (void)read_profile(garbage); }, {"garbage.txt:3:"});
  const auto too_few = dir.file("few.txt", "1 2\n2 3\n");
  expect_error_containing([&] { (void)read_profile(too_few); }, {"few.txt", "at least 4"});
}

// MiniProf file text from points in mm (X lateral, Y vertical) with a typical header.
std::string miniprof_text(const std::vector<double>& x_mm, const std::vector<double>& y_mm, bool old_style) {
  std::string text;
  if (old_style) {
    text = "#MINIWHEELPROF\nTest_0001.whl\nMINIPROF 2020\nStock.......:\n\" 32.58 37.11 14.71\n(Sd/Sh/qR)\n\n";
  } else {
    text = "Filename=test.ban\nMPTypeNo=299\nXYPoints=" + std::to_string(x_mm.size()) +
           "\n\"RefPoint1=\"\nRefPoint1=0.0000, 0.0000\nColumnDef=X,Y,A\n\n";
    text += "\" 99.0 99.0 0.0\n";  // a commented-out point
  }
  for (std::size_t i = 0; i < x_mm.size(); ++i) {
    char line[96];
    std::snprintf(line, sizeof line, old_style ? "%.9f    %.9f\n" : "%.9f\t%.9f\t0.0\n", x_mm[i], y_mm[i]);
    text += line;
  }
  return text;
}

TEST(MiniProfReader, RailWithVerticalAxisUpIsTurnedOver) {
  // A measured MiniProf rail has Y up; here: the shipped rail turned by 180 degrees about x.
  const TempDir dir;
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  std::vector<double> x, y;
  for (std::size_t i = 0; i < rail.size(); ++i) {
    x.push_back(-rail.y_m[i] / kMm);
    y.push_back(-rail.z_m[i] / kMm);
  }
  const auto path = dir.file("rail.ban", miniprof_text(x, y, false));
  const Profile p = read_profile(path);
  EXPECT_EQ(p.kind, ProfileKind::rail);
  ASSERT_EQ(p.size(), rail.size());
  for (std::size_t i = 0; i < rail.size(); i += 50) {
    EXPECT_NEAR(p.y_m[i], rail.y_m[i], 1e-11);
    EXPECT_NEAR(p.z_m[i], rail.z_m[i], 1e-11);
  }
  // Without the automatic orientation the columns come as they are.
  ProfileReadOptions as_is;
  as_is.miniprof_auto_vertical = false;
  const Profile raw = read_profile(path, as_is);
  EXPECT_NEAR(raw.y_m[0], x[0] * kMm, 1e-12);
  EXPECT_NEAR(raw.z_m[0], y[0] * kMm, 1e-12);
}

TEST(MiniProfReader, OldStyleWheelFileWithoutColumnDef) {
  const TempDir dir;
  const Profile wheel = read_profile(kProfiles / "MBench_S1002_v3.prw");
  std::vector<double> x, y;
  for (std::size_t i = 0; i < wheel.size(); ++i) {
    x.push_back(wheel.y_m[i] / kMm);
    y.push_back(wheel.z_m[i] / kMm);
  }
  const Profile p = read_profile(dir.file("wheel.WHL", miniprof_text(x, y, true)));
  EXPECT_EQ(p.kind, ProfileKind::wheel);
  ASSERT_EQ(p.size(), wheel.size());
  EXPECT_NEAR(p.y_m.back(), wheel.y_m.back(), 1e-11);
  EXPECT_NEAR(p.z_m.back(), wheel.z_m.back(), 1e-11);
}

TEST(MiniProfReader, MalformedFilesNameFileAndLine) {
  const TempDir dir;
  const auto bad = dir.file("bad.ban", "ColumnDef=X,Y\n\n1 2\n2 3\n3 ; 4 ; x\n4 5\n");
  expect_error_containing([&] { (void)read_profile(bad); }, {"bad.ban:5:"});
  const auto short_row = dir.file("short.ban", "ColumnDef=X,A,Y\n\n1 0 2\n2 0 3\n3 0\n4 0 5\n");
  expect_error_containing([&] { (void)read_profile(short_row); }, {"short.ban:5:"});
  const auto no_x = dir.file("nox.whl", "ColumnDef=A,Y\n\n1 2\n2 3\n3 4\n4 5\n");
  expect_error_containing([&] { (void)read_profile(no_x); }, {"nox.whl:1:", "ColumnDef"});
  const auto no_blank = dir.file("noblank.whl", "ColumnDef=X,Y\n1 2\n2 3\n");
  expect_error_containing([&] { (void)read_profile(no_blank); }, {"noblank.whl", "blank line"});
}

TEST(Profile, MirroringAndValidation) {
  Profile p{{1.0, 2.0, 3.0, 4.0}, {0.5, 0.6, 0.7, 0.8}, ProfileKind::rail, "test"};
  const Profile my = mirrored_y(p);
  EXPECT_DOUBLE_EQ(my.y_m[1], -2.0);
  EXPECT_DOUBLE_EQ(my.z_m[1], 0.6);
  const Profile mz = mirrored_z(p);
  EXPECT_DOUBLE_EQ(mz.z_m[2], -0.7);
  p.z_m[2] = std::nan("");
  EXPECT_THROW(validate(p), Error);
  p.z_m.pop_back();
  EXPECT_THROW(validate(p), Error);
}

// Decimal commas ("0,5 1,25", "12,5;3,4") would be read as twice as many numbers, every reader
// taking the wrong columns: each reader refuses them naming the line, while a single comma-separated
// pair "12,5" (y = 12, z = 5) and decimal points with commas as separators pass.
TEST(ProfileReaders, DecimalCommasAreNamedWithTheirLine) {
  const TempDir dir;
  const auto text = dir.file("comma.txt", "# y z\n-30,5 12,25\n-20,0 1,5\n-10,0 0,25\n0,0 0,0\n10,0 0,25\n");
  expect_error_containing([&] { (void)read_profile(text); }, {"comma.txt:2:", "decimal commas (-30,5)", "(-30.5)"});
  const auto semicolons = dir.file("semicolons.txt", "-30.5 12.25\n-20;1\n12,5;3,4\n0 0\n10 0.25\n");
  expect_error_containing([&] { (void)read_profile(semicolons); }, {"semicolons.txt:3:", "decimal commas (12,5)"});
  const std::string head = "spline.begin\n units.len.f = 1000\n point.begin\n";
  const auto simpack = dir.file("comma.prr", head + "-30,5 12,25\n-20,0 1,5\n-10,0 0,25\n0,0 0,0\n point.end\n");
  expect_error_containing([&] { (void)read_profile(simpack); }, {"comma.prr:4:", "decimal commas"});
  const auto miniprof = dir.file("comma.ban", "ColumnDef=X,Y\n\n-30,5\t12,25\n-20,0\t1,5\n-10,0\t0,25\n0,0\t0,0\n");
  expect_error_containing([&] { (void)read_profile(miniprof); }, {"comma.ban:3:", "decimal commas"});
  // Comma-separated pairs and decimal points are read as before (15 mm wide).
  const Profile pairs = read_profile(dir.file("pairs.txt", "0,2\n5,3\n10,4\n15,5\n"));
  EXPECT_DOUBLE_EQ(pairs.y_m[1], 5 * kMm);
  EXPECT_DOUBLE_EQ(pairs.z_m[1], 3 * kMm);
  const Profile points = read_profile(dir.file("points.txt", "0.5, 2\n5.5, 3\n10.5,4\n15.5;5\n"));
  EXPECT_DOUBLE_EQ(points.y_m[3], 15.5 * kMm);
}

// An undercut profile (the gauge face overhangs: y goes back along the points) is not a graph
// z(y), which the contact search takes: the part under the overhang is missing from it (a flange
// contact there would fail with a message about the load). validate names the overhang (read_profile
// first curates it, tests/profile_curation_test.cpp), as tests/data/uic60_undercut.prr is made: the gauge face below z = 20 mm leans back
// under the head by 0.15 mm per mm. The shipped profiles, whose y is monotonic, pass, and so does
// an overhang of measurement noise (ProfileLimits::max_lateral_retreat_m).
TEST(Profile, UndercutProfileNamesTheOverhang) {
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  EXPECT_NO_THROW(validate(read_profile(kProfiles / "MBench_S1002_v3.prw")));
  Profile undercut = rail;
  undercut.source = "undercut";
  const double y20 = -43.251229 * kMm;
  for (std::size_t i = 0; i < undercut.size(); ++i)
    if (undercut.y_m[i] < -40 * kMm && undercut.z_m[i] > 20 * kMm) undercut.y_m[i] = y20 + 0.15 * (undercut.z_m[i] - 20 * kMm);
  expect_error_containing([&] { validate(undercut); },
                          {"profile undercut: the profile is undercut: between point 1 (y = -40.4746 mm", "overhangs by 2.7",
                           "z(y)"});
  // A ripple of 0.015 mm amplitude and 1 mm wavelength on the gauge face, steeper than its lean: y
  // goes back by up to 0.03 mm, within the allowed 0.05 mm.
  Profile noisy = rail;
  bool goes_back = false;
  for (std::size_t i = 0; i < noisy.size(); ++i)
    if (noisy.y_m[i] < -42.5 * kMm) noisy.y_m[i] += 0.015 * kMm * std::sin(2 * M_PI * noisy.z_m[i] / kMm);
  for (std::size_t i = 0; i + 1 < noisy.size(); ++i) goes_back = goes_back || noisy.y_m[i + 1] < noisy.y_m[i];
  EXPECT_TRUE(goes_back);
  EXPECT_NO_THROW(validate(noisy));
}

// Points on the lower half of a circle of radius R (z down: z = R - sqrt(R^2 - y^2), curvature
// +1/R), rounded like the shipped files (1e-6 mm).
Profile circle_profile(double radius_m, double half_width_m, double spacing_m) {
  Profile p;
  p.source = "circle";
  const int n = static_cast<int>(std::round(2.0 * half_width_m / spacing_m));
  for (int k = 0; k <= n; ++k) {
    const double y = -half_width_m + k * spacing_m;
    const double z = radius_m - std::sqrt(radius_m * radius_m - y * y);
    p.y_m.push_back(std::round(y * 1e9) * 1e-9);
    p.z_m.push_back(std::round(z * 1e9) * 1e-9);
  }
  return p;
}

TEST(SmoothProfile, ReproducesCircleCurvature) {
  const double radius = 0.3;
  const SmoothProfile s(circle_profile(radius, 0.06, 0.5e-3));
  for (double y = -0.05; y <= 0.05; y += 0.005) {
    EXPECT_NEAR(s.curvature_per_m(y), 1.0 / radius, 0.01 / radius) << "y = " << y;
    const double root = std::sqrt(radius * radius - y * y);
    EXPECT_NEAR(s.z(y), radius - root, 1e-8);
    EXPECT_NEAR(s.dz_dy(y), y / root, 1e-5);
    EXPECT_NEAR(s.d2z_dy2_per_m(y), radius * radius / (root * root * root), 0.01 / radius);
  }
}

TEST(SmoothProfile, ReproducesSmallArcAndNoisyCircle) {
  // The flange-root radius of S1002 is about 13 mm.
  const double radius = 0.013;
  const SmoothProfile s(circle_profile(radius, 0.009, 0.2e-3));
  for (double y = -0.006; y <= 0.006; y += 0.001) {
    EXPECT_NEAR(s.curvature_per_m(y), 1.0 / radius, 0.01 / radius) << "y = " << y;
  }
  // Measurement-like noise of 2 µm needs a longer smoothing length.
  Profile noisy = circle_profile(0.3, 0.06, 0.25e-3);
  unsigned state = 12345u;
  for (auto& z : noisy.z_m) {
    state = state * 1664525u + 1013904223u;
    z += 2e-6 * (static_cast<double>(state >> 8) / static_cast<double>(1u << 24) - 0.5) * 2.0;
  }
  SmoothingOptions smoothing;
  smoothing.smoothing_length_m = 5e-3;
  smoothing.knot_spacing_m = 1e-3;
  const SmoothProfile sn(noisy, smoothing);
  for (double y = -0.04; y <= 0.04; y += 0.005) {
    EXPECT_NEAR(sn.curvature_per_m(y), 1.0 / 0.3, 0.05 / 0.3) << "y = " << y;
  }
}

TEST(SmoothProfile, FollowsTheShippedPoints) {
  const Profile wheel = read_profile(kProfiles / "MBench_S1002_v3.prw");
  const SmoothProfile s(wheel);
  EXPECT_EQ(s.kind(), ProfileKind::wheel);
  // y grows along the curve even though the file order runs from +y to -y.
  EXPECT_DOUBLE_EQ(s.y_min_m(), s.at(s.s_begin_m()).y_m);
  EXPECT_NEAR(s.y_min_m(), wheel.y_m.back(), 5e-6);
  EXPECT_NEAR(s.y_max_m(), wheel.y_m.front(), 5e-6);
  // Distance from the points to the curve, normal to it: within 5 µm everywhere (largest at
  // the curvature jumps of the flange root).
  double worst = 0.0;
  for (std::size_t i = 1; i + 1 < wheel.size(); ++i) {
    const double y = wheel.y_m[i];
    const double slope = s.dz_dy(y);
    worst = std::max(worst, std::abs(s.z(y) - wheel.z_m[i]) / std::sqrt(1.0 + slope * slope));
  }
  EXPECT_LT(worst, 5e-6);
  // Near the taping line S1002 is smooth: the curvature there is about 3.1 1/m.
  EXPECT_NEAR(s.curvature_per_m(0.0), 3.11, 0.02);
  EXPECT_THROW((void)s.z(0.2), Error);
}

// SmoothProfile evaluates its cubic B-spline piecewise (a Taylor expansion per knot interval, built
// from Eigen's Spline): the pieces must join as a cubic spline does (value, slope and second
// derivative continuous at every knot) and the derivatives must be those of the values.
TEST(SmoothProfile, PiecewiseEvaluationIsATwiceContinuousCubicSpline) {
  const Profile wheel = read_profile(kProfiles / "MBench_S1002_v3.prw");
  const SmoothingOptions options;
  const SmoothProfile s(wheel, options);
  const double length = s.s_end_m() - s.s_begin_m();
  const int intervals = std::max(4, static_cast<int>(std::ceil(length / options.knot_spacing_m)));
  const double h = length / intervals;
  double value = 0.0, slope = 0.0, second = 0.0;
  for (int k = 1; k < intervals; ++k) {
    const double knot = k * h;
    const ProfileCurvePoint left = s.at(knot - 1e-12), right = s.at(knot + 1e-12);
    value = std::max({value, std::abs(left.y_m - right.y_m), std::abs(left.z_m - right.z_m)});
    slope = std::max({slope, std::abs(left.dy_ds - right.dy_ds), std::abs(left.dz_ds - right.dz_ds)});
    second = std::max({second, std::abs(left.d2y_ds2_per_m - right.d2y_ds2_per_m),
                       std::abs(left.d2z_ds2_per_m - right.d2z_ds2_per_m)});
  }
  EXPECT_LT(value, 1e-11);   // m (2e-12 m apart)
  EXPECT_LT(slope, 1e-8);    // the slope changes by |z''| 2e-12 ~ 1e-10 across the gap
  EXPECT_LT(second, 1e-3);   // 1/m, against curvatures up to ~100 1/m at the flange root
  // Central differences of the values give the first derivatives, and of those the second.
  for (double at = 0.3 * h; at < length; at += 37.3 * h) {
    const double e = 1e-6;
    const ProfileCurvePoint m = s.at(at - e), c = s.at(at), p = s.at(at + e);
    EXPECT_NEAR((p.y_m - m.y_m) / (2 * e), c.dy_ds, 1e-6) << "s = " << at;
    EXPECT_NEAR((p.z_m - m.z_m) / (2 * e), c.dz_ds, 1e-6) << "s = " << at;
    EXPECT_NEAR((p.dz_ds - m.dz_ds) / (2 * e), c.d2z_ds2_per_m, 1e-3 * (1.0 + std::abs(c.d2z_ds2_per_m)))
        << "s = " << at;
  }
}

}  // namespace
}  // namespace railcontact
