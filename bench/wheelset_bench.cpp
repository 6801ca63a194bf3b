// Wheelset evaluation timing (docs/WHEELSET.md §8): S1002 on UIC60 1:40, both wheels, 0.2 mm
// elements, 98.1 kN per wheel, V = 20 m/s.
//   BM_WheelsetTimeStep        by position, a time step: the wheelset moves 1 µm laterally per
//                              evaluation, back and forth over 50 µm (warm start: plans and pressures of the previous step)
//   BM_WheelsetCold            by position, a fresh Wheelset per evaluation (plans built, no warm start)
//   BM_WheelsetByLoad          by load (each wheel's height solved, tangential forces in the balance),
//                              the time step's lateral steps; ...Balanced: the roll balanced too
//   BM_WheelsetStepExact       the time step with the exact solver instead of nH-FastSim
//   BM_WheelsetStepFullK2      the time step with nH-FastSim's K2 on the patch itself (coarsening 1)
//   BM_WheelsetStepRigidSlip   the time step with the rigid-slip direction instead of the elastic slip
//   BM_WheelsetStepConformal   the time step on conformal contact surfaces (docs/WHEELSET.md §4)
//   BM_WheelsetStage...        the time step's stages one by one (see stage_inputs below)
//   BM_WheelsetCoupledStep     the time step of S1002 on UIC60 at 1:30 (data/wheel_rail/
//                              s1002_uic60_1in30.json) at y = -5.0 mm, where the right wheel's tread
//                              and flange root are separate patches 3.9 mm apart: argument 1 with
//                              their elastic coupling (docs/WHEELSET.md §5 "Coupled patches"), 0 without
//   BM_WheelsetTable           the time step from a wheelset table (wheelset_table.hpp; ...Radial,
//                              ...RigidSlip: with that slip direction instead of the default): y within
//                              ±0.5 mm of the argument in 1 µm steps, 98.1 kN per wheel, 2 mrad of
//                              yaw; the table (0.2 mm elements, y in 0.1 mm steps over ±0.5 mm,
//                              90/100/110 kN) is built before the timing; ...Auto: the table
//                              built on the automatic contact surface
//   BM_WheelsetStageBreakdown  the time step by position (as BM_WheelsetTimeStep) and, with
//                              argument ...1 appended (BreakdownByLoad), the time step by load
//                              (as BM_WheelsetByLoad), its stages timed inside the step
//                              (Wheelset::time_stages): counters in ms per step (docs/WHEELSET.md
//                              §8 "Where a step's time goes")
// Counters: patches, elements in contact, and the normal solver's iterations per patch of the last
// evaluation.
// The argument is y in micrometres (BM_WheelsetByLoad and BM_WheelsetTable: each wheel's own height
// at zero roll, the y-sweep's states, flange contact to -6.8 mm); contact search, normal problem and the tangential solver are
// all included.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "railcontact/normal.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"
#include "railcontact/wheelset_table.hpp"

