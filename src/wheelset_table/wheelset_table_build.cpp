// Building a wheelset table (wheelset_table.hpp, docs/WHEELSET_TABLE.md): Wheelset::evaluate at
// every node of the (y, wheel load) grid, each patch kept with its flexibilities and a coarse copy.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <mutex>
#include <optional>

#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset_table.hpp"
#include "flexibility_table/table_json.hpp"
#include "wheelset_table/wheelset_table_json.hpp"
#include "railcontact/version.h"

namespace railcontact {
namespace {

// The largest table a build accepts: about 0.2 s per node at 0.2 mm elements (a wheelset solve by
// load), so 20000 nodes are about an hour.
constexpr std::size_t kMaximumWheelsetTableNodes = 20000;

// The coarse copy of a patch for FastSim at lookup: blocks of factor × factor elements, the largest
// factor (at most kMaximumCoarsening) that leaves about `target` elements; on a steep patch
// (|sin γ| > 0.5: flange contact, whose spin sin γ / r is several per metre) at most 2 × 2 blocks,
// since FastSim's error grows with the spin times the block's size: on S1002/UIC60 at y = −6.6 mm
// (γ = 1.2 rad, 4600 elements) 3 × 3 blocks put the table's lateral force 3.0 % of μFz from the
// wheelset on the fly, 2 × 2 blocks 0.9 % (docs/WHEELSET_TABLE.md §3).
int runtime_coarsening(const ContactPatch& fine, int target, double contact_angle_rad) {
  const double ratio = static_cast<double>(fine.elements().count()) / std::max(1, target);
  const int largest = std::abs(std::sin(contact_angle_rad)) > 0.5 ? 2 : kMaximumCoarsening;
  return std::clamp(static_cast<int>(std::floor(std::sqrt(std::max(1.0, ratio)))), 1, largest);
}

// The coarse copy of `fine` into mesh and pressure. Returns the coarse copy's centre of pressure
// measured from the fine one's (zero when the copy is the patch itself, factor 1).
std::array<double, 2> keep_runtime_copy(const ContactPatch& fine, int target, double contact_angle_rad, Mesh& mesh,
                                        std::vector<double>& pressure_Pa) {
  const int factor = runtime_coarsening(fine, target, contact_angle_rad);
  const ContactPatch coarse = coarsened(fine, factor);
  mesh = coarse.mesh();
  pressure_Pa.assign(coarse.mesh().size(), 0.0);
  const std::vector<std::size_t>& indices = coarse.elements().indices();
  for (std::size_t e = 0; e < indices.size(); ++e) pressure_Pa[indices[e]] = coarse.pressure_Pa()[e];
  if (factor == 1) return {0.0, 0.0};
  return {-coarse.x1_shift_m(), -coarse.x2_shift_m()};
}

// The lobes of a patch of several, as the wheelset solves it (the same NhFastSimPerLobe on the same
// patch): each lobe's flexibilities and coarse copy (its share of the runtime elements) with its
// centre of pressure in the contact frame (fine_x1, fine_x2: the patch's), and where a neck is
// blended the whole patch's weight and flexibilities. Nothing for a patch of one lobe.
struct KeptLobes {
  std::vector<WheelsetTableLobe> lobes;
  double whole_patch_weight = 0.0;
  std::optional<Flexibility> whole_patch_flexibility;
  CreepageCoupling whole_patch_coupling;  // about the patch's origin
};
KeptLobes keep_lobes(const ContactPatch& fine, int runtime_elements, double contact_angle_rad, double fine_x1_m,
                     double fine_x2_m, double s2, const NhFastSimOptions& nh_fastsim) {
  KeptLobes kept;
  if (!NhFastSimPerLobe::has_several_lobes(fine)) return kept;
  const NhFastSimPerLobe per_lobe(fine, nh_fastsim);
  if (const Flexibility* whole = per_lobe.whole_patch_flexibility()) {
    kept.whole_patch_weight = per_lobe.whole_patch_weight();
    kept.whole_patch_flexibility = *whole;
    kept.whole_patch_coupling = per_lobe.whole_patch_coupling();
  }
  const double fine_elements = static_cast<double>(fine.elements().count());
  for (std::size_t k = 0; k < per_lobe.lobe_count(); ++k) {
    const NhFastSimPerLobe::LobeView lobe = per_lobe.lobe(k);
    WheelsetTableLobe l;
    l.flexibility = lobe.flexibility;
    const int target = std::max(
        20, static_cast<int>(std::lround(runtime_elements * static_cast<double>(lobe.patch.elements().count()) / fine_elements)));
    const std::array<double, 2> lobe_coarse =
        keep_runtime_copy(lobe.patch, target, contact_angle_rad, l.runtime_mesh, l.runtime_pressure_Pa);
    l.coupling = lobe.coupling.moved_to(lobe_coarse[0], lobe_coarse[1], lobe.flexibility);
    l.pressure_centre_x1_m = fine_x1_m + lobe.x1_centre_m + lobe_coarse[0];
    l.pressure_centre_x2_m = fine_x2_m + s2 * (lobe.x2_centre_m + lobe_coarse[1]);
    kept.lobes.push_back(std::move(l));
  }
  return kept;
}

// The strips of a conformal runtime copy: column j lies at x2 = s2 x2_solve(j) + centre_x2 from
// the reference point along X2 in the wheel's own frame (the developed coordinate of the patch's
// strips; centre_x2 the copy's centre in the contact frame), and takes the strip frame there,
// interpolated linearly between the patch's strips in contact.
std::vector<WheelsetTableStrip> runtime_strips(const std::vector<ConformalStrip>& strips, const Mesh& runtime_mesh,
                                               double centre_x2_m, double s2, const Vector3& centre) {
  std::vector<WheelsetTableStrip> out(static_cast<std::size_t>(runtime_mesh.n2));
  for (int j = 0; j < runtime_mesh.n2; ++j) {
    const double s = s2 * runtime_mesh.x2(j) + centre_x2_m;
    std::size_t k = 0;
    while (k + 2 < strips.size() && strips[k + 1].s_m < s) ++k;
    const ConformalStrip& a = strips[k];
    const ConformalStrip& b = strips[std::min(k + 1, strips.size() - 1)];
    const double t = b.s_m > a.s_m ? std::clamp((s - a.s_m) / (b.s_m - a.s_m), 0.0, 1.0) : 0.0;
    WheelsetTableStrip& strip = out[static_cast<std::size_t>(j)];
    strip.angle_rad = (1.0 - t) * a.angle_rad + t * b.angle_rad;
    for (std::size_t i = 0; i < 3; ++i)
      strip.point_from_wheelset_centre_m[i] =
          (1.0 - t) * a.wheel_point_track_m[i] + t * b.wheel_point_track_m[i] - centre[i];
  }
  return out;
}

// The conformal surface's solution of a patch (its own numbers, unblended), its runtime copy with
// a strip per column, and for a patch of several lobes each lobe's (as the wheelset solves it:
// NhFastSimPerLobe on the developed patch).
WheelsetTableConformalPatch conformal_table_patch(const WheelsetPatch& patch, double weight, const Vector3& centre,
                                                  WheelSide side, int runtime_elements,
                                                  const NhFastSimOptions& nh_fastsim) {
  WheelsetTableConformalPatch c;
  c.weight = weight;
  c.normal_force_N = patch.normal_force_N;
  c.pressure_force_track_N = patch.pressure_force_track_N;
  c.area_m2 = patch.area_m2;
  c.elements_in_contact = patch.elements_in_contact;
  c.max_pressure_Pa = patch.max_pressure_Pa;
  c.pressure_centre_x1_m = patch.pressure_centre_x1_m;
  c.pressure_centre_x2_m = patch.pressure_centre_x2_m;
  c.flexibility = patch.solvers.front().flexibility;
  if (patch.elements_in_contact == 0 || patch.strips.empty()) return c;
  const double s2 = side == WheelSide::left ? -1.0 : 1.0;
  const double fine_x1 = c.pressure_centre_x1_m, fine_x2 = c.pressure_centre_x2_m;
  // The runtime copy as for a planar patch (2 × 2 blocks at most where the patch is steep).
  const std::array<double, 2> coarse =
      keep_runtime_copy(patch.patch, runtime_elements, patch.region.contact_angle_rad, c.runtime_mesh, c.runtime_pressure_Pa);
  c.pressure_centre_x1_m += coarse[0];
  c.pressure_centre_x2_m += s2 * coarse[1];
  c.coupling = patch.solvers.front().coupling.moved_to(coarse[0], coarse[1], c.flexibility);
  c.strips = runtime_strips(patch.strips, c.runtime_mesh, c.pressure_centre_x2_m, s2, centre);
  KeptLobes kept = keep_lobes(patch.patch, runtime_elements, patch.region.contact_angle_rad, fine_x1, fine_x2, s2,
                              nh_fastsim);
  c.lobes = std::move(kept.lobes);
  for (WheelsetTableLobe& l : c.lobes)
    l.strips = runtime_strips(patch.strips, l.runtime_mesh, l.pressure_centre_x2_m, s2, centre);
  c.whole_patch_weight = kept.whole_patch_weight;
  if (kept.whole_patch_flexibility) {
    c.flexibility = *kept.whole_patch_flexibility;
    c.coupling = kept.whole_patch_coupling.moved_to(coarse[0], coarse[1], c.flexibility);
  }
  return c;
}

// A patch's reference point, frame, geometry, normal force and measures as a node keeps them.
WheelsetTablePatch table_patch_fields(const WheelsetPatch& patch, const Vector3& centre) {
  WheelsetTablePatch t;
  const InterpenetrationRegion& region = patch.region;
  t.reference_point_track_m = region.reference_point_track_m;
  // The creepage point (on the undeformed wheel surface) from the wheelset centre.
  for (int i = 0; i < 3; ++i) t.point_from_wheelset_centre_m[i] = patch.creepage_point_track_m[i] - centre[i];
  t.x1_axis = region.x1_axis;
  t.x2_axis = region.x2_axis;
  t.x3_axis = region.x3_axis;
  t.contact_angle_rad = region.contact_angle_rad;
  t.rolling_radius_m = patch.rolling_radius_m;
  t.rail_profile_y_m = region.rail_profile_y_m;
  t.wheel_profile_y_m = region.wheel_profile_y_m;
  t.normal_force_N = patch.normal_force_N;
  t.area_m2 = patch.area_m2;
  t.elements_in_contact = patch.elements_in_contact;
  t.max_pressure_Pa = patch.max_pressure_Pa;
  t.pressure_centre_x1_m = patch.pressure_centre_x1_m;
  t.pressure_centre_x2_m = patch.pressure_centre_x2_m;
  t.flexibility = patch.solvers.front().flexibility;
  t.coupling = patch.solvers.front().coupling;  // about the fine patch's origin until its copy is kept
  return t;
}

// A planar patch's runtime copy and lobes for FastSim at lookup (nothing for a patch with overlap
// but no element in contact yet).
void keep_planar_runtime(const WheelsetPatch& patch, WheelSide side, int runtime_elements,
                         const NhFastSimOptions& nh_fastsim, WheelsetTablePatch& t) {
  if (patch.elements_in_contact == 0) return;
  // The kept patch is in the solve frame (mirrored for a left wheel) with its origin at the centre
  // of pressure; the coarse copy is re-centred on its own, a fraction of an element away. Centres
  // are kept in the contact frame: x2 = s2 × (solve frame x2).
  const double s2 = side == WheelSide::left ? -1.0 : 1.0;
  const double angle = patch.region.contact_angle_rad;
  const std::array<double, 2> coarse =
      keep_runtime_copy(patch.patch, runtime_elements, angle, t.runtime_mesh, t.runtime_pressure_Pa);
  const double fine_x1 = t.pressure_centre_x1_m, fine_x2 = t.pressure_centre_x2_m;
  t.pressure_centre_x1_m += coarse[0];
  t.pressure_centre_x2_m += s2 * coarse[1];
  t.coupling = t.coupling.moved_to(coarse[0], coarse[1], t.flexibility);
  // A patch of several lobes: each lobe's flexibilities and coarse copy.
  KeptLobes kept = keep_lobes(patch.patch, runtime_elements, angle, fine_x1, fine_x2, s2, nh_fastsim);
  t.lobes = std::move(kept.lobes);
  t.whole_patch_weight = kept.whole_patch_weight;
  if (kept.whole_patch_flexibility) {
    t.flexibility = *kept.whole_patch_flexibility;
    t.coupling = kept.whole_patch_coupling.moved_to(coarse[0], coarse[1], t.flexibility);
  }
}

// A patch as a node keeps it. On the conformal surface (weight above 0) its conformal part, and
// where it blends the two surfaces the planar surface's fields and runtime copy; fully conformal,
// the fields of its own solution without a planar runtime copy.
WheelsetTablePatch table_patch(const WheelsetPatch& patch, const Vector3& centre, WheelSide side, int runtime_elements,
                               const NhFastSimOptions& nh_fastsim) {
  if (patch.conformal_weight == 0.0) {
    WheelsetTablePatch t = table_patch_fields(patch, centre);
    keep_planar_runtime(patch, side, runtime_elements, nh_fastsim, t);
    return t;
  }
  const bool blended = patch.conformal_weight < 1.0;
  require(!blended || (patch.planar_surface && patch.conformal_surface),
          "wheelset table: a blended patch came without its two surfaces' solutions");
  WheelsetTablePatch t = table_patch_fields(blended ? *patch.planar_surface : patch, centre);
  if (blended) keep_planar_runtime(*patch.planar_surface, side, runtime_elements, nh_fastsim, t);
  t.conformal = conformal_table_patch(blended ? *patch.conformal_surface : patch, patch.conformal_weight, centre, side,
                                      runtime_elements, nh_fastsim);
  return t;
}

// The nodes in blocks of kWheelsetTableBlock consecutive y values at one yaw and load: along a
// block the wheelset's warm start carries over from node to node, each block starts cold. The
// blocks are independent, so a runner may compute them in any order and anywhere, and the table
// does not depend on it. A block travels as the JSON list of its nodes.
struct NodeBlock {
  std::size_t iyaw, il, iy_begin, iy_end;
};
std::vector<NodeBlock> node_blocks(const WheelsetTableGrid& grid) {
  std::vector<NodeBlock> blocks;
  for (std::size_t iyaw = 0; iyaw < grid.yaw_rad.size(); ++iyaw)
    for (std::size_t il = 0; il < grid.wheel_load_N.size(); ++il)
      for (std::size_t iy = 0; iy < grid.y_m.size(); iy += kWheelsetTableBlock)
        blocks.push_back({iyaw, il, iy, std::min(iy + kWheelsetTableBlock, grid.y_m.size())});
  return blocks;
}

// One node: the wheelset at (y, yaw) by its load, each wheel's height and patches kept; a failed
// solve is a gap with its message.
WheelsetTableNode solve_node(Wheelset& wheelset, const WheelsetTrack& track, double y_m, double yaw_rad, double load_N,
                             int runtime_elements, const NhFastSimOptions& nh_fastsim) {
  WheelsetTableNode node;
  node.y_m = y_m;
  node.yaw_rad = yaw_rad;
  node.wheel_load_N = load_N;
  WheelsetState state;
  state.position.lateral_displacement_m = y_m;
  state.position.yaw_rad = yaw_rad;
  try {
    const WheelsetResult r = wheelset.evaluate(state);
    for (int w = 0; w < 2; ++w) {
      const WheelResult& wheel = r.wheels[w];
      node.vertical_displacement_m[w] = wheel.vertical_displacement_m;
      const Vector3 centre{0.0, y_m, track.nominal_axle_height_m() + wheel.vertical_displacement_m};
      for (const WheelsetPatch& p : wheel.patches)
        node.wheels[w].push_back(table_patch(p, centre, wheel.side, runtime_elements, nh_fastsim));
    }
  } catch (const Error& e) {
    node.status = WheelsetTableNodeStatus::failed;
    node.message = e.what();
    node.wheels = {};
  }
  return node;
}

// A block's nodes, solved in y order on one warm wheelset, as the runner carries them: the seconds
// it took on the first line, then the nodes' JSON.
std::string solve_block(const WheelsetTrack& track, const WheelsetTableGrid& grid, const NodeBlock& block,
                        const WheelsetOptions& wheelset_options, const WheelsetTableOptions& options) {
  WheelsetOptions o = wheelset_options;
  const double load_N = grid.wheel_load_N[block.il];
  o.loads = WheelLoads{load_N, load_N, false};
  Wheelset wheelset(track, o);
  std::vector<WheelsetTableNode> solved_nodes;
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t iy = block.iy_begin; iy < block.iy_end; ++iy)
    solved_nodes.push_back(solve_node(wheelset, track, grid.y_m[iy], grid.yaw_rad[block.iyaw], load_N,
                                      options.runtime_elements, wheelset_options.nh_fastsim));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return fmt::format("{:.17g}\n{}", seconds, detail::wheelset_table_nodes_json(solved_nodes));
}

// The nodes of a grid (Wheelset::evaluate at each, its patches kept), computed by the options'
// runner; the progress counts them from done_before of total.
struct SolvedNodes {
  std::vector<WheelsetTableNode> nodes;  // in the order of grid.index()
  std::size_t solved = 0;
  std::string first_failure;  // the message of the first gap
};

// Where the runner's blocks come back (from any thread, in any order): each node in its place
// in the grid, the solved ones and the first gap (in grid order) counted, the progress reported.
class NodeStore {
 public:
  NodeStore(const WheelsetTableGrid& grid, const std::vector<NodeBlock>& blocks,
            const WheelsetTableProgressCallback& progress, std::size_t done_before, std::size_t total)
      : grid_(grid), blocks_(blocks), progress_(progress), done_before_(done_before), total_(total) {
    out_.nodes.resize(grid.size());
  }

