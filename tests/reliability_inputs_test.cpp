// Bad input files (issue 14, docs/RELIABILITY.md "Input files"): every reader refuses what is not
// a regular file of a sensible size, case files that are not UTF-8, implausible profiles (shuffled,
// repeated or crossing points, wrong extent or length unit) and implausible flexibility tables,
// with one message naming the input; file content is quoted escaped; relative profile paths of a
// case file are relative to the case file. Test data are written to ::testing::TempDir() and
// removed afterwards.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "case/case.hpp"
#include "cli_run.hpp"
#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;

const fs::path kProfiles = fs::path(RAILCONTACT_DATA_DIR) / "profiles";

// A fresh directory per test (ctest runs tests in parallel processes), removed afterwards.
class Scratch {
 public:
  Scratch() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::path(::testing::TempDir()) /
            (std::string("railcontact_reliability_") + info->test_suite_name() + "_" + info->name() + "_" +
             std::to_string(getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Scratch() { fs::remove_all(path_); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }
  [[nodiscard]] fs::path file(const std::string& name, const std::string& bytes) const {
    const fs::path p = path_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

 private:
  fs::path path_;
};

// The working directory changed for the lifetime of the object.
class WorkingDirectory {
 public:
  explicit WorkingDirectory(const fs::path& directory) : previous_(fs::current_path()) { fs::current_path(directory); }
  ~WorkingDirectory() { fs::current_path(previous_); }
  WorkingDirectory(const WorkingDirectory&) = delete;
  WorkingDirectory& operator=(const WorkingDirectory&) = delete;

 private:
  fs::path previous_;
};

// The Error thrown by fn (kind and message); fails the test when none is thrown.
struct Thrown {
  ErrorKind kind = ErrorKind::internal;
  std::string message;
};
Thrown error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return {e.kind(), e.what()};
  }
  ADD_FAILURE() << "no railcontact::Error thrown";
  return {};
}

void expect_contains(const std::string& message, const std::vector<std::string>& parts) {
  for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\nmissing: " << part;
}

// The CLI under a time and memory limit: a reader that hangs or reads an endless device fails
// the test in seconds instead of blocking the suite or exhausting the machine's memory.
CommandResult run_cli_bounded(const std::string& arguments) {
  return test::run_cli(arguments, test::bounded_run_prefix(8000000, 120));
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The point lines of a SIMPACK file (between point.begin and point.end) and the rest.
struct SimpackParts {
  std::string head, tail;
  std::vector<std::string> points;
};
SimpackParts split_simpack(const std::string& text) {
  SimpackParts parts;
  std::istringstream in(text);
  std::string line;
  int section = 0;  // 0 head, 1 points, 2 tail
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t");
    const std::string trimmed = first == std::string::npos ? "" : line.substr(first);
    if (section == 1 && trimmed.rfind("point.end", 0) == 0) section = 2;
    if (section == 1 && !trimmed.empty() && trimmed[0] != '!') {
      parts.points.push_back(line);
      continue;
    }
    (section == 2 ? parts.tail : parts.head) += line + "\n";
    if (section == 0 && trimmed.rfind("point.begin", 0) == 0) section = 1;
  }
  return parts;
}
std::string join_simpack(const SimpackParts& parts) {
  std::string text = parts.head;
  for (const auto& p : parts.points) text += p + "\n";
  return text + parts.tail;
}

const std::string kEllipseCase =
    "[geometry]\ntype = \"ellipse\"\na = 0.006\nb = 0.004\n[material]\nE = 2.1e11\nnu = 0.3\n"
    "[load]\nnormal_force = 98100.0\n[friction]\nmu = 0.3\n[creepage]\nxi = 0.001\n";

// ---- item 8: not a regular file, too large ---------------------------------------------------

TEST(ReadTextFile, RefusesDirectoriesDevicesMissingAndOversizedFiles) {
  const Scratch dir;
  const auto directory = error_of([&] { (void)read_text_file(dir.path(), "case file", 1000); });
  EXPECT_EQ(directory.kind, ErrorKind::io);
  expect_contains(directory.message, {"case file", dir.path().string(), "is a directory"});
  const auto device = error_of([] { (void)read_text_file("/dev/zero", "profile", 1000); });
  EXPECT_EQ(device.kind, ErrorKind::io);
  expect_contains(device.message, {"/dev/zero", "character device", "not a regular file"});
  const auto missing = error_of([&] { (void)read_text_file(dir.path() / "none.toml", "case file", 1000); });
  EXPECT_EQ(missing.kind, ErrorKind::io);
  expect_contains(missing.message, {"none.toml", "cannot open", "no such file"});
  const fs::path fifo = dir.path() / "pipe";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const auto pipe = error_of([&] { (void)read_text_file(fifo, "profile", 1000); });  // would block in open()
  EXPECT_EQ(pipe.kind, ErrorKind::io);
  expect_contains(pipe.message, {"FIFO"});
  const fs::path big = dir.file("big.txt", std::string(1001, 'x'));
  const auto large = error_of([&] { (void)read_text_file(big, "profile", 1000); });
  EXPECT_EQ(large.kind, ErrorKind::invalid_input);
  expect_contains(large.message, {"big.txt", "too large", "1001 bytes", "at most 1000 bytes"});
  EXPECT_EQ(read_text_file(dir.file("ok.txt", std::string(1000, 'y')), "profile", 1000), std::string(1000, 'y'));
}

TEST(ReadTextFile, EveryReaderRefusesADirectory) {
  const Scratch dir;
  const fs::path d = dir.path() / "folder.prr";
  fs::create_directories(d);
  for (const auto& read : std::vector<std::function<void()>>{
           [&] { (void)read_case_file(d); },
           [&] { (void)read_profile(d); },
           [&] { (void)read_simpack_profile(d); },
           [&] { (void)read_miniprof_profile(d); },
           [&] { (void)read_text_profile(d); },
           [&] { (void)load_flexibility_table(d); },
           [&] { (void)read_wheel_rail_setup(d); },
       }) {
    const auto e = error_of(read);
    EXPECT_EQ(e.kind, ErrorKind::io) << e.message;
    expect_contains(e.message, {"folder.prr", "is a directory"});
  }
}

TEST(ReadTextFile, OversizedInputsAreRefusedBeforeReading) {
  const Scratch dir;
  // Sparse files: their size is what is checked, nothing is read.
  const auto sized = [&](const std::string& name, std::uintmax_t bytes) {
    const fs::path p = dir.file(name, "");
    fs::resize_file(p, bytes);
    return p;
  };
  const auto case_file = error_of([&] { (void)read_case_file(sized("case.toml", (1u << 20) + 1)); });
  EXPECT_EQ(case_file.kind, ErrorKind::invalid_input);
  expect_contains(case_file.message, {"case file", "case.toml", "too large", "1048577 bytes", "1 MiB"});
  const auto profile = error_of([&] { (void)read_profile(sized("rail.prr", (16u << 20) + 1)); });
  expect_contains(profile.message, {"profile", "rail.prr", "too large", "16 MiB"});
  const auto table = error_of([&] { (void)load_flexibility_table(sized("table.json", (256u << 20) + 1)); });
  expect_contains(table.message, {"flexibility table", "table.json", "too large", "256 MiB"});
  const auto setup = error_of([&] { (void)read_wheel_rail_setup(sized("setup.json", (1u << 20) + 1)); });
  expect_contains(setup.message, {"wheel-rail set-up", "setup.json", "too large"});
}

TEST(ReliabilityCli, RunOnADirectoryOrADeviceSaysSoAtOnce) {
  const Scratch dir;
  // Was: "missing section [geometry]" for a directory; a hang for /dev/zero.
  const CommandResult directory = run_cli_bounded("run " + dir.path().string());
  test::expect_one_error_line(directory, "is a directory");
  EXPECT_EQ(directory.exit_code, 3);  // io
  const CommandResult zero = run_cli_bounded("run /dev/zero");
  test::expect_one_error_line(zero, "/dev/zero");
  EXPECT_EQ(zero.exit_code, 3);
  const fs::path fifo = dir.path() / "case.toml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const CommandResult pipe = run_cli_bounded("run " + fifo.string());
  test::expect_one_error_line(pipe, "FIFO");
  EXPECT_EQ(pipe.exit_code, 3);
  const CommandResult table = run_cli_bounded(std::string("run --flextable /dev/zero"));
  test::expect_one_error_line(table, "/dev/zero");
}

// ---- item 6: case files must be UTF-8 ----------------------------------------------------------

TEST(CaseFileUtf8, Latin1BytesAreRefusedWithLineAndColumn) {
  // "x=1§" saved as Latin-1: § is the single byte 0xA7 (undefined behaviour in toml++ 3.3.0).
  const auto short_case = error_of([] { (void)parse_case("x=1\xA7", "latin1.toml"); });
  EXPECT_EQ(short_case.kind, ErrorKind::invalid_input);
  expect_contains(short_case.message, {"latin1.toml:1:", "0xA7", "column 4", "UTF-8"});
  // Column in characters: "é" (two bytes in UTF-8) counts once.
  const Scratch dir;
  const fs::path file = dir.file("case.toml", kEllipseCase + "# \xC3\xA9t\xE9\n");
  const auto in_file = error_of([&] { (void)read_case_file(file); });
  const int line = 1 + static_cast<int>(std::count(kEllipseCase.begin(), kEllipseCase.end(), '\n'));
  expect_contains(in_file.message, {"case.toml:" + std::to_string(line) + ":", "0xE9", "column 5"});
  // Truncated and overlong sequences, surrogates.
  for (const std::string bad : {"a = \"\xE2\x82\"", "a = \"\xC0\xAF\"", "a = \"\xED\xA0\x80\"", "\xFF"}) {
    const auto e = error_of([&] { (void)parse_case(bad, "bad.toml"); });
    expect_contains(e.message, {"bad.toml:1:", "is not UTF-8"});
  }
  // Valid UTF-8 outside ASCII is still TOML's business (here: fine in a comment).
  EXPECT_NO_THROW((void)parse_case(kEllipseCase + "# \xC3\xA9t\xC3\xA9, 30 \xC2\xB0\x43\n", "utf8.toml"));
}

TEST(Utf8, ValidPrefix) {
  EXPECT_EQ(valid_utf8_prefix(""), 0u);
  EXPECT_EQ(valid_utf8_prefix("abc"), 3u);
  EXPECT_EQ(valid_utf8_prefix("\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80"), 9u);  // é € 😀
  EXPECT_EQ(valid_utf8_prefix("ab\xA7"), 2u);
  EXPECT_EQ(valid_utf8_prefix("\xF4\x90\x80\x80"), 0u);  // above U+10FFFF
  EXPECT_EQ(valid_utf8_prefix("\xE0\x80\xAF"), 0u);      // overlong
}

// ---- item 7 (part): file content quoted escaped and short --------------------------------------

TEST(QuotedContent, PrintableExcerptEscapesAndCaps) {
  EXPECT_EQ(printable_excerpt("1 2 abc"), "1 2 abc");
  EXPECT_EQ(printable_excerpt("\x1B[31mred\x07"), "\\x1B[31mred\\x07");
  EXPECT_EQ(printable_excerpt("x\xA7y"), "x\\xA7y");
  EXPECT_EQ(printable_excerpt("\xC3\xA9"), "\xC3\xA9");          // é stays
  EXPECT_EQ(printable_excerpt("a\xE2\x80\xAE" "b"), "a\\u202Eb");  // right-to-left override
  EXPECT_EQ(printable_excerpt(std::string(100, 'z')), std::string(60, 'z') + "…");
  EXPECT_EQ(printable_excerpt(std::string(60, 'z')), std::string(60, 'z'));
}

TEST(QuotedContent, ReadersDoNotEchoUnprintableBytes) {
  const Scratch dir;
  const auto raw_free = [](const std::string& message) {
    for (const char c : message) {
      const auto u = static_cast<unsigned char>(c);
      EXPECT_FALSE(u < 0x20 || u == 0x7F) << "raw control byte " << int(u) << " in: " << message;
    }
    EXPECT_EQ(valid_utf8_prefix(message), message.size()) << message;
  };
  const auto text = error_of([&] { (void)read_profile(dir.file("p.txt", "1 2\n2 3\n\x1B[2J\xA7\xFF garbage\n4 5\n")); });
  raw_free(text.message);
  expect_contains(text.message, {"p.txt:3:", "\\x1B[2J\\xA7\\xFF garbage"});
  const auto simpack = error_of([&] {
    (void)read_profile(dir.file("p.prr", "spline.begin\n units.len.f = 1000\x01\n point.begin\n1 2\n2 3\n3 4\n5 6\n point.end\n"));
  });
  raw_free(simpack.message);
  expect_contains(simpack.message, {"p.prr:2:", "1000\\x01"});
  const auto miniprof = error_of([&] { (void)read_profile(dir.file("p.ban", "ColumnDef=X,Y\n\n1 2\n2 3\n3 \x08\x08\n4 5\n")); });
  raw_free(miniprof.message);
  expect_contains(miniprof.message, {"p.ban:5:", "\\x08"});
  const auto long_line = error_of([&] { (void)read_profile(dir.file("long.txt", "1 2\n" + std::string(5000, 'q') + "\n")); });
  EXPECT_LT(long_line.message.size(), 300u) << long_line.message;
  expect_contains(long_line.message, {"long.txt:2:", "…"});
  // Case files: a key holding control characters (TOML escapes in a quoted key).
  const auto key = error_of([] { (void)parse_case(kEllipseCase + "[mesh]\n\"el\\u001b[2Jements\" = 5\n", "k.toml"); });
  raw_free(key.message);
  expect_contains(key.message, {"k.toml:", "unknown key 'el\\x1B[2Jements'"});
  const auto solver =
      error_of([] { (void)parse_case(kEllipseCase + "[solvers]\nrun = [\"fast\\u0007sim\"]\n", "s.toml"); });
  raw_free(solver.message);
  expect_contains(solver.message, {"unknown solver 'fast\\x07sim'"});
}

// ---- item 2: implausible profiles --------------------------------------------------------------

TEST(ProfileChecks, ShuffledSimpackRailIsRefused) {
  const Scratch dir;
  SimpackParts parts = split_simpack(file_text(kProfiles / "MBench_UIC60_v3.prr"));
  ASSERT_EQ(parts.points.size(), 495u);
  EXPECT_NO_THROW((void)read_profile(dir.file("copy.prr", join_simpack(parts))));  // the copy itself is fine
  // A fixed permutation (a linear congruential shuffle): reproducible.
  unsigned state = 2024u;
  for (std::size_t i = parts.points.size() - 1; i > 0; --i) {
    state = state * 1664525u + 1013904223u;
    std::swap(parts.points[i], parts.points[(state >> 8) % (i + 1)]);
  }
  const fs::path shuffled = dir.file("shuffled.prr", join_simpack(parts));
  const auto e = error_of([&] { (void)read_profile(shuffled); });
  EXPECT_EQ(e.kind, ErrorKind::invalid_input);
  expect_contains(e.message, {"shuffled.prr", "in order along the profile"});
  // Also when built from the point list directly (SmoothProfile validates).
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  Profile swapped = rail;
  std::swap(swapped.y_m[100], swapped.y_m[300]);
  std::swap(swapped.z_m[100], swapped.z_m[300]);
  expect_contains(error_of([&] { (void)SmoothProfile(swapped); }).message, {"in order along the profile"});
}

TEST(ProfileChecks, RepeatedCrossingAndReversingPointsAreRefused) {
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  Profile repeated = rail;
  repeated.y_m.insert(repeated.y_m.begin() + 200, repeated.y_m[200]);
  repeated.z_m.insert(repeated.z_m.begin() + 200, repeated.z_m[200]);
  expect_contains(error_of([&] { validate(repeated); }).message, {"points 201 and 202 coincide"});

  // Along z = 0 to y = 30 mm, back up diagonally, then down across the first leg at y = 25.5 mm.
  Profile crossing{{}, {}, ProfileKind::rail, "crossing"};
  const auto add = [&](double y_mm, double z_mm) {
    crossing.y_m.push_back(y_mm * 1e-3);
    crossing.z_m.push_back(z_mm * 1e-3);
  };
  for (int k = 0; k <= 30; ++k) add(k, 0.0);
  for (int k = 1; k <= 5; ++k) add(30.0 - 0.9 * k, -k);
  for (int k = 1; k <= 10; ++k) add(25.5, -5.0 + k);
  const auto crosses = error_of([&] { validate(crossing); });
  expect_contains(crosses.message, {"crossing", "crosses itself", "in order along the profile"});

  // A spike: one point out and straight back.
  Profile spike = rail;
  spike.y_m[250] = spike.y_m[249] + 0.5 * (spike.y_m[251] - spike.y_m[249]);
  spike.z_m[250] = spike.z_m[249] - 3e-3;
  expect_contains(error_of([&] { validate(spike); }).message, {"turn back at point 251"});
}

TEST(ProfileChecks, ExtentAndUnits) {
  const Scratch dir;
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  // Metres read as millimetres: the rail written in metres, read as the default millimetres.
  const fs::path metres = dir.path() / "rail_in_metres.txt";
  write_text_profile(metres, rail, 1.0);
  const auto tiny = error_of([&] { (void)read_profile(metres); });
  EXPECT_EQ(tiny.kind, ErrorKind::invalid_input);
  expect_contains(tiny.message, {"rail_in_metres.txt", "0.0743 mm laterally", "10 to 400 mm", "metres read as millimetres",
                                 "read as millimetres"});
  // SIMPACK with units.len.f = 1: millimetres read as metres (74 m wide).
  std::string text = file_text(kProfiles / "MBench_UIC60_v3.prr");
  const auto at = text.find("+1.000000000000000e+03");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 22, "1");
  const auto huge = error_of([&] { (void)read_profile(dir.file("len_f_1.prr", text)); });
  expect_contains(huge.message, {"len_f_1.prr", "mm laterally", "millimetres read as metres", "units.len.f = 1 at line 37"});
  // A profile 100 m wide given to the library directly: refused before any spline (was an
  // endless loop in monotone_range, a signed overflow of the knot count and gigabytes of memory).
  Profile wide = rail;
  for (double& y : wide.y_m) y *= 100.0 / 0.0743;
  expect_contains(error_of([&] { (void)SmoothProfile(wide); }).message, {"laterally", "400 mm"});
  expect_contains(error_of([&] { (void)WheelRailPair(read_profile(kProfiles / "MBench_S1002_v3.prw"), wide); }).message,
                  {"laterally"});
  // Too tall, too long between points.
  Profile tall = rail;
  tall.z_m.back() += 0.5;
  expect_contains(error_of([&] { validate(tall); }).message, {"vertically", "at most 200 mm"});
  Profile sparse = rail;
  sparse.y_m.erase(sparse.y_m.begin() + 100, sparse.y_m.begin() + 300);
  sparse.z_m.erase(sparse.z_m.begin() + 100, sparse.z_m.begin() + 300);
  expect_contains(error_of([&] { validate(sparse); }).message, {"points 100 and 101 are", "at most 10 mm apart"});
}