namespace {

using namespace railcontact;

const WheelsetTrack& track() {
  static const WheelsetTrack t = default_wheelset_track();
  return t;
}

// A state at y where both wheels carry 98.1 kN vertically: the wheelset's height and roll solved
// together (WheelLoads::balance_roll), the state of a rigid axle under its load. In flange contact
// (y = -6.3 ... -6.6 mm) the flange then carries F3 = 147-267 kN. Each wheel's own height at zero
// roll is not such a state: at y = -6.8 mm it presses the flange with F3 = 1.13 MN, six times the
// physical load (with both loads balanced the flange climbs there; docs/WHEELSET.md §8).
WheelsetState loaded_state(double y_m) {
  WheelsetOptions balanced;
  balanced.loads = WheelLoads{98.1e3, 98.1e3, true};
  Wheelset by_load(track(), balanced);
  WheelsetState s;
  s.position.lateral_displacement_m = y_m;
  s.position = by_load.evaluate(s).state.position;
  return s;
}

WheelsetOptions by_position(TangentialSolver solver = TangentialSolver::nh_fastsim, int coarsening = 0) {
  WheelsetOptions o;
  o.loads.reset();
  o.solvers = {solver};
  o.nh_fastsim.flexibility_coarsening = coarsening;
  return o;
}

void report(benchmark::State& state, const WheelsetResult& r) {
  std::size_t patches = 0, elements = 0;
  int iterations = 0;
  for (const WheelResult& w : r.wheels) {
    patches += w.patches.size();
    for (const WheelsetPatch& p : w.patches) {
      elements += p.elements_in_contact;
      iterations += p.normal_iterations;
    }
  }
  state.counters["patches"] = static_cast<double>(patches);
  state.counters["contact_elements"] = static_cast<double>(elements);
  state.counters["normal_iterations"] = patches > 0 ? static_cast<double>(iterations) / patches : 0.0;
}

// The time step's lateral displacement: 1 µm per step, back and forth over 50 µm (a drift of a
// whole run would carry a flange state off its contact).
double stepped_y_m(double y0_m, long step) {
  const long k = step % 100;
  return y0_m + 1e-6 * static_cast<double>(k < 50 ? k : 100 - k);
}

void time_step(benchmark::State& state, TangentialSolver solver, int coarsening = 0,
               ContactSurface surface = ContactSurface::planar,
               SlipDirection slip_direction = WheelsetOptions{}.nh_fastsim.bound.slip_direction) {
  WheelsetState s = loaded_state(static_cast<double>(state.range(0)) * 1e-6);
  const double y0 = s.position.lateral_displacement_m;
  WheelsetOptions options = by_position(solver, coarsening);
  options.contact_surface = surface;
  options.nh_fastsim.bound.slip_direction = slip_direction;
  Wheelset wheelset(track(), options);
  WheelsetResult r = wheelset.evaluate(s);
  long step = 0;
  for (auto _ : state) {
    s.position.lateral_displacement_m = stepped_y_m(y0, ++step);
    r = wheelset.evaluate(s);
    benchmark::DoNotOptimize(r.force_track_N);
  }
  report(state, r);
}

void BM_WheelsetTimeStep(benchmark::State& state) { time_step(state, TangentialSolver::nh_fastsim); }
void BM_WheelsetStepExact(benchmark::State& state) { time_step(state, TangentialSolver::exact); }
void BM_WheelsetStepFullK2(benchmark::State& state) { time_step(state, TangentialSolver::nh_fastsim, 1); }
// The time step with the rigid-slip direction instead of the default elastic slip (the cost of the
// full-slip iteration where a patch slips everywhere).
void BM_WheelsetStepRigidSlip(benchmark::State& state) {
  time_step(state, TangentialSolver::nh_fastsim, 0, ContactSurface::planar, SlipDirection::rigid_slip);
}
// The same steps on conformal contact surfaces (docs/WHEELSET.md §4 "Conformal contact").
void BM_WheelsetStepConformal(benchmark::State& state) {
  time_step(state, TangentialSolver::nh_fastsim, 0, ContactSurface::conformal);
}

void BM_WheelsetCold(benchmark::State& state) {
  const WheelsetState s = loaded_state(static_cast<double>(state.range(0)) * 1e-6);
  const Wheelset prototype(track(), by_position());
  WheelsetResult r;
  for (auto _ : state) {
    Wheelset wheelset(prototype);  // a copy starts cold
    r = wheelset.evaluate(s);
    benchmark::DoNotOptimize(r.force_track_N);
  }
  report(state, r);
}

// The time step where a wheel has two patches within the coupling distance, with and without the
// coupling (the argument), by position at the loaded state of a rigid axle.
void BM_WheelsetCoupledStep(benchmark::State& state) {
  const WheelsetTrack t(load_wheel_rail_pair(
      read_wheel_rail_setup(std::string(RAILCONTACT_DATA_DIR) + "/wheel_rail/s1002_uic60_1in30.json")));
  WheelsetOptions balanced;
  balanced.loads = WheelLoads{98.1e3, 98.1e3, true};
  WheelsetState s;
  s.position.lateral_displacement_m = -5.0e-3;
  s.position = Wheelset(t, balanced).evaluate(s).state.position;
  const double y0 = s.position.lateral_displacement_m;
  WheelsetOptions options = by_position();
  if (state.range(0) == 0) options.patch_coupling = {0.0, 0.0};
  Wheelset wheelset(t, options);
  WheelsetResult r = wheelset.evaluate(s);
  long step = 0;
  for (auto _ : state) {
    s.position.lateral_displacement_m = stepped_y_m(y0, ++step);
    r = wheelset.evaluate(s);
    benchmark::DoNotOptimize(r.force_track_N);
  }
  report(state, r);
}

// The time step's lateral steps by load from y = the argument (µm), with these loads.
void by_load_steps(benchmark::State& state, const WheelLoads& loads) {
  WheelsetState s;
  const double y0 = static_cast<double>(state.range(0)) * 1e-6;
  s.position.lateral_displacement_m = y0;
  WheelsetOptions o;
  o.loads = loads;
  Wheelset wheelset(track(), o);
  WheelsetResult r = wheelset.evaluate(s);
  long step = 0;
  for (auto _ : state) {
    s.position.lateral_displacement_m = stepped_y_m(y0, ++step);
    r = wheelset.evaluate(s);
    benchmark::DoNotOptimize(r.force_track_N);
  }
  report(state, r);
}

void BM_WheelsetByLoad(benchmark::State& state) { by_load_steps(state, WheelLoads{}); }

// By load with the roll balanced too (WheelLoads::balance_roll: a rigid axle carrying both loads,
// the states of loaded_state): each wheel's height, the axle's roll and the tangential forces'
// vertical part solved.
void BM_WheelsetByLoadBalanced(benchmark::State& state) { by_load_steps(state, WheelLoads{98.1e3, 98.1e3, true}); }

// The time step's stages one by one (both wheels, the state of BM_WheelsetTimeStep), through the
// public API: the contact search; the potential contact areas with their undeformed distance;
// the normal problems on the whole areas, each started from the previous step's pressure (the
// wheelset first tries the window of the previous contact, docs/WHEELSET.md §8, so its normal stage
// is cheaper than this one); nH-FastSim on the patches (its K2 and flexibilities, then the march).
struct StageInputs {
  WheelsetPosition position, previous;
  std::vector<InterpenetrationRegion> regions;
  std::vector<TangentPlaneArea> areas;
  std::vector<std::vector<double>> previous_pressure_Pa, pressure_Pa;
};
StageInputs stage_inputs(double y_um) {
  StageInputs in;
  in.position = loaded_state(y_um * 1e-6).position;
  in.previous = in.position;
  in.previous.lateral_displacement_m -= 1e-6;
  const WheelsetOptions o;
  for (const WheelSide side : {WheelSide::right, WheelSide::left})
    for (const InterpenetrationRegion& r : track().contact_search(side, in.position).regions) {
      in.regions.push_back(r);
      in.areas.push_back(track().potential_contact_area(in.position, r, o.element_size_m));
      const TangentPlaneArea& a = in.areas.back();
      NormalContactSolver solver(a.mesh, o.material, o.normal);
      // The previous step's pressure on this mesh: the overlap 1 µm earlier, on the same elements.
      const std::vector<double> h_before = track().undeformed_distance_m(in.previous, r, a.mesh);
      in.previous_pressure_Pa.push_back(solver.solve_at_approach(h_before, 0.0).pressure_Pa);
      in.pressure_Pa.push_back(solver.solve_at_approach(a.h_m, 0.0).pressure_Pa);
    }
  return in;
}

void BM_WheelsetStageSearch(benchmark::State& state) {
  const StageInputs in = stage_inputs(static_cast<double>(state.range(0)));
  for (auto _ : state)
    for (const WheelSide side : {WheelSide::right, WheelSide::left})
      benchmark::DoNotOptimize(track().contact_search(side, in.position));
}

void BM_WheelsetStageArea(benchmark::State& state) {
  const StageInputs in = stage_inputs(static_cast<double>(state.range(0)));
  const WheelsetOptions o;
  for (auto _ : state)
    for (const InterpenetrationRegion& r : in.regions)
      benchmark::DoNotOptimize(track().potential_contact_area(in.position, r, o.element_size_m));
}

void BM_WheelsetStageNormal(benchmark::State& state) {
  const StageInputs in = stage_inputs(static_cast<double>(state.range(0)));
  const WheelsetOptions o;
  std::vector<NormalContactSolver> solvers;
  for (const TangentPlaneArea& a : in.areas) solvers.emplace_back(a.mesh, o.material, o.normal);
  int iterations = 0;
  for (auto _ : state) {
    iterations = 0;
    for (std::size_t k = 0; k < solvers.size(); ++k) {
      const NormalSolution n = solvers[k].solve_at_approach(in.areas[k].h_m, 0.0, in.previous_pressure_Pa[k]);
      iterations += n.iterations;
      benchmark::DoNotOptimize(n.normal_force_N);
    }
  }
  state.counters["normal_iterations"] = static_cast<double>(iterations) / static_cast<double>(solvers.size());
}

void BM_WheelsetStageTangential(benchmark::State& state) {
  const StageInputs in = stage_inputs(static_cast<double>(state.range(0)));
  const WheelsetOptions o;
  const Creepage creepage{0.5e-3, 0.3e-3, 0.1};
  for (auto _ : state)
    for (std::size_t k = 0; k < in.areas.size(); ++k) {
      const ContactPatch patch(in.areas[k].mesh, in.pressure_Pa[k], o.material);
      const NhFastSim nh(patch, o.nh_fastsim);
      benchmark::DoNotOptimize(nh.solve(creepage, o.friction_coefficient).forces);
    }
}

// The time step's own stages, timed inside the step (Wheelset::time_stages): ms per step in each,
// the same states and steps as BM_WheelsetTimeStep (by position) and BM_WheelsetByLoad (by load).
void stage_breakdown(benchmark::State& state, bool by_load) {
  WheelsetState s;
  WheelsetOptions options;
  if (by_load) {
    s.position.lateral_displacement_m = static_cast<double>(state.range(0)) * 1e-6;
  } else {
    s = loaded_state(static_cast<double>(state.range(0)) * 1e-6);
    options = by_position();
  }
  const double y0 = s.position.lateral_displacement_m;
  Wheelset wheelset(track(), options);
  WheelsetResult r = wheelset.evaluate(s);
  wheelset.time_stages(true);
  long step = 0;
  double normal_solves = 0.0;  // by load: of both wheels' height iterations, over the steps
  for (auto _ : state) {
    s.position.lateral_displacement_m = stepped_y_m(y0, ++step);
    r = wheelset.evaluate(s);
    benchmark::DoNotOptimize(r.force_track_N);
    normal_solves += r.wheels[0].load_iterations + r.wheels[1].load_iterations;
  }
  report(state, r);
  const WheelsetStageTimes& t = wheelset.stage_times();
  const double per_step_ms = 1e3 / static_cast<double>(std::max(1L, t.evaluations));
  state.counters["search_ms"] = t.search_s * per_step_ms;
  state.counters["area_ms"] = t.area_s * per_step_ms;
  state.counters["normal_ms"] = t.normal_s * per_step_ms;
  state.counters["height_ms"] = t.height_s * per_step_ms;
  state.counters["kinematics_ms"] = t.kinematics_s * per_step_ms;
  state.counters["tangential_ms"] = t.tangential_s * per_step_ms;
  state.counters["assembly_ms"] = t.assembly_s * per_step_ms;
  state.counters["stages_ms"] = t.total_s() * per_step_ms;
  if (by_load) state.counters["normal_solves_per_wheel"] = normal_solves / (2.0 * static_cast<double>(step));
}
void BM_WheelsetStageBreakdown(benchmark::State& state) { stage_breakdown(state, false); }
void BM_WheelsetStageBreakdownByLoad(benchmark::State& state) { stage_breakdown(state, true); }

// The wheelset's default slip direction for nH-FastSim (WheelsetOptions).
const SlipDirection kDefaultSlipDirection = WheelsetOptions{}.nh_fastsim.bound.slip_direction;

void wheelset_table_step(benchmark::State& state, SlipDirection slip_direction, bool tangential_in_balance = false,
                         ContactSurface surface = ContactSurface::planar) {
  const double y0 = static_cast<double>(state.range(0)) * 1e-6;
  std::vector<double> ys;
  for (int k = -5; k <= 5; ++k) ys.push_back(y0 + k * 0.1e-3);
  WheelsetTableOptions options;
  options.wheelset.nh_fastsim.bound.slip_direction = slip_direction;
  options.wheelset.contact_surface = surface;
  const WheelsetTable table = build_wheelset_table(track(), {ys, {0.0}, {90e3, 100e3, 110e3}}, options);
  WheelsetState s;
  s.position.yaw_rad = 2e-3;
  const WheelLoads loads{98.1e3, 98.1e3, false};
  WheelsetResult r;
  long step = 0;
  for (auto _ : state) {
    s.position.lateral_displacement_m = y0 + static_cast<double>(step++ % 1000 - 500) * 1e-6;
    r = table.evaluate(s, loads, 0.3, tangential_in_balance);
    benchmark::DoNotOptimize(r.force_track_N);
  }
  report(state, r);
}

// The wheelset's default slip direction (elastic-slip), the rigid-slip one (without the full-slip
// iteration) and Eq 8's radial one.
void BM_WheelsetTable(benchmark::State& state) { wheelset_table_step(state, kDefaultSlipDirection); }
void BM_WheelsetTableRigidSlip(benchmark::State& state) { wheelset_table_step(state, SlipDirection::rigid_slip); }
void BM_WheelsetTableRadial(benchmark::State& state) { wheelset_table_step(state, SlipDirection::radial); }
// With the tangential forces in the vertical balance, as the command line, the C API and Python
// look the table up (a secant on the table's load: two or three lookups).
void BM_WheelsetTableBalanced(benchmark::State& state) {
  wheelset_table_step(state, kDefaultSlipDirection, true);
}
// A table built on the automatic surface: the flange patch (weight 1) marched strip by strip.
void BM_WheelsetTableAuto(benchmark::State& state) {
  wheelset_table_step(state, kDefaultSlipDirection, false, ContactSurface::automatic);
}
// The same with the rigid-slip direction: what the curved surface costs a lookup by itself.
void BM_WheelsetTableAutoRigidSlip(benchmark::State& state) {
  wheelset_table_step(state, SlipDirection::rigid_slip, false, ContactSurface::automatic);
}

BENCHMARK(BM_WheelsetTimeStep)->Arg(0)->Arg(-6300)->Arg(-6400)->Arg(-6500)->Arg(-6600)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStageSearch)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStageArea)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStageNormal)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStageTangential)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStageBreakdown)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStageBreakdownByLoad)->Arg(0)->Arg(-6800)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetCold)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetCoupledStep)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetByLoad)->Arg(0)->Arg(-6800)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetByLoadBalanced)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStepExact)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStepFullK2)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStepConformal)->Arg(0)->Arg(-6500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetStepRigidSlip)->Arg(0)->Arg(-6500)->Arg(-6600)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WheelsetTable)->Arg(0)->Arg(-6800)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WheelsetTableRigidSlip)->Arg(0)->Arg(-6800)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WheelsetTableRadial)->Arg(0)->Arg(-6800)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WheelsetTableBalanced)->Arg(0)->Arg(-6800)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WheelsetTableAuto)->Arg(0)->Arg(-6800)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WheelsetTableAutoRigidSlip)->Arg(0)->Arg(-6800)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