  void store(std::size_t b, const std::string& text) {
    const NodeBlock& block = blocks_.at(b);
    const std::size_t newline = text.find('\n');
    const double seconds = std::stod(text.substr(0, newline));
    std::vector<WheelsetTableNode> block_nodes = detail::parse_wheelset_table_nodes(text.substr(newline + 1));
    require(block_nodes.size() == block.iy_end - block.iy_begin, "wheelset table: a block came back incomplete");
    const std::lock_guard<std::mutex> guard(lock_);
    ++blocks_stored_;
    for (std::size_t i = 0; i < block_nodes.size(); ++i) {
      const std::size_t index = grid_.index(block.iy_begin + i, block.iyaw, block.il);
      WheelsetTableNode& node = out_.nodes[index];
      node = std::move(block_nodes[i]);
      if (node.status == WheelsetTableNodeStatus::solved) {
        ++out_.solved;
      } else if (index < first_failure_index_) {
        first_failure_index_ = index;
        out_.first_failure = node.message;
      }
      ++done_;
      if (progress_) {
        WheelsetTableProgress p;
        p.nodes_done = done_before_ + done_;
        p.nodes_total = total_;
        p.node = &node;
        p.node_seconds = seconds / static_cast<double>(block_nodes.size());
        progress_(p);
      }
    }
  }