TEST(ProfileChecks, KnotCountIsBoundedBeforeTheSpline) {
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  SmoothingOptions options;
  options.knot_spacing_m = 1e-12;  // 1.3e11 intervals: was a signed overflow (line 77)
  options.smoothing_length_m = 1e-12;
  const auto e = error_of([&] { (void)SmoothProfile(rail, options); });
  EXPECT_EQ(e.kind, ErrorKind::invalid_input);
  expect_contains(e.message, {"knot intervals", "at most 200000"});
}

TEST(ProfileChecks, ShippedProfilesPass) {
  EXPECT_NO_THROW(validate(read_profile(kProfiles / "MBench_UIC60_v3.prr")));
  EXPECT_NO_THROW(validate(read_profile(kProfiles / "MBench_S1002_v3.prw")));
}

// ---- item 10: relative profile paths of a case file --------------------------------------------

std::string wheel_rail_case(const std::string& wheel, const std::string& rail) {
  return "[geometry]\ntype = \"wheel-rail\"\nwheel = \"" + wheel + "\"\nrail = \"" + rail +
         "\"\ny = 0.0\n[material]\nE = 2.1e11\nnu = 0.28\n[load]\nnormal_force = 80000.0\n[friction]\nmu = 0.3\n"
         "[creepage]\nxi = 0.001\n[mesh]\nelements = 300\n[solvers]\nrun = [\"fastsim\"]\n";
}

