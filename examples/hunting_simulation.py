#!/usr/bin/python3
"""Hunting of a wheelset on tangent track: a time-domain simulation through railcontact's Python
module, finding the critical speed (docs/PYTHON.md "A hunting simulation").

The model: one wheelset (S1002 on UIC60 1:40, 1435 mm gauge, 98.1 kN per wheel) guided by its
primary suspension from a bogie frame that runs straight at constant speed V. Two degrees of
freedom, the lateral displacement y and the yaw angle psi of the wheelset:

    m  y''   = Fy_right + Fy_left - k_y y - c_y y'
    Iz psi'' = Mz - k_psi psi,             k_psi = k_x b^2  (k_x: both axle boxes, b: half their spacing)

Fy and Mz (about the wheelset centre, from every contact patch) come from railcontact at the
state (y, psi, V, y', psi'): the creepages, the gravitational stiffness of the contact angles and
the flange contact are all in the contact model. SciPy's solve_ivp (RK45) integrates.

Three contact models:
  table      nh-fastsim from a wheelset table (docs/WHEELSET_TABLE.md), built once, then ~10 us per
             evaluation;
  on-the-fly nh-fastsim solved at every evaluation (contact search, normal problem, K2, FastSim);
  fastsim    classic FastSim (Kalker's flexibilities of the equivalent ellipse), on the fly.

The critical speed is found with the table: for each speed, two runs start from a small (0.5 mm)
and a large (5 mm) lateral disturbance; the limit-cycle amplitude is the largest |y| over the last
second. The on-the-fly models are run at two speeds, below and above it, for comparison.

Usage: /usr/bin/python3 examples/hunting_simulation.py [--out DIR] [--quick]
Writes hunting.csv (amplitude against speed), hunting_runs.csv, hunting_summary.json and the
figures hunting_time.png, hunting_bifurcation.png, hunting_models.png into DIR.
"""
import argparse
import json
import os
import sys
import time

import numpy as np

try:
    import railcontact
except ImportError:  # run from the source tree: the build's module
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(here, "..", "build", "python"))
    import railcontact

from scipy.integrate import solve_ivp

# The wheelset and its primary suspension (SI units).
MASS_KG = 1500.0
YAW_INERTIA_KG_M2 = 900.0
LATERAL_STIFFNESS_N_PER_M = 2 * 0.2e6  # both axle boxes
LONGITUDINAL_STIFFNESS_N_PER_M = 2 * 1.0e6  # both axle boxes
HALF_BOX_SPACING_M = 1.0
LATERAL_DAMPING_N_S_PER_M = 2 * 2.0e3
WHEEL_LOAD_N = 98.1e3
MU = 0.3
HUNTING_AMPLITUDE_M = 1e-3  # a limit cycle larger than this is hunting


class Contact:
    """The contact forces of one model, with the time spent in them."""

    def __init__(self, name, wheelset, use_table):
        self.name, self.wheelset, self.use_table = name, wheelset, use_table
        self.seconds, self.evaluations = 0.0, 0

    def forces(self, y, psi, speed, vy, vpsi):
        """Fy of both wheels (N) and Mz about the wheelset centre (N m)."""
        start = time.perf_counter()
        if self.use_table:
            f = self.wheelset.table_forces(y, psi, speed=speed, lateral_velocity=vy, yaw_rate=vpsi)
            fy, mz = f[1] + f[4], f[6]
        else:
            r = self.wheelset.evaluate(y, yaw=psi, speed=speed, lateral_velocity=vy, yaw_rate=vpsi)
            fy = r.force_track_N[1]
            mz = sum(p.reference_point_track_m[0] * p.force_track_N[1] -
                     (p.reference_point_track_m[1] - y) * p.force_track_N[0]
                     for wheel in r.wheels for p in wheel.patches)
        self.seconds += time.perf_counter() - start
        self.evaluations += 1
        return fy, mz


