// Resource limits (docs/RELIABILITY.md "Resource limits"): a mesh or a table that would need more
// memory or time than a machine has is refused before it is allocated or built, with the figure
// it would need, and robustness fixes of the JSON readers found while fuzzing them (fuzz/).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "railcontact/error.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/wheel_rail.hpp"
#include "wheel_rail/wheel_rail_setup.hpp"

namespace railcontact {
namespace {

struct Failure {
  bool thrown = false;
  ErrorKind kind = ErrorKind::internal;
  std::string message;
};

Failure failure_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return {true, e.kind(), e.what()};
  }
  return {};
}

void expect_parts(const Failure& f, std::initializer_list<const char*> parts) {
  ASSERT_TRUE(f.thrown);
  EXPECT_EQ(f.kind, ErrorKind::invalid_input) << f.message;
  for (const char* part : parts) EXPECT_NE(f.message.find(part), std::string::npos) << part << " in: " << f.message;
}

// A potential contact area of ~8e6 elements (beyond the 4e6 allowed, within the 16.8e6 a mesh may
// have) is refused with its size and memory before h is computed on it.
TEST(ResourceLimits, PotentialContactAreaBeyondItsMemoryIsRefusedWithTheFigure) {
  const WheelRailPair pair = default_wheel_rail_pair();
  const WheelRailContactPoint c = pair.contact_point(0.0);
  const double approach = hertz_from_curvatures(c.A_per_m, c.B_per_m, 98100.0, Material{}).approach_m;
  PotentialAreaOptions options;
  options.dx1_m = options.dx2_m = 0.1e-3;
  const PotentialContactArea area = potential_contact_area(pair, c, approach, options);
  const double elements = static_cast<double>(area.mesh.size());
  ASSERT_LT(elements, kMaximumPotentialAreaElements);
  // The same area with elements sqrt(elements / 8e6) times as large along each axis.
  options.dx1_m = options.dx2_m = 0.1e-3 * std::sqrt(elements / 8e6);
  const Failure f = failure_of([&] { (void)potential_contact_area(pair, c, approach, options); });
  expect_parts(f, {"potential contact area: a mesh of", "elements of", "would need about", "GiB for the normal solve",
                   "at most 4e+06 elements (1.49 GiB) are allowed"});
  // Elements so small that their count overflows an int: refused, not wrapped.
  options.dx1_m = options.dx2_m = 1e-12;
  expect_parts(failure_of([&] { (void)potential_contact_area(pair, c, approach, options); }),
               {"potential contact area: a mesh of", "would need about"});
}

// A build whose work (nodes × elements^1.5) exceeds the cap is refused before the first node, by
// the library and by the CLI (bad_input_catalogue.tsv).
TEST(ResourceLimits, FlexibilityTableBuildBeyondItsWorkIsRefusedBeforeTheFirstNode) {
  EXPECT_NO_THROW(check_flexibility_table_work(100, 20, 3000));      // a paper-size table: 2000 nodes
  EXPECT_NO_THROW(check_flexibility_table_work(10000, 20, 3000));    // the largest grid at 3000 elements
  expect_parts(failure_of([] { check_flexibility_table_work(5001, 1, 200000); }),
               {"flexibility table: 5001 y values × 1 load = 5001 nodes at 200000 elements in contact would take about",
                "hours", "at most the work of 200000 nodes at 3000 elements (about 5.6 hours) is allowed"});
  FlexibilityTableOptions options;
  options.patch.target_elements = 200000;
  int nodes = 0;
  const Failure f = failure_of([&] {
    (void)build_flexibility_table(default_wheel_rail_pair(), flexibility_table_y_grid(-5e-3, 5e-3, 0.01e-3), {98100.0},
                                  options, [&](const FlexibilityTableProgress&) { ++nodes; });
  });
  expect_parts(f, {" y values × 1 load = ", "nodes at 200000 elements in contact would take about"});
  EXPECT_EQ(nodes, 0);
}

