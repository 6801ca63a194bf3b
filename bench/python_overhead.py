#!/usr/bin/python3
"""The Python module's overhead against the C and C++ calls it wraps (issue #13's targets):

  1. a single-patch nh-fastsim call, railcontact.Solver.solve, at most 20 us more than the C++
     call (NhFastSim::forces, bench/c_api_bench.cpp BM_CppNhFastSimForces);
  2. a batch of 10 000 states, railcontact.Solver.batch, at most 5 % of its time outside the
     solver: the C API's rc_batch_creep_forces of the same states (BM_CApiBatch/1) is the solver's
     own time.

Both sides in one run: the script runs the benchmark binary (--benchmark_format=json) for the C
and C++ numbers, then times the same calls through Python on the same patch (a = 6 mm, b = 4 mm,
F3 = 80 kN, about 3000 elements, mu = 0.3) and the same states, one thread each.

Usage (from the project root, after the build):
  PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--build build] [--repeats 5]
Prints a table and, with --json FILE, writes the figures. Exit 1 when a target is missed.
The repeats interleave the two sides (one benchmark run, then the Python calls) so that both see
the same load on a shared machine; each figure is the median over the repeats.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np

A_M, B_M, F3_N, MU = 6e-3, 4e-3, 8e4, 0.3
CREEPAGE = (1e-3, 5e-4, 0.3)  # xi, eta, phi (1/m): as kCreepage of bench/c_api_bench.cpp
BATCH_STATES = 10000          # kBatchStates
SINGLE_TARGET_US = 20.0
BATCH_TARGET = 0.05


def batch_creepages():
    """The states of BM_CApiBatch: xi from -3e-3 to 3e-3, eta from 1e-3 to -1e-3, phi 0.3 1/m."""
    t = np.arange(BATCH_STATES, dtype=float) / (BATCH_STATES - 1)
    return np.column_stack([-3e-3 + 6e-3 * t, 1e-3 - 2e-3 * t, np.full(BATCH_STATES, 0.3)])


def run_benchmarks(binary, min_time):
    """Real time (us) of each benchmark of interest, from one run of the binary's JSON output."""
    names = ["BM_CppNhFastSimForces", "BM_CApiSolve", "BM_CApiBatch/1/real_time"]
    command = [binary, "--benchmark_filter=^(BM_CppNhFastSimForces|BM_CApiSolve|BM_CApiBatch/1/)",
               "--benchmark_format=json", f"--benchmark_min_time={min_time}"]
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    report = json.loads(out)
    scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}
    times = {b["name"]: b["real_time"] * scale[b["time_unit"]] for b in report["benchmarks"]}
    missing = [n for n in names if n not in times]
    if missing:
        sys.exit(f"python_overhead: {binary} did not report {missing}")
    return {n: times[n] for n in names}, " ".join(command), report["context"]


