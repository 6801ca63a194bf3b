// `railcontact study profiles`: every wheel–rail set-up checked end to end (see the header).
#include "study/profile_pair_study.hpp"

#include <fmt/core.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "railcontact/contact_geometry.hpp"
#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"
#include "railcontact/wheelset_table.hpp"
#include "study/contact_geometry_study.hpp"
#include "output/figures.hpp"
#include "study/mpi_cases.hpp"
#include "output/output_directory.hpp"
#include "study/wheel_rail_setups.hpp"

namespace railcontact::study {

namespace {

constexpr double kMm = 1e-3;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kConicityAmplitude_m = 3e-3;  // EN 15302's usual amplitude
constexpr double kTarget_percent = 3.0;        // nH-FastSim against the exact solver, % of μ F3
constexpr double kTableTarget_percent = 2.0;   // the wheelset table against on the fly, % of μ Fz
constexpr double kWheelLoad_N = WheelLoads{}.right_N;  // the sweeps' load per wheel
// The table's nodes are at quarter steps of the sweep (its states midway between two nodes) over
// this last stretch before the flange climbs, where the flange's force rises steeply with y
// (docs/WHEELSET_TABLE.md §3), and at half steps elsewhere.
constexpr double kTableFineStretch_m = 2e-3;
// The table's loads, per sweep load. A lookup with the tangential forces in the vertical balance
// looks the wheel up at another table load, and there the forces are interpolated linearly between
// loads: at a node where the flange snaps in on Car7358 (y = −7.2125 mm) in steps of 1/4 of the load
// by 7.4 % of μFz, in 1/8 by 2.3 %; over the study's three failing set-ups 1/16 steps took the
// largest misses from 3.95 to 1.89 % (Car7358) and from 3.32 to 1.23 % (the 1:20 rail). Near flange
// climb at ±10 mrad the tangential forces lift or press the flange wheel by up to about half its
// load (Car7358 and the 1:20 rail need 0.70-1.41 times it): 0.75-1.25 left 15 states refused, 0.625-
// 1.4375 one (the 1:20 rail at its flange-climb limit, +10 mrad, 1.53 times, with Y/Q three times
// Nadal's limit; at 1.5 times that node's flange overlaps past the end of the rail profile's flank,
// a gap) (docs/VALIDATION.md §7).
constexpr std::array<double, 14> kTableLoads{0.625, 0.6875, 0.75,  0.8125, 0.875, 0.9375, 1.0,
                                               1.0625, 1.125, 1.1875, 1.25,  1.3125, 1.375, 1.4375};
constexpr double kTableRefinement = 0.01;  // WheelsetTableRefinement::lateral_force_fraction of the tables

// The rigid contact geometry: where the right wheel's flange climbs (towards −y, at most 15 mm) and
// the equivalent conicity at 3 mm (NaN when the flange climbs before it). A wide gauge puts flange
// contact beyond 10 mm: the search goes to 15 mm.
struct PairGeometry {
  double climb_y_m = -15e-3;  // the last y (≤ 0) before the flange climbs
  double tan_gamma_e = kNaN;
};

PairGeometry pair_geometry(const WheelsetTrack& track, double step_m) {
  PairGeometry g;
  const auto reach = [&](double direction) {
    double last = 0.0;
    for (int k = 1; k * step_m <= 15e-3 + 1e-12; ++k) {
      try {
        (void)rigid_contact_geometry(track, direction * k * step_m);
      } catch (const Error& e) {
        if (!is_flange_climb(e)) throw;
        break;
      }
      last = direction * k * step_m;
    }
    return last;
  };
  g.climb_y_m = reach(-1.0);
  const double half = std::min({-g.climb_y_m, reach(1.0), 6e-3});
  if (half < kConicityAmplitude_m) return g;
  const RollingRadiusDifference delta_r(rigid_contact_sweep(track, -half, half, step_m));
  if (largest_conicity_amplitude_m(delta_r) >= kConicityAmplitude_m)
    g.tan_gamma_e = equivalent_conicity(delta_r, kConicityAmplitude_m).tan_gamma_e_regression;
  return g;
}

// One (set-up, yaw) sweep, summarised.
struct SweepSummary {
  std::string setup;
  double yaw_rad = 0.0;
  int states = 0;
  double last_y_m = 0.0;
  std::string stop;  // why the sweep ended before the flange-climb limit (empty: it reached it)
  std::size_t most_patches = 0;
  double worst_dF1_percent = 0.0, worst_dF1_y_m = 0.0;
  double worst_dF2_percent = 0.0, worst_dF2_y_m = 0.0;
  double worst_step_N = 0.0, worst_step_y_m = 0.0;  // the largest step of a wheel force between two y
  int jumps = 0;                                     // steps standing out from their neighbours (see below)
  int fine_swept_steps = 0;                          // candidate jumps swept again in 0.01 mm steps
  std::string fine_failure;  // the first fine state that could not be solved (counted as a jump)
  double largest_angle_variation_rad = 0.0;          // over the patches (contact_angle_variation_rad)
  double tan_gamma_e = kNaN;
  // The wheelset table against nH-FastSim on the fly: the largest difference per track-frame
  // component over both wheels and every state (% of μ Fz), and the states it could not look up.
  std::array<double, 3> worst_table_percent{0.0, 0.0, 0.0};
  std::array<double, 3> worst_table_y_m{0.0, 0.0, 0.0};
  int table_states = 0, table_refused = 0;
  std::string table_refusal;  // the first refusal's message
  // Refused states where a wheel's Y/Q is beyond Nadal's flange-climb limit (physically the flange
  // climbs there; not counted in table_refused), and the first one's note.
  int table_refused_beyond_nadal = 0;
  std::string table_beyond_nadal;
};

// The table's lateral grid for a sweep of states y_k = −k h, k = 0 … steps: nodes midway between
// two states (a state is then where linear interpolation errs most), at quarter steps over the
// last kTableFineStretch_m; the outermost node is the last state itself, which the rigid geometry
// has shown to lie before the flange climbs.
std::vector<double> table_y_grid(int steps, double h) {
  std::vector<double> y;
  const double fine_from = -steps * h + kTableFineStretch_m;
  for (int k = 0; k <= steps; ++k) {
    const double state = -k * h, half = state < fine_from ? 0.25 * h : 0.5 * h;
    y.push_back(state + half);
    y.push_back(k == steps ? state : state - half);
  }
  std::sort(y.begin(), y.end());
  y.erase(std::unique(y.begin(), y.end(), [&](double a, double b) { return std::abs(a - b) < 1e-3 * h; }), y.end());
  return y;
}

// The set-up's wheelset table over the sweeps' positions and yaws, at kTableLoads times the sweeps'
// load: the vertical balance with the tangential forces looks up off the load (a load beyond the grid
// is refused: WheelsetTable.ABalanceThatNeedsALoadOutsideTheGridIsRefused).
WheelsetTable build_table(const WheelsetTrack& track, const WheelsetOptions& wheelset, int steps,
                          const ProfilePairStudyOptions& o, std::ostream& log) {
  std::vector<double> yaws = o.yaws_rad;
  std::sort(yaws.begin(), yaws.end());
  yaws.erase(std::unique(yaws.begin(), yaws.end()), yaws.end());
  std::vector<double> loads_N;
  for (double fraction : kTableLoads) loads_N.push_back(fraction * kWheelLoad_N);
  const WheelsetTableGrid grid{table_y_grid(steps, o.y_step_m), yaws, loads_N};
  WheelsetTableOptions options;
  options.wheelset = wheelset;
  // Nodes added where a flange snaps in or a second contact appears (docs/WHEELSET_TABLE.md §3).
  options.refinement.lateral_force_fraction = kTableRefinement;
  options.runner = table_node_runner(o.threads);
  const auto start = std::chrono::steady_clock::now();
  std::size_t reported = 0;
  return build_wheelset_table(track, grid, options, [&](const WheelsetTableProgress& p) {
    if (p.nodes_done * 10 / p.nodes_total == reported && p.nodes_done != p.nodes_total) return;
    reported = p.nodes_done * 10 / p.nodes_total;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fmt::print(log, "  table: {}/{} nodes, {:.0f} s left\n", p.nodes_done, p.nodes_total,
               elapsed / static_cast<double>(p.nodes_done) * static_cast<double>(p.nodes_total - p.nodes_done));
  });
}

// A jump: a step of a wheel's force larger than 1 % of its load and three times both neighbouring
// steps, with the number of patches unchanged (a patch that appears starts from zero force and
// grows; a jump is a discontinuity of the model). Near the flange a wheel's force rises steeply but
// continuously (on S1002/UIC60 at yaw 10 mrad its lateral force grows by 51 kN from −6.5 to −6.6 mm,
// by at most 7.3 kN in any 0.01 mm of it): `resolved(k)` sweeps a candidate step between y[k−1] and
// y[k] again in kFineSteps steps and says whether one of those alone still stands out so.
constexpr int kFineSteps = 10;
constexpr double kJumpFraction = 0.01;  // of the load
constexpr double kJumpContrast = 3.0;   // against both neighbouring steps

// The steps of a sequence of wheel forces (the largest component per step), and the first k in
// [1, size) whose step is a jump against its neighbours among these; 0 for none.
std::vector<double> force_steps(const std::vector<std::array<double, 3>>& force) {
  std::vector<double> step(force.size(), 0.0);
  for (std::size_t k = 1; k < force.size(); ++k)
    for (int i = 0; i < 3; ++i) step[k] = std::max(step[k], std::abs(force[k][i] - force[k - 1][i]));
  return step;
}
bool stands_out(const std::vector<double>& step, std::size_t k, double load_N) {
  const double before = k >= 2 ? step[k - 1] : 0.0, after = k + 1 < step.size() ? step[k + 1] : 0.0;
  return step[k] > kJumpFraction * load_N && step[k] > kJumpContrast * std::max(before, after);
}

// A candidate swept again: a jump, and why when a fine state could not be solved.
struct FineSweep {
  bool jump = false;
  std::string failure;
};

void count_jumps(const std::vector<std::array<double, 3>>& force, const std::vector<std::size_t>& patches,
                 const std::vector<double>& y, double load_N, const std::function<FineSweep(std::size_t)>& resolved,
                 SweepSummary& s) {
  const std::vector<double> step = force_steps(force);
  for (std::size_t k = 1; k < force.size(); ++k) {
    if (step[k] > s.worst_step_N) s.worst_step_N = step[k], s.worst_step_y_m = y[k];
    if (patches[k] != patches[k - 1] || !stands_out(step, k, load_N)) continue;
    ++s.fine_swept_steps;
    const FineSweep fine = resolved(k);
    if (fine.jump) ++s.jumps;
    if (!fine.failure.empty() && s.fine_failure.empty()) s.fine_failure = fine.failure;
  }
}

// The right wheel's force from y_from to y_to in kFineSteps steps, on a wheelset with nH-FastSim
// alone (the sweep's balance solver, so its forces are the sweep's): a jump when one fine step is a
// jump with the patches unchanged across it, or a fine state cannot be solved (with its message).
FineSweep jump_on_fine_steps(const WheelsetTrack& track, WheelsetOptions options, double yaw_rad, double y_from_m,
                             double y_to_m, double load_N) {
  options.solvers = {TangentialSolver::nh_fastsim};
  Wheelset wheelset(track, options);
  std::vector<std::array<double, 3>> force;
  std::vector<std::size_t> patches;
  for (int j = 0; j <= kFineSteps; ++j) {
    WheelsetState state;
    state.position.lateral_displacement_m = y_from_m + (y_to_m - y_from_m) * j / kFineSteps;
    state.position.yaw_rad = yaw_rad;
    try {
      const WheelResult right = wheelset.evaluate(state).wheels[0];
      force.push_back({right.force_track_N[0], right.force_track_N[1], right.force_track_N[2]});
      patches.push_back(right.patches.size());
    } catch (const Error& e) {
      return {true, fmt::format("y = {:.3f} mm: {}", state.position.lateral_displacement_m / kMm, e.what())};
    }
  }
  const std::vector<double> step = force_steps(force);
  for (std::size_t k = 1; k < step.size(); ++k)
    if (patches[k] == patches[k - 1] && stands_out(step, k, load_N)) return {true, {}};
  return {false, {}};
}

}  // namespace

double nadal_limit(double contact_angle_rad, double mu) {
  const double t = std::tan(contact_angle_rad);
  return (t - mu) / (1.0 + mu * t);
}

namespace {

// Nadal's flange-climb criterion on the wheel of a state whose patch is steepest: its Y/Q (the
// wheel's lateral force towards the side its steepest patch's pressure pushes it, over its vertical
// force) against the limit (tan γ − μ)/(1 + μ tan γ) at that patch's contact angle γ.
struct NadalCheck {
  double y_over_q = 0.0, limit = kNaN, contact_angle_rad = 0.0;
  WheelSide side = WheelSide::right;
  [[nodiscard]] bool beyond() const { return std::isfinite(limit) && y_over_q > limit; }
};
NadalCheck nadal_check(const WheelsetResult& r, double mu) {
  NadalCheck n;
  for (const WheelResult& wheel : r.wheels) {
    for (const WheelsetPatch& patch : wheel.patches) {
      const double gamma = std::abs(patch.region.contact_angle_rad);
      if (!(gamma > n.contact_angle_rad) || !(wheel.force_track_N[2] > 0.0)) continue;
      const double towards = patch.pressure_force_track_N[1] >= 0.0 ? 1.0 : -1.0;
      n.contact_angle_rad = gamma;
      n.side = wheel.side;
      n.y_over_q = towards * wheel.force_track_N[1] / wheel.force_track_N[2];
      n.limit = nadal_limit(gamma, mu);
    }
  }
  return n;
}

// The table looked up at the sweep's state against nH-FastSim on the fly (the second solver), per
// wheel and track-frame component, as % of μ Fz; a lookup the table refuses (a node it needs is a
// gap) is counted and its first message kept.
void compare_with_table(const WheelsetTable& table, const WheelsetState& state, const WheelsetResult& on_the_fly,
                        double mu, const std::string& name, std::ostream& rows, SweepSummary& s) {
  WheelsetResult looked_up;
  try {
    looked_up = table.evaluate(state, WheelLoads{kWheelLoad_N, kWheelLoad_N}, mu, true);
  } catch (const Error& e) {
    // Beyond Nadal's limit the state is one where the flange climbs (a physical end, stated apart).
    if (const NadalCheck n = nadal_check(on_the_fly, mu); n.beyond()) {
      if (s.table_refused_beyond_nadal++ == 0)
        s.table_beyond_nadal = fmt::format(
            "y = {:.2f} mm, the {} wheel's Y/Q = {:.2f} beyond Nadal's limit {:.2f} (contact angle {:.1f}°, μ = {:g}): {}",
            state.position.lateral_displacement_m / kMm, n.side == WheelSide::right ? "right" : "left", n.y_over_q,
            n.limit, n.contact_angle_rad * 180.0 / M_PI, mu, e.what());
      return;
    }
    if (s.table_refused++ == 0) s.table_refusal = e.what();
    return;
  }
  ++s.table_states;
  for (std::size_t side = 0; side < 2; ++side) {
    const Vector3& fly = on_the_fly.wheels[side].solver_force_track_N[1];
    const Vector3& tab = looked_up.wheels[side].force_track_N;
    std::array<double, 3> d{};
    for (int i = 0; i < 3; ++i) {
      d[i] = (tab[i] - fly[i]) * 100.0 / (mu * kWheelLoad_N);
      if (std::abs(d[i]) > std::abs(s.worst_table_percent[i]))
        s.worst_table_percent[i] = d[i], s.worst_table_y_m[i] = state.position.lateral_displacement_m;
    }
    fmt::print(rows, "{},{:.3f},{:.4f},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.4f},{:.4f},{:.4f}\n", name,
               state.position.yaw_rad * 1e3, state.position.lateral_displacement_m / kMm,
               side_name(on_the_fly.wheels[side].side), on_the_fly.wheels[side].patches.size(), fly[0], fly[1], fly[2],
               tab[0], tab[1], tab[2], d[0], d[1], d[2]);
  }
}

std::string percent(double v) { return std::isfinite(v) ? fmt::format("{:+.2f} %", v) : "–"; }

// The CSV files written during the sweeps: one row per patch, and one per state and wheel of the
// table check (with a table only).
struct SweepRows {
  std::ofstream patches;
  std::ofstream table_check;
};

SweepRows open_sweep_rows(const output::OutputDirectory& out, bool table) {
  SweepRows rows;
  rows.patches = output::open_output_file(out.path("profile_pairs.csv"));
  fmt::print(rows.patches,
             "setup,yaw_mrad,y_mm,side,patch,patches,contact_angle_rad,rail_profile_y_mm,normal_force_N,xi,eta,"
             "phi_per_m,exact_F1_N,exact_F2_N,nh_fastsim_F1_N,nh_fastsim_F2_N,dF1_percent_mu_F3,dF2_percent_mu_F3,"
             "wheel_Fx_N,wheel_Fy_N,wheel_Fz_N,contact_angle_variation_rad\n");
  if (table) {
    rows.table_check = output::open_output_file(out.path("table_check.csv"));
    fmt::print(rows.table_check, "setup,yaw_mrad,y_mm,side,patches,on_the_fly_Fx_N,on_the_fly_Fy_N,on_the_fly_Fz_N,table_Fx_N,"
                                 "table_Fy_N,table_Fz_N,dFx_percent_mu_Fz,dFy_percent_mu_Fz,dFz_percent_mu_Fz\n");
  }
  return rows;
}

void close_sweep_rows(SweepRows& rows, const output::OutputDirectory& out, bool table) {
  rows.patches.close();
  if (rows.patches.fail()) throw output::write_error(out.path("profile_pairs.csv"), errno);
  if (table) {
    rows.table_check.close();
    if (rows.table_check.fail()) throw output::write_error(out.path("table_check.csv"), errno);
  }
}

// The sweeps' wheelset: the exact solver and nH-FastSim on every patch, balanced with nH-FastSim's
// forces (the wheelset a user of nH-FastSim gets, which the table is compared with).
WheelsetOptions sweep_wheelset_options(const ProfilePairStudyOptions& o) {
  WheelsetOptions options;
  options.element_size_m = o.element_size_m;
  options.solvers = {TangentialSolver::exact, TangentialSolver::nh_fastsim};
  options.balance_solver = TangentialSolver::nh_fastsim;
  options.contact_surface = o.contact_surface;
  return options;
}

// One set-up's sweeps: the same track, wheelset and table at every yaw.
struct SetupSweeps {
  std::string name;
  const WheelsetTrack& track;
  WheelsetOptions options;
  const WheelsetTable* table = nullptr;  // with ProfilePairStudyOptions::table
  int steps = 0;                         // states y = −k y_step, k = 0 … steps (to the flange climb)
  double tan_gamma_e = kNaN;
};

// One state's patches: nH-FastSim against the exact solver (as % of μ F3), the worst kept; a row
// per patch.
void record_patches(const WheelsetResult& r, const std::string& name, double yaw, double mu, std::ostream& rows,
                    SweepSummary& s) {
  for (const WheelResult& w : r.wheels) {
    s.most_patches = std::max(s.most_patches, w.patches.size());
    for (std::size_t p = 0; p < w.patches.size(); ++p) {
      const WheelsetPatch& patch = w.patches[p];
      const TangentialForces& exact = patch.solvers[0].forces;
      const TangentialForces& fast = patch.solvers[1].forces;
      // A patch that carries no force (an overlap without an element in contact, e.g. lifted off by
      // its neighbour's pressure: docs/WHEELSET.md §5) has no tangential force from either solver.
      const double scale = patch.normal_force_N > 0.0 ? 100.0 / (mu * patch.normal_force_N) : 0.0;
      const double d1 = (fast.F1_N - exact.F1_N) * scale, d2 = (fast.F2_N - exact.F2_N) * scale;
      if (std::abs(d1) > std::abs(s.worst_dF1_percent)) s.worst_dF1_percent = d1, s.worst_dF1_y_m = s.last_y_m;
      if (std::abs(d2) > std::abs(s.worst_dF2_percent)) s.worst_dF2_percent = d2, s.worst_dF2_y_m = s.last_y_m;
      fmt::print(rows, "{},{:.3f},{:.4f},{},{},{},{:.8f},{:.6f},{:.3f},{:.8e},{:.8e},{:.8e},{:.3f},{:.3f},{:.3f},{:.3f},"
                       "{:.4f},{:.4f},{:.3f},{:.3f},{:.3f},{:.5f}\n",
                 name, yaw * 1e3, s.last_y_m / kMm, side_name(w.side), p, w.patches.size(),
                 patch.region.contact_angle_rad, patch.region.rail_profile_y_m / kMm, patch.normal_force_N,
                 patch.creepage.xi, patch.creepage.eta, patch.creepage.phi, exact.F1_N, exact.F2_N, fast.F1_N,
                 fast.F2_N, d1, d2, w.force_track_N[0], w.force_track_N[1], w.force_track_N[2],
                 contact_angle_variation_rad(patch.region));
      s.largest_angle_variation_rad = std::max(s.largest_angle_variation_rad, contact_angle_variation_rad(patch.region));
    }
  }
}

// The sweep at one yaw from y = 0 towards the right wheel's flange, until the flange climbs or a
// state cannot be evaluated (at y = 0 an error); each state recorded and checked against the table.
SweepSummary sweep_at_yaw(const SetupSweeps& setup, double yaw, double y_step_m, SweepRows& rows) {
  Wheelset wheelset(setup.track, setup.options);
  SweepSummary s;
  s.setup = setup.name;
  s.yaw_rad = yaw;
  s.tan_gamma_e = setup.tan_gamma_e;
  const double mu = setup.options.friction_coefficient;
  std::vector<std::array<double, 3>> right_force;
  std::vector<std::size_t> right_patches;
  std::vector<double> ys;
  for (int k = 0; k <= setup.steps; ++k) {
    WheelsetState state;
    state.position.lateral_displacement_m = -k * y_step_m;
    state.position.yaw_rad = yaw;
    WheelsetResult r;
    try {
      r = wheelset.evaluate(state);
    } catch (const Error& e) {
      if (k == 0)
        throw Error(e.kind(), fmt::format("study profiles: {} at y = 0, yaw {:g} rad: {}", setup.name, yaw, e.what()));
      s.stop = fmt::format("y = {:.2f} mm: {}", state.position.lateral_displacement_m / kMm, e.what());
      break;
    }
    ++s.states;
    s.last_y_m = state.position.lateral_displacement_m;
    record_patches(r, setup.name, yaw, mu, rows.patches, s);
    if (setup.table) compare_with_table(*setup.table, state, r, mu, setup.name, rows.table_check, s);
    const WheelResult& right = r.wheels[0];
    right_force.push_back({right.force_track_N[0], right.force_track_N[1], right.force_track_N[2]});
    right_patches.push_back(right.patches.size());
    ys.push_back(s.last_y_m);
  }
  count_jumps(right_force, right_patches, ys, kWheelLoad_N, [&](std::size_t k) {
    return jump_on_fine_steps(setup.track, setup.options, yaw, ys[k - 1], ys[k], kWheelLoad_N);
  }, s);
  return s;
}

// pairs.csv: one row per set-up and yaw.
void write_pairs_csv(const output::OutputDirectory& out, const std::vector<SweepSummary>& summaries) {
  std::ofstream pairs = output::open_output_file(out.path("pairs.csv"));
  fmt::print(pairs, "setup,yaw_mrad,tan_gamma_e_3mm,states,last_y_mm,most_patches,worst_dF1_percent,worst_dF1_y_mm,"
                    "worst_dF2_percent,worst_dF2_y_mm,worst_step_N,worst_step_y_mm,jumps,fine_swept_steps,largest_angle_variation_rad,stop,"
                    "table_states,table_refused,table_dFx_percent,table_dFx_y_mm,table_dFy_percent,table_dFy_y_mm,"
                    "table_dFz_percent,table_dFz_y_mm,table_refused_beyond_nadal\n");
  for (const SweepSummary& s : summaries)
    fmt::print(pairs,
               "{},{:.3f},{:.5f},{},{:.4f},{},{:.3f},{:.4f},{:.3f},{:.4f},{:.1f},{:.4f},{},{},{:.4f},\"{}\",{},{},{:.3f},{:.4f},"
               "{:.3f},{:.4f},{:.3f},{:.4f},{}\n",
               s.setup, s.yaw_rad * 1e3, s.tan_gamma_e, s.states, s.last_y_m / kMm, s.most_patches, s.worst_dF1_percent,
               s.worst_dF1_y_m / kMm, s.worst_dF2_percent, s.worst_dF2_y_m / kMm, s.worst_step_N,
               s.worst_step_y_m / kMm, s.jumps, s.fine_swept_steps, s.largest_angle_variation_rad, s.stop, s.table_states, s.table_refused,
               s.worst_table_percent[0], s.worst_table_y_m[0] / kMm, s.worst_table_percent[1],
               s.worst_table_y_m[1] / kMm, s.worst_table_percent[2], s.worst_table_y_m[2] / kMm,
               s.table_refused_beyond_nadal);
  pairs.close();
  if (pairs.fail()) throw output::write_error(out.path("pairs.csv"), errno);
}

// summary.md's first part: nH-FastSim against the exact solver, the steps and jumps, per sweep.
void print_sweeps_md(std::ostream& md, const ProfilePairStudyOptions& o, const std::vector<SweepSummary>& summaries) {
  fmt::print(md, "# Profile pairs end to end\n\n");
  fmt::print(md,
             "Each wheel–rail set-up: the wheelset by load (98.1 kN per wheel, μ = 0.3, 20 m/s, pure rolling) from y = 0 "
             "towards the right wheel's flange in steps of {:g} mm until the flange climbs, {:g} mm elements, {} contact "
             "surfaces, the exact solver and nH-FastSim on every patch. nH-FastSim's largest miss per component as a share of μ F3 (target "
             "{:g} %); the largest step of the right wheel's force between two positions, and the jumps: a step above 1 % "
             "of the load and three times both neighbouring steps with the number of patches unchanged is swept again "
             "in {} steps (nH-FastSim) and counted only where one of those alone stands out so (swept: how many "
             "steps were; a steep but continuous rise, as the flange engages, is not a jump); the largest "
             "difference between the rail's normal angle over a patch's overlap and its contact angle (a planar patch is "
             "flagged above {:g} rad, docs/WHEELSET.md §4).\n\n",
             o.y_step_m / kMm, o.element_size_m / kMm, contact_surface_name(o.contact_surface), kTarget_percent,
             kFineSteps, kLargeContactAngleVariation_rad);
  fmt::print(md, "| set-up | yaw (mrad) | tan γe (3 mm) | states | to y (mm) | patches | F1 miss (at y mm) | F2 miss (at y mm) "
                 "| largest step (kN, at y mm) | jumps (swept) | largest angle variation (rad) | within target |\n"
                 "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const SweepSummary& s : summaries) {
    const bool ok = std::abs(s.worst_dF1_percent) <= kTarget_percent && std::abs(s.worst_dF2_percent) <= kTarget_percent &&
                    s.jumps == 0;
    fmt::print(md, "| {} | {:+.0f} | {} | {} | {:.2f} | {} | {} ({:.2f}) | {} ({:.2f}) | {:.1f} ({:.2f}) | {} ({}) | {:.3f} | {} |\n",
               s.setup, s.yaw_rad * 1e3, std::isfinite(s.tan_gamma_e) ? fmt::format("{:.4f}", s.tan_gamma_e) : "–",
               s.states, s.last_y_m / kMm, s.most_patches, percent(s.worst_dF1_percent), s.worst_dF1_y_m / kMm,
               percent(s.worst_dF2_percent), s.worst_dF2_y_m / kMm, s.worst_step_N / 1e3, s.worst_step_y_m / kMm, s.jumps,
               s.fine_swept_steps, s.largest_angle_variation_rad, ok ? "yes" : "**no**");
  }
  for (const SweepSummary& s : summaries) {
    if (!s.stop.empty()) fmt::print(md, "\n- {} at yaw {:+.0f} mrad stopped before the flange-climb limit: {}\n", s.setup,
                                    s.yaw_rad * 1e3, s.stop);
    if (!s.fine_failure.empty())
      fmt::print(md, "\n- {} at yaw {:+.0f} mrad: a state of the 0.01 mm sweep again could not be solved, and its step "
                     "counts as a jump: {}\n",
                 s.setup, s.yaw_rad * 1e3, s.fine_failure);
  }
}

// summary.md's second part (with a table): the table against the wheelset on the fly, per sweep.
void print_table_check_md(std::ostream& md, const ProfilePairStudyOptions& o, const std::vector<SweepSummary>& summaries) {
  fmt::print(md,
             "\n## The wheelset table against the wheelset on the fly\n\n"
             "Per set-up a wheelset table (docs/WHEELSET_TABLE.md) over the sweeps' yaws, its lateral nodes midway "
             "between the sweep's positions ({:g} mm apart, {:g} mm over the last {:g} mm before the flange climbs; the "
             "last position itself a node; refined where a wheel's lateral normal force leaves the line between "
             "neighbouring nodes by more than {:g} % of the load), wheel loads from {:g} to {:g} kN in steps of {:g} kN; looked up at "
             "every state with the tangential forces in the vertical balance, against nH-FastSim on the fly. The "
             "largest difference of a wheel's force per track-frame component, over both wheels, as a share of μ Fz "
             "(target {:g} %). A state the table refuses counts against the target, unless a wheel's Y/Q there "
             "is beyond Nadal's flange-climb limit (tan γ − μ)/(1 + μ tan γ) at the contact angle γ of its steepest "
             "patch: the flange climbs there, and such states are listed apart.\n\n",
             o.y_step_m / kMm, 0.5 * o.y_step_m / kMm, kTableFineStretch_m / kMm, 100.0 * kTableRefinement,
             kTableLoads.front() * kWheelLoad_N / 1e3, kTableLoads.back() * kWheelLoad_N / 1e3,
             (kTableLoads[1] - kTableLoads[0]) * kWheelLoad_N / 1e3,
             kTableTarget_percent);
  fmt::print(md, "| set-up | yaw (mrad) | states | Fx (at y mm) | Fy (at y mm) | Fz (at y mm) | within target |\n"
                 "|---|---|---|---|---|---|---|\n");
  for (const SweepSummary& s : summaries) {
    bool ok = s.table_refused == 0;
    for (const double d : s.worst_table_percent) ok = ok && std::abs(d) <= kTableTarget_percent;
    fmt::print(md, "| {} | {:+.0f} | {}{} | {} ({:.2f}) | {} ({:.2f}) | {} ({:.2f}) | {} |\n", s.setup, s.yaw_rad * 1e3,
               s.table_states,
               fmt::format("{}{}", s.table_refused ? fmt::format(" ({} refused)", s.table_refused) : "",
                           s.table_refused_beyond_nadal
                               ? fmt::format(" ({} refused where the flange climbs)", s.table_refused_beyond_nadal)
                               : ""),
               percent(s.worst_table_percent[0]), s.worst_table_y_m[0] / kMm, percent(s.worst_table_percent[1]),
               s.worst_table_y_m[1] / kMm, percent(s.worst_table_percent[2]), s.worst_table_y_m[2] / kMm,
               ok ? "yes" : "**no**");
  }
  for (const SweepSummary& s : summaries) {
    if (s.table_refused)
      fmt::print(md, "\n- {} at yaw {:+.0f} mrad: the table refused {} states, the first: {}\n", s.setup,
                 s.yaw_rad * 1e3, s.table_refused, s.table_refusal);
    if (s.table_refused_beyond_nadal)
      fmt::print(md,
                 "\n- {} at yaw {:+.0f} mrad: the table refused {} states where the flange climbs by Nadal's "
                 "criterion (not counted above), the first: {}\n",
                 s.setup, s.yaw_rad * 1e3, s.table_refused_beyond_nadal, s.table_beyond_nadal);
  }
}

void write_summary_md(const output::OutputDirectory& out, const ProfilePairStudyOptions& o,
                      const std::vector<SweepSummary>& summaries) {
  std::ofstream md = output::open_output_file(out.path("summary.md"));
  print_sweeps_md(md, o, summaries);
  if (o.table) print_table_check_md(md, o, summaries);
  md.close();
  if (md.fail()) throw output::write_error(out.path("summary.md"), errno);
}

}  // namespace

void run_profile_pair_study(const ProfilePairStudyOptions& o, std::ostream& log) {
  validate_sweep(o.element_size_m, o.y_step_m, 1e-3, o.yaws_rad);
  const std::vector<std::filesystem::path> files = wheel_rail_setup_files(o.setups);
  require(!files.empty(), "study profiles: no wheel-rail set-up files");

  output::OutputDirectory out(o.output_directory, &log);
  SweepRows rows = open_sweep_rows(out, o.table);
  std::vector<SweepSummary> summaries;
  const auto start = std::chrono::steady_clock::now();
  const std::size_t sweeps = files.size() * o.yaws_rad.size();
  std::size_t done = 0;
  for (const std::filesystem::path& file : files) {
    const WheelRailSetup setup = read_wheel_rail_setup(file);
    const WheelsetTrack track = wheelset_track_of(setup);
    const PairGeometry geometry = pair_geometry(track, 0.1e-3);  // EN 15302 resolution, whatever the sweep step
    SetupSweeps sweeps_of{file.stem().string(), track, sweep_wheelset_options(o)};
    fmt::print(log, "{}: the flange climbs beyond y = {:.2f} mm; tan γe(3 mm) = {:.4f}\n", sweeps_of.name,
               geometry.climb_y_m / kMm, geometry.tan_gamma_e);
    sweeps_of.steps = static_cast<int>(std::floor(-geometry.climb_y_m / o.y_step_m + 1e-9));
    sweeps_of.tan_gamma_e = geometry.tan_gamma_e;
    std::optional<WheelsetTable> table;
    if (o.table) table = build_table(track, sweeps_of.options, sweeps_of.steps, o, log);  // on the sweeps' contact surface
    sweeps_of.table = table ? &*table : nullptr;
    for (const double yaw : o.yaws_rad) {
      const SweepSummary& s = summaries.emplace_back(sweep_at_yaw(sweeps_of, yaw, o.y_step_m, rows));
      ++done;
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fmt::print(log, "  yaw {:+.0f} mrad: {} states to y = {:.2f} mm ({}/{}), {:.0f} s left\n", yaw * 1e3, s.states,
                 s.last_y_m / kMm, done, sweeps, elapsed / static_cast<double>(done) * static_cast<double>(sweeps - done));
    }
  }
  close_sweep_rows(rows, out, o.table);
  write_pairs_csv(out, summaries);
  write_summary_md(out, o, summaries);
  if (o.figures) output::draw_figures("plot_profile_pairs.py", out.staging(), log);
  out.commit();
}

}  // namespace railcontact::study