def simulate(contact, speed, y0, duration):
    """One run: (t, y, psi, status) with status 'ok' or why it stopped (the flange climbing
    beyond the table, a contact error)."""
    k_psi = LONGITUDINAL_STIFFNESS_N_PER_M * HALF_BOX_SPACING_M ** 2

    def rhs(t, s):
        y, psi, vy, vpsi = s
        fy, mz = contact.forces(y, psi, speed, vy, vpsi)
        return [vy, vpsi, (fy - LATERAL_STIFFNESS_N_PER_M * y - LATERAL_DAMPING_N_S_PER_M * vy) / MASS_KG,
                (mz - k_psi * psi) / YAW_INERTIA_KG_M2]

    samples = []

    def recorded(t, s):
        samples.append((t, s[0], s[1]))
        return rhs(t, s)

    try:
        # rtol 1e-4, atol 0.1 um: an on-the-fly solve's forces step by the mesh's discretisation, and
        # tighter tolerances only shrink the steps (1e-6 / 1e-9: 6.5 times the evaluations, y within 0.03 um).
        sol = solve_ivp(recorded, (0.0, duration), [y0, 0.0, 0.0, 0.0], method="RK45", max_step=2e-3, rtol=1e-4,
                        atol=1e-7)
        return sol.t, sol.y[0], sol.y[1], "ok" if sol.success else sol.message
    except railcontact.RailcontactError as e:  # e.g. y beyond the table: the flange climbs
        t, y, psi = (np.array(v) for v in zip(*samples)) if samples else (np.zeros(1),) * 3
        return t, y, psi, f"stopped at t = {t[-1]:.3f} s: {e}"


def amplitude(t, y, duration):
    """The largest |y| over the last second (inf when the run stopped early)."""
    if t[-1] < duration - 1e-9:
        return float("inf")
    return float(np.max(np.abs(y[t >= duration - 1.0])))