class PythonSide:
    """The same calls through the Python module, on one solver."""

    def __init__(self, seconds):
        import railcontact
        self.solver = railcontact.Solver("nh-fastsim", mu=MU, elements=3000)
        self.solver.set_ellipse(a=A_M, b=B_M, normal_force=F3_N)
        self.creepages = batch_creepages()
        xi, eta, phi = CREEPAGE
        start = time.perf_counter()
        calls = 0
        while time.perf_counter() - start < 0.05:
            self.solver.solve(xi, eta, phi)
            calls += 1
        self.calls = max(10, int(calls * seconds / 0.05))
        self.batch()  # warm-up

    def single(self):
        """Time per Solver.solve call (us), over self.calls calls."""
        xi, eta, phi = CREEPAGE
        solve = self.solver.solve
        start = time.perf_counter()
        for _ in range(self.calls):
            solve(xi, eta, phi)
        return (time.perf_counter() - start) / self.calls * 1e6

    def batch(self):
        """Time of one Solver.batch of the states on one thread (us)."""
        start = time.perf_counter()
        forces = self.solver.batch(self.creepages, threads=1)
        elapsed = (time.perf_counter() - start) * 1e6
        assert forces.shape == (BATCH_STATES, 4) and np.all(np.isfinite(forces))
        return elapsed


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build", help="the build directory (default: build)")
    parser.add_argument("--repeats", type=int, default=5, help="repeats of each measurement (median)")
    parser.add_argument("--min-time", type=float, default=0.2, help="--benchmark_min_time of the C/C++ side (s)")
    parser.add_argument("--json", help="write the figures into this file")
    args = parser.parse_args()

    binary = os.path.join(args.build, "bench", "c_api_bench")
    python = PythonSide(args.min_time)
    # Interleaved: each repeat runs the C/C++ side, then the Python side, so that both see the
    # same load on a shared machine; the figures are the medians over the repeats.
    runs = []
    for _ in range(args.repeats):
        cxx, command, context = run_benchmarks(binary, args.min_time)
        runs.append((cxx, python.single(), python.batch()))
    cpp = statistics.median(r[0]["BM_CppNhFastSimForces"] for r in runs)
    c_api = statistics.median(r[0]["BM_CApiSolve"] for r in runs)
    c_batch = statistics.median(r[0]["BM_CApiBatch/1/real_time"] for r in runs)
    py_single = statistics.median(r[1] for r in runs)
    py_batch = statistics.median(r[2] for r in runs)
    calls = python.calls
    single_extra = statistics.median(r[1] - r[0]["BM_CppNhFastSimForces"] for r in runs)
    batch_outside = statistics.median((r[2] - r[0]["BM_CApiBatch/1/real_time"]) / r[2] for r in runs)
    load = os.getloadavg()
    figures = {
        "cpp_nh_fastsim_forces_us": cpp,
        "c_api_solve_us": c_api,
        "python_solve_us": py_single,
        "python_minus_cpp_us": single_extra,
        "python_minus_c_api_us": py_single - c_api,
        "single_target_us": SINGLE_TARGET_US,
        "c_api_batch_us": c_batch,
        "python_batch_us": py_batch,
        "batch_states": BATCH_STATES,
        "batch_fraction_outside_solver": batch_outside,
        "batch_target": BATCH_TARGET,
        "benchmark_command": command,
        "repeats": args.repeats,
        "load_average": load,
        "cpus": context.get("num_cpus"),
    }
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}, {context.get('num_cpus')} CPUs; "
          f"medians of {args.repeats} interleaved repeats")
    print(f"C/C++ side: {command}")
    print("single patch, nh-fastsim, ~3000 elements (one call):")
    print(f"  C++ NhFastSim::forces          {cpp:9.2f} us")
    print(f"  C API rc_solver_solve          {c_api:9.2f} us  (+{c_api - cpp:.2f} us)")
    print(f"  Python Solver.solve            {py_single:9.2f} us  (+{single_extra:.2f} us over C++, "
          f"+{py_single - c_api:.2f} us over C; {calls} calls per repeat)")
    print(f"  target: at most {SINGLE_TARGET_US:g} us over C++: {'met' if single_extra <= SINGLE_TARGET_US else 'NOT met'}")
    print(f"batch of {BATCH_STATES} states, one thread, the patch prepared inside the call:")
    print(f"  C API rc_batch_creep_forces    {c_batch / 1e3:9.2f} ms  ({c_batch / BATCH_STATES:.2f} us per state)")
    print(f"  Python Solver.batch            {py_batch / 1e3:9.2f} ms  ({py_batch / BATCH_STATES:.2f} us per state)")
    print(f"  outside the solver: {100 * batch_outside:.2f} % of the Python call "
          f"(target at most {100 * BATCH_TARGET:g} %: {'met' if batch_outside <= BATCH_TARGET else 'NOT met'})")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(figures, f, indent=1)
    return 0 if single_extra <= SINGLE_TARGET_US and batch_outside <= BATCH_TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