  // The nodes, once every block is stored.
  SolvedNodes finished() {
    require(blocks_stored_ == blocks_.size() && done_ == out_.nodes.size(), [&] {
      return fmt::format("wheelset table: the runner stored {} of the {} blocks", blocks_stored_, blocks_.size());
    });
    return std::move(out_);
  }

 private:
  const WheelsetTableGrid& grid_;
  const std::vector<NodeBlock>& blocks_;
  const WheelsetTableProgressCallback& progress_;
  std::size_t done_before_, total_;
  std::mutex lock_;
  SolvedNodes out_;
  std::size_t done_ = 0, blocks_stored_ = 0;
  std::size_t first_failure_index_ = std::numeric_limits<std::size_t>::max();
};

SolvedNodes solve_nodes(const WheelsetTrack& track, const WheelsetTableGrid& grid, const WheelsetOptions& wheelset_options,
                        const WheelsetTableOptions& options, const WheelsetTableProgressCallback& progress,
                        std::size_t done_before, std::size_t total) {
  const std::vector<NodeBlock> blocks = node_blocks(grid);
  const TableNodeSolver solve = [&](std::size_t b) {
    return solve_block(track, grid, blocks.at(b), wheelset_options, options);
  };
  NodeStore nodes(grid, blocks, progress, done_before, total);
  const TableNodeStore store = [&](std::size_t b, const std::string& text) { nodes.store(b, text); };
  if (options.runner) {
    options.runner(blocks.size(), solve, store);
  } else {
    for (std::size_t b = 0; b < blocks.size(); ++b) store(b, solve(b));
  }
  return nodes.finished();
}

// A wheel's lateral normal force at a node: its patches' pressure resultants along y (the
// conformal part's blended in by its weight).
double lateral_normal_force_N(const std::vector<WheelsetTablePatch>& patches) {
  double f = 0.0;
  for (const WheelsetTablePatch& p : patches) {
    const double planar = p.normal_force_N * p.x3_axis[1];
    const double w = p.conformal ? p.conformal->weight : 0.0;
    f += (1.0 - w) * planar + (w > 0.0 ? w * p.conformal->pressure_force_track_N[1] : 0.0);
  }
  return f;
}

// The midpoints of the grid's y intervals that WheelsetTableRefinement halves (sorted).
std::vector<double> refined_y(const WheelsetTableGrid& grid, const std::vector<WheelsetTableNode>& nodes,
                              const WheelsetTableRefinement& refinement) {
  const std::vector<double>& y = grid.y_m;
  std::vector<char> halve(y.size() > 1 ? y.size() - 1 : 0, 0);
  for (std::size_t iyaw = 0; iyaw < grid.yaw_rad.size(); ++iyaw)
    for (std::size_t il = 0; il < grid.wheel_load_N.size(); ++il)
      for (std::size_t iy = 1; iy + 1 < y.size(); ++iy) {
        const WheelsetTableNode &a = nodes[grid.index(iy - 1, iyaw, il)], &n = nodes[grid.index(iy, iyaw, il)],
                                &b = nodes[grid.index(iy + 1, iyaw, il)];
        if (a.status != WheelsetTableNodeStatus::solved || n.status != WheelsetTableNodeStatus::solved ||
            b.status != WheelsetTableNodeStatus::solved)
          continue;
        const double t = (y[iy] - y[iy - 1]) / (y[iy + 1] - y[iy - 1]);
        for (std::size_t w = 0; w < 2; ++w) {
          const double line = (1.0 - t) * lateral_normal_force_N(a.wheels[w]) + t * lateral_normal_force_N(b.wheels[w]);
          if (std::abs(lateral_normal_force_N(n.wheels[w]) - line) > refinement.lateral_force_fraction * n.wheel_load_N)
            halve[iy - 1] = halve[iy] = 1;
        }
      }
  std::vector<double> added;
  for (std::size_t k = 0; k < halve.size(); ++k)
    if (halve[k] && y[k + 1] - y[k] > refinement.smallest_step_m) added.push_back(0.5 * (y[k] + y[k + 1]));
  return added;
}

}  // namespace