TEST(CaseFilePaths, RelativeProfilePathsAreRelativeToTheCaseFile) {
  const Scratch dir;
  const fs::path cases = dir.path() / "cases", elsewhere = dir.path() / "elsewhere";
  fs::create_directories(cases / "profiles");
  fs::create_directories(elsewhere);
  fs::copy_file(kProfiles / "MBench_S1002_v3.prw", cases / "wheel.prw");
  fs::copy_file(kProfiles / "MBench_UIC60_v3.prr", cases / "profiles" / "rail.prr");
  const fs::path case_file = cases / "case.toml";
  std::ofstream(case_file) << wheel_rail_case("wheel.prw", "profiles/rail.prr");
  const WorkingDirectory cwd(elsewhere);
  const Case c = read_case_file(case_file);
  EXPECT_EQ(fs::path(c.wheel_rail.wheel_file), cases / "wheel.prw");
  EXPECT_EQ(fs::path(c.wheel_rail.rail_file), cases / "profiles" / "rail.prr");
  // A relative case path: relative to the working directory, then the profiles to the case.
  const Case relative = read_case_file(fs::path("..") / "cases" / "case.toml");
  EXPECT_EQ(fs::path(relative.wheel_rail.wheel_file), fs::path("../cases/wheel.prw"));
  EXPECT_TRUE(fs::exists(relative.wheel_rail.wheel_file));
  // Absolute paths stay; parse_case without a directory keeps paths relative to the working directory.
  const Case absolute = parse_case(wheel_rail_case((cases / "wheel.prw").string(), "rail.prr"), "t.toml", cases);
  EXPECT_EQ(fs::path(absolute.wheel_rail.wheel_file), cases / "wheel.prw");
  EXPECT_EQ(parse_case(wheel_rail_case("wheel.prw", "rail.prr"), "t.toml").wheel_rail.wheel_file, "wheel.prw");
  // The CLI, run from another directory, finds the profiles next to the case file.
  const CommandResult run = run_cli_bounded("run --json " + case_file.string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("\"fastsim\""), std::string::npos) << run.out;
}

