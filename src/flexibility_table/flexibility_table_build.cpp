// Building a flexibility table (docs/FLEXTABLE.md §2): contact jumps located on the geometry
// alone, then per node (y, Fz) the wheel–rail patch, K2's force rows and the term-by-term
// nH-FastSim flexibilities, exactly as a wheel–rail case computes them on the fly.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <mutex>
#include <optional>

#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/text_file.hpp"
#include "railcontact/flexibility_table.hpp"
#include "flexibility_table/table_json.hpp"
#include "railcontact/version.h"

namespace railcontact {
namespace {

constexpr double kMm = 1e-3;
constexpr std::size_t kMaxYValues = kMaximumFlexibilityTableYValues;
constexpr std::size_t kMaxLoads = kMaximumFlexibilityTableLoads;

using Clock = std::chrono::steady_clock;

std::optional<WheelRailContactPoint> try_contact_point(const WheelRailPair& pair, double y_m) {
  try {
    return pair.contact_point(y_m);
  } catch (const Error&) {
    return std::nullopt;  // the node at this y fails and reports why
  }
}

double first_touch_change_m(const WheelRailContactPoint& a, const WheelRailContactPoint& b) {
  return std::max(std::fabs(a.y_rail_m - b.y_rail_m), std::fabs(a.y_wheel_m - b.y_wheel_m));
}

struct JumpBracket {
  double y_left_m, y_right_m;
  double y_rail_left_m, y_rail_right_m;
};

// Bisects [a, b] while the first-touch point moves by more than the threshold: a piece no longer
// than the resolution across which it still moves that much holds a jump. A continuous motion
// ends the recursion after about (its extent / threshold) pieces.
void find_jumps(const WheelRailPair& pair, double a, const WheelRailContactPoint& ca, double b,
                const WheelRailContactPoint& cb, const FlexibilityTableOptions& options, std::vector<JumpBracket>& jumps) {
  if (first_touch_change_m(ca, cb) <= options.contact_jump_m) return;
  if (b - a <= options.contact_jump_resolution_m) {
    jumps.push_back({a, b, ca.y_rail_m, cb.y_rail_m});
    return;
  }
  const double m = 0.5 * (a + b);
  const std::optional<WheelRailContactPoint> cm = try_contact_point(pair, m);
  if (!cm) return;
  find_jumps(pair, a, ca, m, *cm, options, jumps);
  find_jumps(pair, m, *cm, b, cb, options, jumps);
}

// "2 contact patches, the largest carrying 67.5 % of the load"
std::string several_patches_message(const WheelRailPatch& p) {
  return fmt::format("{} contact patches, the largest carrying {:.1f} % of the load", p.patches,
                     100.0 * (1.0 - p.dropped_load_fraction));
}

FlexibilityTableNode solve_node(const WheelRailPair& pair, double y_m, double Fz_N, const FlexibilityTableOptions& options) {
  FlexibilityTableNode n;
  n.y_m = y_m;
  n.vertical_load_N = Fz_N;
  WheelRailPatchOptions patch_options = options.patch;
  patch_options.vertical_load_N = Fz_N;
  patch_options.allow_several_patches = true;  // marked, not thrown
  try {
    const WheelRailPatch p = solve_wheel_rail_patch(pair, y_m, patch_options);
    if (p.patches > 1) {
      n.status = FlexibilityNodeStatus::several_patches;
      n.message = several_patches_message(p);
      return n;
    }
    // nH-FastSim's recipe, the very one a wheel-rail case runs on the fly.
    const NhFastSim nh(p.patch, options.nh_fastsim);
    n.flexibility = nh.flexibility();
    n.f11_N = nh.flexibilities().f11_N;
    n.f22_N = nh.flexibilities().f22_N;
    n.f23_Nm = nh.flexibilities().f23_Nm;
    n.coupling = nh.coupling();
    n.normal_force_N = p.normal_force_N;
    n.contact_angle_rad = p.contact_angle_rad;
    n.spin_per_m = p.spin_per_m;
    n.area_m2 = p.area_m2;
    n.elements_in_contact = p.elements_in_contact;
  } catch (const Error& e) {
    n = FlexibilityTableNode{};
    n.y_m = y_m;
    n.vertical_load_N = Fz_N;
    n.status = FlexibilityNodeStatus::failed;
    n.message = e.what();
  }
  return n;
}

void validate(const FlexibilityTableOptions& o) {
  require(std::isfinite(o.contact_jump_m) && o.contact_jump_m > 0.0,
          "flexibility table: the contact-jump threshold must be positive");
  require(std::isfinite(o.contact_jump_resolution_m) && o.contact_jump_resolution_m > 0.0 &&
              o.contact_jump_resolution_m < o.contact_jump_m,
          "flexibility table: the contact-jump resolution must be positive and below the threshold");
}

void validate_grid(const std::vector<double>& values, const char* what, std::size_t max_count) {
  require(!values.empty(), [&] { return fmt::format("flexibility table: at least one {} is needed", what); });
  require(values.size() <= max_count,
          [&] { return fmt::format("flexibility table: at most {} {} values", max_count, what); });
  for (std::size_t k = 0; k < values.size(); ++k) {
    require(std::isfinite(values[k]), [&] { return fmt::format("flexibility table: every {} must be finite", what); });
    require(k == 0 || values[k] > values[k - 1],
            [&] { return fmt::format("flexibility table: the {} values must be strictly increasing", what); });
  }
}

}  // namespace

void check_flexibility_table_work(std::size_t y_values, std::size_t loads, int target_elements) {
  const double nodes = static_cast<double>(y_values) * static_cast<double>(loads);
  const double per_node = std::pow(std::max(1.0, static_cast<double>(target_elements)) / kFlexibilityTableReferenceElements, 1.5);
  const double work = nodes * per_node;
  if (work <= kMaximumFlexibilityTableWork) return;
  const auto hours = [](double node_equivalents) { return node_equivalents * kFlexibilityTableSecondsPerNode / 3600.0; };
  throw Error(fmt::format(
      "flexibility table: {} y values × {} load{} = {:g} nodes at {} elements in contact would take about {:.3g} hours "
      "(about {:g} s per node at {:g} elements, growing as elements^1.5); at most the work of {:g} nodes at {:g} "
      "elements (about {:.2g} hours) is allowed: use fewer y values or loads, or fewer elements",
      y_values, loads, loads == 1 ? "" : "s", nodes, target_elements, hours(work), kFlexibilityTableSecondsPerNode,
      kFlexibilityTableReferenceElements, kMaximumFlexibilityTableWork, kFlexibilityTableReferenceElements,
      hours(kMaximumFlexibilityTableWork)));
}

std::vector<double> flexibility_table_y_grid(double y_from_m, double y_to_m, double y_step_m) {
  require(std::isfinite(y_from_m) && std::isfinite(y_to_m) && y_to_m >= y_from_m, [&] {
    return fmt::format("flexibility table: the y range must be finite with y_to >= y_from (got {} ... {} m)", y_from_m,
                       y_to_m);
  });
  require(std::isfinite(y_step_m) && y_step_m > 0.0,
          [&] { return fmt::format("flexibility table: the y step must be positive (got {} m)", y_step_m); });
  const double count = std::floor((y_to_m - y_from_m) / y_step_m + 1e-9) + 1.0;
  require(count <= static_cast<double>(kMaxYValues),
          [&] { return fmt::format("flexibility table: at most {} y values", kMaxYValues); });
  std::vector<double> y;
  for (int k = 0; k < static_cast<int>(count); ++k) {
    const double value = y_from_m + k * y_step_m;
    y.push_back(std::fabs(value) < 1e-12 ? 0.0 : value);
  }
  return y;
}

namespace {

void validate_build_inputs(const std::vector<double>& y_grid_m, const std::vector<double>& load_grid_N,
                           const FlexibilityTableOptions& options) {
  validate(options);
  validate_grid(y_grid_m, "y", kMaxYValues);
  validate_grid(load_grid_N, "vertical load", kMaxLoads);
  check_flexibility_table_work(y_grid_m.size(), load_grid_N.size(), options.patch.target_elements);
  require(load_grid_N.front() > 0.0, "flexibility table: the vertical loads must be positive");
  validate(options.patch.material);
  require(options.patch.target_elements >= kMinimumWheelRailElements &&
              options.patch.target_elements <= kMaximumWheelRailElements,
          [&] {
            return fmt::format("flexibility table: the target elements in contact {} must lie in [{}, {}]",
                               options.patch.target_elements, kMinimumWheelRailElements, kMaximumWheelRailElements);
          });
}

// What the table was built from and with.
FlexibilityTableMetadata table_metadata(const WheelRailPair& pair, const FlexibilityTableOptions& options) {
  FlexibilityTableMetadata metadata;
  metadata.wheel_profile = file_fingerprint(pair.wheel().source());
  metadata.rail_profile = file_fingerprint(pair.rail().source());
  metadata.track = pair.parameters();
  metadata.material = options.patch.material;
  metadata.target_elements = options.patch.target_elements;
  metadata.contact_reference = options.patch.reference;
  metadata.collocation_offset = options.nh_fastsim.collocation_offset;
  metadata.nh_fastsim_recipe = nh_fastsim_recipe(options.nh_fastsim.creepage_coupling);
  metadata.flexibility_coarsening = options.nh_fastsim.flexibility_coarsening;
  metadata.railcontact_version = RC_VERSION_STRING;
  metadata.created_utc = options.created_utc.empty() ? detail::utc_now() : options.created_utc;
  return metadata;
}

// The table's y values: the grid with both ends of every contact jump added, and the jumps by
// their left node.
struct YGridWithJumps {
  std::vector<double> y_m;
  std::vector<ContactJump> jumps;
};

// Contact jumps: on the geometry alone (the first-touch point does not depend on the load). The
// smooth reference moves continuously: it has none.
YGridWithJumps y_grid_with_jumps(const WheelRailPair& pair, const std::vector<double>& y_grid_m,
                                 const FlexibilityTableOptions& options) {
  std::vector<JumpBracket> brackets;
  if (options.locate_contact_jumps && options.patch.reference == ContactReference::first_touch) {
    std::vector<std::optional<WheelRailContactPoint>> points;
    for (double y : y_grid_m) points.push_back(try_contact_point(pair, y));
    for (std::size_t k = 0; k + 1 < y_grid_m.size(); ++k)
      if (points[k] && points[k + 1])
        find_jumps(pair, y_grid_m[k], *points[k], y_grid_m[k + 1], *points[k + 1], options, brackets);
  }
  YGridWithJumps grid{y_grid_m, {}};
  std::vector<double>& y = grid.y_m;
  for (const JumpBracket& j : brackets) {
    y.push_back(j.y_left_m);
    y.push_back(j.y_right_m);
  }
  std::sort(y.begin(), y.end());
  y.erase(std::unique(y.begin(), y.end()), y.end());
  for (const JumpBracket& j : brackets) {
    const auto left = static_cast<std::size_t>(std::lower_bound(y.begin(), y.end(), j.y_left_m) - y.begin());
    grid.jumps.push_back({left, j.y_rail_left_m, j.y_rail_right_m});
  }
  return grid;
}

// The solve time at the head of node k's text ("seconds\nnode JSON"). The text may come from a
// shard's journal (railcontact merge): checked, not trusted.
double node_seconds(std::size_t k, const std::string& text, std::size_t newline) {
  const std::string time = text.substr(0, newline);
  char* end = nullptr;
  const double seconds = std::strtod(time.c_str(), &end);
  require(newline != std::string::npos && !time.empty() && end == time.c_str() + time.size() && std::isfinite(seconds),
          [&] {
            return fmt::format("flexibility table: node {} does not begin with its solve time in seconds (got '{}'; a "
                               "damaged shard journal?)",
                               k, printable_excerpt(time));
          });
  return seconds;
}

}  // namespace

FlexibilityTable build_flexibility_table(const WheelRailPair& pair, const std::vector<double>& y_grid_m,
                                         const std::vector<double>& load_grid_N, const FlexibilityTableOptions& options,
                                         const FlexibilityTableProgressCallback& progress) {
  validate_build_inputs(y_grid_m, load_grid_N, options);
  FlexibilityTableMetadata metadata = table_metadata(pair, options);
  YGridWithJumps grid = y_grid_with_jumps(pair, y_grid_m, options);
  const std::vector<double>& y = grid.y_m;

  // Every node on its own (no state carries over from one to the next), so that the runner may
  // compute them in any order and anywhere; encoded for the runner as "seconds\nnode JSON".
  const std::size_t loads = load_grid_N.size();
  const std::size_t total = y.size() * loads;
  std::vector<FlexibilityTableNode> nodes(total);
  const TableNodeSolver solve = [&](std::size_t k) {
    const auto start = Clock::now();
    const FlexibilityTableNode n = solve_node(pair, y[k / loads], load_grid_N[k % loads], options);
    return fmt::format("{:.17g}\n{}", std::chrono::duration<double>(Clock::now() - start).count(),
                       detail::flexibility_table_node_json(n));
  };
  std::mutex store_lock;
  std::size_t solved = 0, stored = 0;
  const TableNodeStore store = [&](std::size_t k, const std::string& text) {
    require(k < total, [&] { return fmt::format("flexibility table: the runner stored node {} of {}", k, total); });
    const std::size_t newline = text.find('\n');
    const double seconds = node_seconds(k, text, newline);
    FlexibilityTableNode n = detail::parse_flexibility_table_node(text.substr(newline + 1), k);
    const std::lock_guard<std::mutex> guard(store_lock);
    nodes[k] = std::move(n);
    solved += nodes[k].status == FlexibilityNodeStatus::solved;
    ++stored;
    if (progress) progress({stored, total, &nodes[k], seconds});
  };
  if (options.runner) {
    options.runner(total, solve, store);
  } else {
    for (std::size_t k = 0; k < total; ++k) store(k, solve(k));
  }
  require(stored == total, [&] {
    return fmt::format("flexibility table: the runner stored {} of the {} nodes", stored, total);
  });
  require(solved > 0,
          [&] { return fmt::format("flexibility table: no node could be solved (first: {})", nodes.front().message); });
  return FlexibilityTable(std::move(metadata), std::move(grid.y_m), load_grid_N, std::move(nodes),
                          std::move(grid.jumps));
}

}  // namespace railcontact
