#!/usr/bin/python3
"""The Python module's overhead against the C and C++ calls it wraps (issue #13's targets):

  1. a single-patch nh-fastsim call, railcontact.Solver.solve, at most 20 us more than the C++
     call (NhFastSim::forces, bench/c_api_bench.cpp BM_CppNhFastSimForces);
  2. a batch of 10 000 states, railcontact.Solver.batch, at most 5 % of its time outside the
     solver: the C API's rc_batch_creep_forces of the same states is the solver's own time.

Both sides in one run, on the same patch (a = 6 mm, b = 4 mm, F3 = 80 kN, about 3000 elements,
mu = 0.3) and the same states, one thread each:
  - the single call: the benchmark binary build/bench/c_api_bench (--benchmark_format=json) for
    the C++ and C calls, then the Python calls;
  - the batch: rc_batch_creep_forces of the shared library (BUILD/librailcontact.so, through
    ctypes: one foreign call per batch) and Solver.batch back to back in this process, so that
    both run with the same process, heap and core (a separate process scattered by +-20 % against
    this one on a shared machine); BM_CApiBatch/1 of the binary is printed for reference.

Usage (from the project root, after the build):
  PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--build build] [--repeats 5]
Prints a table and, with --json FILE, writes the figures. Exit 1 when a target is missed.
Times are CPU times (Google Benchmark's cpu_time; time.process_time() here, every call on the
calling thread): on a shared machine the wall time also counts the waits for a core, which
scattered the wall-time comparison by +-20 %. The repeats interleave the two sides (one benchmark
run, then the Python calls); each figure is the median over the repeats.
"""
import argparse
import ctypes
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


class CBatch:
    """rc_batch_creep_forces of the shared library through ctypes (one call per batch)."""

    class Settings(ctypes.Structure):  # rc_settings, in the header's order
        _fields_ = [(name, ctypes.c_double) for name in (
            "youngs_modulus_Pa", "poisson_ratio", "friction_coefficient", "mesh_value", "bound_skew",
            "collocation_offset", "tolerance", "krylov_tolerance", "regularisation", "normal_tolerance",
            "jacobian_step_creepage", "jacobian_step_spin_per_m")] + [(name, ctypes.c_int) for name in (
                "method", "mesh_mode", "flexibility_coarsening", "slip_direction", "max_newton_iterations",
                "max_krylov_iterations", "normal_max_iterations")]

    class Patch(ctypes.Structure):  # rc_patch
        _fields_ = [(name, ctypes.c_double) for name in (
            "normal_force_N", "a_m", "b_m", "A_per_m", "B_per_m", "grid_dx1_m", "grid_dx2_m")] + [
            ("grid_h_m", ctypes.POINTER(ctypes.c_double))] + [(name, ctypes.c_int) for name in (
                "kind", "grid_n1", "grid_n2", "reserved")]

    def __init__(self, library):
        self.lib = ctypes.CDLL(library)
        self.solver = ctypes.c_void_p()
        self.lib.rc_solver_create(ctypes.byref(self.solver))
        settings = self.Settings()
        self.lib.rc_settings_default(ctypes.byref(settings))
        settings.mesh_value = 3000.0
        settings.friction_coefficient = MU
        if self.lib.rc_solver_set_settings(self.solver, ctypes.byref(settings)) != 0:
            sys.exit("python_overhead: rc_solver_set_settings failed")
        self.patch = self.Patch(normal_force_N=F3_N, a_m=A_M, b_m=B_M, kind=0)
        self.creepages = batch_creepages()
        self.forces = np.zeros((BATCH_STATES, 4))
        self.statuses = np.zeros(BATCH_STATES, dtype=np.intc)
        self.lib.rc_batch_creep_forces.argtypes = [
            ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_int,
            ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]

    def batch(self):
        """Time of one rc_batch_creep_forces of the states on one thread (us)."""
        start = time.process_time()
        status = self.lib.rc_batch_creep_forces(
            self.solver, BATCH_STATES, ctypes.byref(self.patch), 1, self.creepages.ctypes.data, 1,
            self.forces.ctypes.data, None, None, self.statuses.ctypes.data)
        elapsed = (time.process_time() - start) * 1e6
        if status != 0:
            sys.exit(f"python_overhead: rc_batch_creep_forces failed ({status})")
        return elapsed