// ---- item 5: flexibility-table node values and recipe -----------------------------------------

FlexibilityTable synthetic_table(int coarsening) {
  FlexibilityTableMetadata m;
  m.wheel_profile = {"wheel.prw", 1};
  m.rail_profile = {"rail.prr", 2};
  m.material = Material{2.1e11, 0.28};
  m.target_elements = 1000;
  m.collocation_offset = 0.0;
  m.flexibility_coarsening = coarsening;
  m.railcontact_version = "test";
  m.created_utc = "2024-01-01T00:00:00Z";
  const std::vector<double> y{-1e-3, 0.0, 1e-3}, loads{5e4, 1e5};
  std::vector<FlexibilityTableNode> nodes;
  for (const double yi : y) {
    for (const double Fz : loads) {
      FlexibilityTableNode n;
      n.y_m = yi;
      n.vertical_load_N = Fz;
      n.flexibility = {5e-14, 6e-14, 7e-14};
      n.f11_N = 1.2e7;
      n.f22_N = 1.1e7;
      n.f23_Nm = 3e4;
      n.normal_force_N = Fz * 1.01;
      n.contact_angle_rad = 0.03;
      n.spin_per_m = -0.06;
      n.area_m2 = 1.2e-4;
      n.elements_in_contact = 1000;
      nodes.push_back(n);
    }
  }
  return FlexibilityTable(m, y, loads, nodes);
}