class Progress:
    """A progress line with the time left (stderr): the time so far per item done, times the
    items left."""

    def __init__(self, total, what):
        self.total, self.done, self.what, self.start = total, 0, what, time.perf_counter()

    def step(self, note=""):
        """One more item done."""
        self.update(self.done + 1, note)

    def update(self, done, note="", total=None):
        """`done` items done in all (a table build's progress(done, total): its total grows as the build
        refines its y grid where the contact jumps)."""
        self.done = done
        if total is not None:
            self.total = total
        elapsed = time.perf_counter() - self.start
        left = elapsed / max(done, 1) * (self.total - done)
        note = f" {note}" if note else ""
        print(f"  [{100 * done / self.total:3.0f} %] {self.what} {done}/{self.total}{note}; "
              f"{elapsed:.0f} s, about {left:.0f} s left", file=sys.stderr, flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="railcontact-out/hunting", help="output directory")
    parser.add_argument("--quick", action="store_true",
                        help="a short check (coarse table and mesh, few speeds, short runs): for the tests")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    quick = args.quick
    # 0.5 mm elements (about 750 per tread patch): an on-the-fly evaluation then costs ~25 ms, not
    # the ~180 ms of 0.2 mm, so that the on-the-fly models can be run at all.
    element_size = 0.5e-3
    duration = 1.5 if quick else 5.0
    speeds = [40.0, 70.0] if quick else [float(v) for v in range(30, 96, 5)]
    compare_speeds = [70.0] if quick else [45.0, 70.0]
    compare_duration = 0.02 if quick else 1.0

    # The table: y over the tread and flange (the flange climbs beyond about 7 mm), yaw ±10 mrad.
    y_grid = np.round(np.arange(-7.0e-3, 7.0001e-3, 0.25e-3 if quick else 0.1e-3), 7)
    yaw_grid = np.arange(-10e-3, 10.001e-3, 5e-3)
    # One load in the table: its lookups balance with the normal forces alone, as the models compared below.
    tabled = railcontact.Wheelset(element_size=element_size, loads=(WHEEL_LOAD_N, WHEEL_LOAD_N), mu=MU,
                                  tangential_in_balance=False)
    table_file = os.path.join(args.out, f"wheelset_table_{element_size * 1e3:g}mm{'_quick' if quick else ''}.json")
    start = time.perf_counter()
    table_nodes_built = None  # with the y values the build adds where the contact jumps
    if os.path.exists(table_file):
        tabled.load_table(table_file)
        print(f"hunting: the wheelset table {table_file} (loaded)", file=sys.stderr)
    else:
        nodes = len(y_grid) * len(yaw_grid)
        print(f"hunting: building the wheelset table ({nodes} nodes, elements {element_size * 1e3:g} mm)",
              file=sys.stderr)
        progress = Progress(nodes, "table nodes")
        every = max(1, nodes // 10)  # about ten lines, the last at the end
        # Without the y refinement (the default adds nodes where the flange snaps in): the figures
        # of docs/PYTHON.md "Hunting" were measured on this grid.
        tabled.build_table(y_grid, yaw_grid, (WHEEL_LOAD_N,),
                           progress=lambda done, total: progress.update(done, total=total)
                           if done % every == 0 or done == total else None,
                           refine_lateral_force_fraction=0.0)
        tabled.save_table(table_file)
        table_nodes_built = progress.total
    table_seconds = time.perf_counter() - start

    # The critical speed, with the table.
    table_contact = Contact("table", tabled, True)
    rows, runs = [], {}
    progress = Progress(2 * len(speeds), "runs")
    sim_start = time.perf_counter()
    for v in speeds:
        row = {"speed_m_per_s": v}
        for label, y0 in (("small", 0.5e-3), ("large", 5e-3)):
            t, y, psi, status = simulate(table_contact, v, y0, duration)
            runs[(v, label)] = (t, y)
            row[f"amplitude_{label}_start_m"] = amplitude(t, y, duration)
            row[f"status_{label}_start"] = status
            progress.step(f"V = {v:g} m/s, {label} start: {status if status != 'ok' else 'ok'}")
        rows.append(row)
    sim_seconds = time.perf_counter() - sim_start

    def critical(key):
        hunting = [r["speed_m_per_s"] for r in rows if r[key] > HUNTING_AMPLITUDE_M]
        return min(hunting) if hunting else None

    # Quick mode's coarse table, two speeds and 1.5 s runs check the machinery; they locate no
    # critical speed.
    linear_critical = None if quick else critical("amplitude_small_start_m")
    nonlinear_critical = None if quick else critical("amplitude_large_start_m")

    # The three contact models at the comparison speeds.
    models = [table_contact,
              Contact("on-the-fly nh-fastsim",
                      railcontact.Wheelset(element_size=element_size, loads=(WHEEL_LOAD_N, WHEEL_LOAD_N), mu=MU,
                                           tangential_in_balance=False), False),
              Contact("on-the-fly fastsim",
                      railcontact.Wheelset(element_size=element_size, loads=(WHEEL_LOAD_N, WHEEL_LOAD_N), mu=MU,
                                           solvers=("fastsim",), tangential_in_balance=False), False)]
    comparison = {}
    progress = Progress(len(models) * len(compare_speeds), "model runs")
    for contact in models:
        contact.seconds, contact.evaluations = 0.0, 0
        if not contact.use_table:
            contact.wheelset.time_stages(True)  # where an evaluation on the fly spends its time
        run_start = time.perf_counter()
        for v in compare_speeds:
            t, y, psi, status = simulate(contact, v, 3e-3, compare_duration)
            comparison[(contact.name, v)] = (t, y, status)
            progress.step(f"{contact.name} at V = {v:g} m/s: {status}")
        total = time.perf_counter() - run_start
        contact.total_seconds = total
    cost = [{"model": c.name, "evaluations": c.evaluations,
             "us_per_evaluation": 1e6 * c.seconds / max(1, c.evaluations),
             "share_of_simulation_in_contact": c.seconds / max(c.total_seconds, 1e-12),
             "simulation_seconds": c.total_seconds,
             # On the fly: µs per evaluation in each of the wheelset's stages (docs/WHEELSET.md §8).
             "stage_us_per_evaluation": {} if c.use_table else
             {name[:-2]: 1e6 * value / max(1, c.evaluations)
              for name, value in c.wheelset.stage_times().items() if name.endswith("_s") and name != "total_s"}}
            for c in models]

    # Outputs.
    with open(os.path.join(args.out, "hunting.csv"), "w") as f:
        f.write("speed_m_per_s,amplitude_small_start_m,amplitude_large_start_m,status_small_start,status_large_start\n")
        for r in rows:
            f.write(f"{r['speed_m_per_s']:g},{r['amplitude_small_start_m']:.6e},{r['amplitude_large_start_m']:.6e},"
                    f"\"{r['status_small_start']}\",\"{r['status_large_start']}\"\n")
    with open(os.path.join(args.out, "hunting_runs.csv"), "w") as f:
        f.write("model,speed_m_per_s,time_s,y_m\n")
        for (name, v), (t, y, _) in comparison.items():
            for ti, yi in zip(t, y):
                f.write(f"{name},{v:g},{ti:.6f},{yi:.6e}\n")
    summary = {"railcontact_version": railcontact.__version__,
               "model": {"mass_kg": MASS_KG, "yaw_inertia_kg_m2": YAW_INERTIA_KG_M2,
                         "lateral_stiffness_N_per_m": LATERAL_STIFFNESS_N_PER_M,
                         "longitudinal_stiffness_N_per_m": LONGITUDINAL_STIFFNESS_N_PER_M,
                         "half_box_spacing_m": HALF_BOX_SPACING_M, "lateral_damping_N_s_per_m": LATERAL_DAMPING_N_S_PER_M,
                         "wheel_load_N": WHEEL_LOAD_N, "friction_coefficient": MU, "element_size_m": element_size},
               "table": {"file": table_file, "y_values": len(y_grid), "yaw_values": len(yaw_grid),
                         "nodes_built": table_nodes_built,
                         "seconds_to_build_or_load": table_seconds},
               "duration_s": duration, "speeds_m_per_s": speeds,
               "critical_speed_small_start_m_per_s": linear_critical,
               "critical_speed_large_start_m_per_s": nonlinear_critical,
               "table_simulation_seconds": sim_seconds, "cost": cost, "quick": quick}
    with open(os.path.join(args.out, "hunting_summary.json"), "w") as f:
        json.dump(summary, f, indent=2, allow_nan=True)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    shown = [v for v in speeds if v in (40.0, 50.0, 55.0, 60.0, 70.0)] or speeds[:3]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for v in shown:
        t, y = runs[(v, "small")]
        ax.plot(t, 1e3 * y, label=f"V = {v:g} m/s")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("lateral displacement y (mm)")
    ax.set_title("Wheelset on tangent track, start 0.5 mm off centre (nh-fastsim from the table)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "hunting_time.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, label, marker in (("amplitude_small_start_m", "start 0.5 mm", "o"),
                               ("amplitude_large_start_m", "start 5 mm", "s")):
        v = [r["speed_m_per_s"] for r in rows if np.isfinite(r[key])]
        a = [1e3 * r[key] for r in rows if np.isfinite(r[key])]
        ax.plot(v, a, marker=marker, label=label)
    stopped = [r["speed_m_per_s"] for r in rows if not np.isfinite(r["amplitude_small_start_m"])]
    if stopped:
        ax.axvspan(min(stopped) - 2.5, max(stopped) + 2.5, color="red", alpha=0.1,
                   label="flange climbs beyond the table")
    ax.set_xlabel("speed V (m/s)")
    ax.set_ylabel("limit-cycle amplitude (mm)")
    ax.set_title("Hunting: limit-cycle amplitude against speed")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "hunting_bifurcation.png"), dpi=120)

    fig, axes = plt.subplots(len(compare_speeds), 1, figsize=(8, 3.2 * len(compare_speeds)), squeeze=False)
    for ax, v in zip(axes[:, 0], compare_speeds):
        for c in models:
            t, y, _ = comparison[(c.name, v)]
            ax.plot(t, 1e3 * y, label=c.name)
        ax.set_title(f"V = {v:g} m/s, start 3 mm off centre")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("y (mm)")
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "hunting_models.png"), dpi=120)

    print(f"Hunting of a wheelset (S1002 / UIC60 1:40, {WHEEL_LOAD_N / 1e3:g} kN per wheel), {args.out}")
    if quick:
        print(f"  quick mode (a check of the machinery): no critical speed; the {duration:g} s runs at "
              f"{', '.join(f'{v:g}' for v in speeds)} m/s on a coarse table are too short and too few to locate one "
              "(run without --quick)")
        for r in rows:
            print(f"  V = {r['speed_m_per_s']:g} m/s: largest |y| over the last second "
                  f"{1e3 * r['amplitude_small_start_m']:.2f} mm from a 0.5 mm start")
    else:
        print(f"  critical speed: {linear_critical} m/s from a 0.5 mm start, {nonlinear_critical} m/s from a 5 mm "
              f"start ({duration:g} s runs, speeds {speeds[0]:g} ... {speeds[-1]:g} m/s)")
    for c in cost:
        print(f"  {c['model']:<22} {c['us_per_evaluation']:9.1f} us per contact evaluation, "
              f"{100 * c['share_of_simulation_in_contact']:5.1f} % of the simulation in contact "
              f"({c['evaluations']} evaluations, {c['simulation_seconds']:.1f} s)")
        if c["stage_us_per_evaluation"]:
            stages = sorted(c["stage_us_per_evaluation"].items(), key=lambda item: -item[1])
            print("    " + ", ".join(f"{name} {us:.0f}" for name, us in stages) + " us")
    print(f"  table: {table_seconds:.1f} s to build or load; the speed sweep took {sim_seconds:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