def run_benchmarks(binary, min_time):
    """CPU time (us) of each benchmark of interest, from one run of the binary's JSON output."""
    names = ["BM_CppNhFastSimForces", "BM_CApiSolve", "BM_CApiBatch/1/real_time"]
    command = [binary, "--benchmark_filter=^(BM_CppNhFastSimForces|BM_CApiSolve|BM_CApiBatch/1/)",
               "--benchmark_format=json", f"--benchmark_min_time={min_time}"]
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    report = json.loads(out)
    scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}
    times = {b["name"]: b["cpu_time"] * scale[b["time_unit"]] for b in report["benchmarks"]}
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
        start = time.process_time()
        calls = 0
        while time.process_time() - start < 0.05:
            self.solver.solve(xi, eta, phi)
            calls += 1
        self.calls = max(10, int(calls * seconds / 0.05))
        self.batch()  # warm-up

    def single(self):
        """Time per Solver.solve call (us), over self.calls calls."""
        xi, eta, phi = CREEPAGE
        solve = self.solver.solve
        start = time.process_time()
        for _ in range(self.calls):
            solve(xi, eta, phi)
        return (time.process_time() - start) / self.calls * 1e6

    def batch(self):
        """Time of one Solver.batch of the states on one thread (us)."""
        start = time.process_time()
        forces = self.solver.batch(self.creepages, threads=1)
        elapsed = (time.process_time() - start) * 1e6
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
    c_side = CBatch(os.path.join(args.build, "librailcontact.so"))
    c_side.batch()  # warm-up
    # Interleaved: each repeat runs the C/C++ side, then the Python side, so that both see the
    # same load on a shared machine; the figures are the medians over the repeats.
    runs = []
    for _ in range(args.repeats):
        cxx, command, context = run_benchmarks(binary, args.min_time)
        py_single = python.single()
        c_batch = c_side.batch()
        py_batch = python.batch()
        runs.append((cxx, py_single, py_batch, c_batch))
    np.testing.assert_array_equal(c_side.forces, python.solver.batch(python.creepages, threads=1))
    cpp = statistics.median(r[0]["BM_CppNhFastSimForces"] for r in runs)
    c_api = statistics.median(r[0]["BM_CApiSolve"] for r in runs)
    bench_batch = statistics.median(r[0]["BM_CApiBatch/1/real_time"] for r in runs)
    py_single = statistics.median(r[1] for r in runs)
    py_batch = statistics.median(r[2] for r in runs)
    c_batch = statistics.median(r[3] for r in runs)
    calls = python.calls
    single_extra = statistics.median(r[1] - r[0]["BM_CppNhFastSimForces"] for r in runs)
    batch_outside = statistics.median((r[2] - r[3]) / r[2] for r in runs)
    load = os.getloadavg()
    figures = {
        "cpp_nh_fastsim_forces_us": cpp,
        "c_api_solve_us": c_api,
        "python_solve_us": py_single,
        "python_minus_cpp_us": single_extra,
        "python_minus_c_api_us": py_single - c_api,
        "single_target_us": SINGLE_TARGET_US,
        "c_api_batch_us": c_batch,
        "c_api_batch_benchmark_us": bench_batch,
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
    print(f"  C API rc_batch_creep_forces    {c_batch / 1e3:9.2f} ms  ({c_batch / BATCH_STATES:.2f} us per state; "
          f"the same in the benchmark binary {bench_batch / 1e3:.2f} ms)")
    print(f"  Python Solver.batch            {py_batch / 1e3:9.2f} ms  ({py_batch / BATCH_STATES:.2f} us per state)")
    print(f"  outside the solver: {100 * batch_outside:.2f} % of the Python call "
          f"(target at most {100 * BATCH_TARGET:g} %: {'met' if batch_outside <= BATCH_TARGET else 'NOT met'})")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(figures, f, indent=1)
    return 0 if single_extra <= SINGLE_TARGET_US and batch_outside <= BATCH_TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