// A table file whose grids would hold more nodes than a build can make is refused on the sizes of
// its y and load lists, before its nodes are read.
TEST(ResourceLimits, FlexibilityTableWithTooManyNodesIsRefusedBeforeItsNodes) {
  nlohmann::json y = nlohmann::json::array(), loads = nlohmann::json::array();
  for (int k = 0; k < 2001; ++k) y.push_back(k);
  for (int k = 1; k <= 1001; ++k) loads.push_back(k);
  const std::string text = nlohmann::json{{"format", "railcontact flexibility table"},
                                          {"format_version", 2},
                                          {"railcontact_version", "0"},
                                          {"created_utc", ""},
                                          {"profiles",
                                           {{"wheel", {{"file", "w"}, {"fnv1a64", "0000000000000000"}}},
                                            {"rail", {{"file", "r"}, {"fnv1a64", "0000000000000000"}}}}},
                                          {"track",
                                           {{"track_gauge_m", 1.435},
                                            {"gauge_measuring_depth_m", 0.014},
                                            {"flange_back_distance_m", 1.36},
                                            {"flange_back_y_m", -0.07},
                                            {"taping_line_from_flange_back_m", 0.07},
                                            {"nominal_rolling_radius_m", 0.46}}},
                                          {"material", {{"youngs_modulus_Pa", 2.1e11}, {"poisson_ratio", 0.3}}},
                                          {"target_elements", 3000},
                                          {"collocation_offset", 0.0},
                                          {"flexibility_coarsening", 0},
                                          {"flexibility_match", "term-by-term"},
                                          {"y_m", y},
                                          {"vertical_load_N", loads},
                                          {"contact_jumps", nlohmann::json::array()},
                                          {"nodes", nlohmann::json::array()}}
                               .dump();
  expect_parts(failure_of([&] { (void)parse_flexibility_table(text, "big.json"); }),
               {"flexibility table big.json: 2001 y values × 1001 loads = 2.003e+06 nodes; at most 2e+06 nodes are read"});
}

// Fuzzing findings (fuzz/crashes/): a number beyond the range of a double made nlohmann throw
// out_of_range, which escaped as an internal error (exit 70); a value nested a million levels deep
// overflowed the stack when quoted in a message.
TEST(JsonReaders, NumberOverflowIsBadInputNotAnInternalError) {
  expect_parts(failure_of([] { (void)parse_flexibility_table("{\"format_version\": 1e999}", "t.json"); }),
               {"flexibility table t.json: malformed JSON: number overflow parsing '1e999'", "is not finite"});
  expect_parts(failure_of([] {
                 (void)wheel_rail::parse_wheel_rail_setup("{\"track\": {\"track_gauge_m\": -1e999}}", "/s/setup.json");
               }),
               {"wheel-rail set-up /s/setup.json: malformed JSON: number overflow parsing '-1e999'"});
}

TEST(JsonReaders, DeeplyNestedValuesAreQuotedByTheirKind) {
  const std::string nested = std::string(1000000, '[') + std::string(1000000, ']');
  expect_parts(failure_of([&] {
                 (void)parse_flexibility_table(
                     "{\"format\": \"railcontact flexibility table\", \"format_version\": " + nested + "}", "t.json");
               }),
               {"format_version a list is not supported"});
  expect_parts(failure_of([&] {
                 (void)wheel_rail::parse_wheel_rail_setup(
                     "{\"wheel_profile\": \"w\", \"rail_profile\": \"r\", \"track\": {\"track_gauge_m\": " + nested + "}}",
                     "/s/setup.json");
               }),
               {"'track_gauge_m' must be a finite number (got a list)"});
}

// A contact jump naming the interval 2^64 - 1: interval + 1 wrapped to 0 and passed the bound
// check, then y[2^64 - 1] was read (UBSan: pointer overflow; found by the flexibility_table fuzz
// target, fuzz/crashes/flexibility_table/). The constructor had the same check.
TEST(JsonReaders, AContactJumpBeyondTheGridIsRefusedNotRead) {
  std::ifstream file(std::string(RAILCONTACT_SOURCE_DIR) + "/fuzz/corpus/flexibility_table/s1002_uic60_3_nodes.json");
  nlohmann::json table = nlohmann::json::parse(file);
  table["contact_jumps"] = nlohmann::json::array({nlohmann::json{{"interval", 18446744073709551615ull},
                                                                 {"y_left_m", 0.0},
                                                                 {"y_right_m", 0.00025},
                                                                 {"y_rail_left_m", 0.0},
                                                                 {"y_rail_right_m", 0.0}}});
  expect_parts(failure_of([&] { (void)parse_flexibility_table(table.dump(), "t.json"); }),
               {"flexibility table t.json: contact_jumps[0] does not name an interval of y_m"});
  table["contact_jumps"] = nlohmann::json::array();
  const FlexibilityTable good = parse_flexibility_table(table.dump(), "t.json");
  expect_parts(failure_of([&] {
                 (void)FlexibilityTable(good.metadata(), good.y_m(), good.vertical_loads_N(), good.nodes(),
                                        {ContactJump{static_cast<std::size_t>(-1), 0.0, 0.0}});
               }),
               {"a contact jump names a missing or repeated y interval"});
}

}  // namespace
}  // namespace railcontact