WheelsetTable build_wheelset_table(const WheelsetTrack& track, const WheelsetTableGrid& grid,
                                   const WheelsetTableOptions& options, const WheelsetTableProgressCallback& progress) {
  if (grid.y_m.empty() || grid.yaw_rad.empty() || grid.wheel_load_N.empty() || grid.size() > kMaximumWheelsetTableNodes) {
    throw Error(fmt::format("wheelset table: {} y values × {} yaws × {} loads = {} nodes; from 1 to {} nodes are allowed "
                            "(about 0.2 s each)",
                            grid.y_m.size(), grid.yaw_rad.size(), grid.wheel_load_N.size(), grid.size(),
                            kMaximumWheelsetTableNodes));
  }
  validate(grid);  // before the work
  if (!(options.runtime_elements >= 20 && options.runtime_elements <= 100000))
    throw Error(fmt::format("wheelset table: runtime_elements = {} must lie in [20, 100000]", options.runtime_elements));
  const WheelsetTableRefinement& refine = options.refinement;
  if (!(refine.lateral_force_fraction >= 0.0 && refine.lateral_force_fraction <= 1.0) ||
      !(refine.smallest_step_m > 0.0 && refine.smallest_step_m <= 1e-3) || !(refine.rounds >= 0 && refine.rounds <= 8))
    throw Error(fmt::format("wheelset table: the refinement's lateral_force_fraction = {:g} must lie in [0, 1], "
                            "smallest_step_m = {:g} in (0, 0.001] m and rounds = {} in [0, 8]",
                            refine.lateral_force_fraction, refine.smallest_step_m, refine.rounds));
  WheelsetOptions wheelset_options = options.wheelset;
  wheelset_options.solvers = {TangentialSolver::nh_fastsim};
  wheelset_options.keep_tractions = true;
  wheelset_options.tangential_forces_in_vertical_balance = false;
  wheelset_options.allow_wheel_lift = false;
  validate(wheelset_options);

  SolvedNodes built = solve_nodes(track, grid, wheelset_options, options, progress, 0, grid.size());
  std::vector<WheelsetTableNode> nodes = std::move(built.nodes);
  std::size_t solved = built.solved;
  const std::string first_failure = built.first_failure;
  // The refinement: the new y values' nodes at every yaw and load, merged into the grid.
  WheelsetTableGrid refined = grid;
  for (int round = 0; round < (options.refinement.lateral_force_fraction > 0.0 ? options.refinement.rounds : 0); ++round) {
    WheelsetTableGrid extra{refined_y(refined, nodes, options.refinement), refined.yaw_rad, refined.wheel_load_N};
    if (extra.y_m.empty()) break;
    if (refined.size() + extra.size() > kMaximumWheelsetTableNodes) break;  // the grid as it is
    SolvedNodes more = solve_nodes(track, extra, wheelset_options, options, progress, refined.size(),
                                   refined.size() + extra.size());
    solved += more.solved;
    WheelsetTableGrid merged{{}, refined.yaw_rad, refined.wheel_load_N};
    std::merge(refined.y_m.begin(), refined.y_m.end(), extra.y_m.begin(), extra.y_m.end(), std::back_inserter(merged.y_m));
    std::vector<WheelsetTableNode> merged_nodes(merged.size());
    std::size_t from_old = 0, from_new = 0;
    for (std::size_t iy = 0; iy < merged.y_m.size(); ++iy) {
      const bool old = from_old < refined.y_m.size() && refined.y_m[from_old] == merged.y_m[iy];
      for (std::size_t iyaw = 0; iyaw < merged.yaw_rad.size(); ++iyaw)
        for (std::size_t il = 0; il < merged.wheel_load_N.size(); ++il)
          merged_nodes[merged.index(iy, iyaw, il)] = old ? std::move(nodes[refined.index(from_old, iyaw, il)])
                                                         : std::move(more.nodes[extra.index(from_new, iyaw, il)]);
      if (old) ++from_old;
      else ++from_new;
    }
    refined = std::move(merged);
    nodes = std::move(merged_nodes);
  }
  WheelsetTableMetadata metadata;
  const auto fingerprint = [](const std::string& source) {
    try {
      return file_fingerprint(source);
    } catch (const Error&) {
      return FileFingerprint{source, 0};  // not read from a file (profile arrays)
    }
  };
  metadata.right_wheel_profile = fingerprint(track.pair(WheelSide::right).wheel().source());
  metadata.right_rail_profile = fingerprint(track.pair(WheelSide::right).rail().source());
  metadata.left_wheel_profile = fingerprint(track.pair(WheelSide::left).wheel().source());
  metadata.left_rail_profile = fingerprint(track.pair(WheelSide::left).rail().source());
  metadata.track = track.parameters();
  metadata.element_size_m = wheelset_options.element_size_m;
  metadata.flexibility_coarsening = wheelset_options.nh_fastsim.flexibility_coarsening;
  metadata.collocation_offset = wheelset_options.nh_fastsim.collocation_offset;
  metadata.nh_fastsim_recipe = nh_fastsim_recipe(wheelset_options.nh_fastsim.creepage_coupling);
  metadata.runtime_elements = options.runtime_elements;
  metadata.reference_weighting = wheelset_options.search.weighting;
  metadata.creepage_on_wheel_surface = true;
  metadata.contact_surface = wheelset_options.contact_surface;
  metadata.contact_surface_switch = wheelset_options.contact_surface_switch;
  metadata.patch_coupling = wheelset_options.patch_coupling;
  metadata.railcontact_version = RC_VERSION_STRING;
  metadata.created_utc = options.created_utc.empty() ? detail::utc_now() : options.created_utc;
  if (solved == 0) throw Error(fmt::format("wheelset table: no node could be solved; the first: {}", first_failure));
  return WheelsetTable(refined, std::move(nodes), track.parameters().nominal_rolling_radius_m,
                       wheelset_options.material, wheelset_options.nh_fastsim.bound, std::move(metadata));
}

}  // namespace railcontact