TEST(FlexibilityTableChecks, ImplausibleNodeValuesNameTheNodeAndKey) {
  const nlohmann::json good = nlohmann::json::parse(flexibility_table_json(synthetic_table(1)));
  EXPECT_NO_THROW((void)parse_flexibility_table(good.dump(), "good.json"));
  struct Bad {
    const char* key;
    double value;
    const char* allowed;
  };
  for (const Bad& bad : {Bad{"L1_m_per_Pa", 1e300, "0 < L1 < 1e-6 m/Pa"}, Bad{"L3_m_per_Pa", 2e-6, "L3"},
                         Bad{"f11_N", 1e300, "f11"}, Bad{"f23_Nm", 1e20, "f23"},
                         Bad{"normal_force_N", 1e300, "1e8 N"}, Bad{"contact_angle_rad", 2.0, "1.5 rad"},
                         Bad{"area_m2", 0.5, "0.01 m2"}, Bad{"spin_per_m", 1e6, "100 1/m"}}) {
    nlohmann::json table = good;
    table["nodes"][3][bad.key] = bad.value;
    const auto e = error_of([&] { (void)parse_flexibility_table(table.dump(), "bad.json"); });
    EXPECT_EQ(e.kind, ErrorKind::invalid_input);
    expect_contains(e.message, {"flexibility table bad.json", "nodes[3]", bad.key, bad.allowed, "not plausible"});
  }
  nlohmann::json no_elements = good;
  no_elements["nodes"][2]["elements_in_contact"] = 0;
  expect_contains(error_of([&] { (void)parse_flexibility_table(no_elements.dump(), "t.json"); }).message,
                  {"nodes[2]", "elements_in_contact"});
  // The status string is quoted escaped.
  nlohmann::json status = good;
  status["nodes"][0]["status"] = "so\x1b[2Jlved";
  expect_contains(error_of([&] { (void)parse_flexibility_table(status.dump(), "t.json"); }).message,
                  {"so\\x1B[2Jlved"});
}

TEST(FlexibilityTableChecks, RecipeMustMatch) {
  const FlexibilityTable table = synthetic_table(1);
  EXPECT_NO_THROW(table.check_recipe(1, 0.0));
  expect_contains(error_of([&] { table.check_recipe(0, 0.0); }).message,
                  {"flexibility coarsening 1", "used with 0 (automatic)"});
  expect_contains(error_of([&] { table.check_recipe(2, 0.0); }).message, {"flexibility coarsening 1", "used with 2"});
  expect_contains(error_of([&] { table.check_recipe(1, 0.5); }).message, {"collocation offset alpha = 0", "given 0.5"});
  EXPECT_NO_THROW(synthetic_table(0).check_recipe(0, 0.0));
}

}  // namespace
}  // namespace railcontact
