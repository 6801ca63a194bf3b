"""Tests of the Python module railcontact (docs/PYTHON.md), run by ctest python.pytest:
/usr/bin/python3 -m pytest python/tests with PYTHONPATH=BUILD/python.

References are independent of the module: Kalker's table (data/kalker_creepage_coefficients.csv),
Coulomb saturation, symmetry, and the C API called directly through ctypes (the shared library
next to the package, or RAILCONTACT_LIBRARY; conftest.py) for the same numbers.
"""
import csv
import ctypes
import math
import os
import threading

import numpy as np
import pytest

import railcontact

SOURCE = os.environ.get("RAILCONTACT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
E, NU, F3, MU = 2.1e11, 0.25, 80e3, 0.3
G = E / (2 * (1 + NU))


def kalker_row(a_over_b, nu):
    with open(os.path.join(SOURCE, "data", "kalker_creepage_coefficients.csv")) as f:
        for row in csv.DictReader(f):
            if float(row["a_over_b"]) == a_over_b and float(row["nu"]) == nu:
                return {k: float(v) for k, v in row.items()}
    raise KeyError((a_over_b, nu))


@pytest.fixture(scope="module")
def circle():
    solver = railcontact.Solver("nh-fastsim", mu=MU, poisson_ratio=NU, elements=2800)
    solver.set_ellipse(5e-3, 5e-3, F3)
    return solver


def test_version():
    major, minor, patch = (int(x) for x in railcontact.__version__.split("."))
    assert major >= 0 and minor >= 0 and patch >= 0
    assert railcontact.abi_version >= 1


def test_linear_theory_of_kalker(circle):
    k = kalker_row(1.0, NU)
    c2 = 5e-3 * 5e-3
    r = circle.solve(xi=1e-6)
    assert r.F1_N == pytest.approx(-G * c2 * k["C11"] * 1e-6, rel=0.03)
    assert r.adhesion_fraction == 1.0
    r = circle.solve(eta=1e-6)
    assert r.F2_N == pytest.approx(-G * c2 * k["C22"] * 1e-6, rel=0.03)
    r = circle.solve(phi=1e-4)
    assert r.F2_N == pytest.approx(-G * c2 ** 1.5 * k["C23"] * 1e-4, rel=0.05)


def test_saturation_and_symmetry(circle):
    assert circle.solve(xi=0.05).F1_N == pytest.approx(-MU * F3, rel=1e-3)
    assert circle.solve(xi=-0.05).F1_N == pytest.approx(MU * F3, rel=1e-3)
    plus, minus = circle.solve(eta=2e-3), circle.solve(eta=-2e-3)
    assert plus.F2_N < 0
    assert minus.F2_N == pytest.approx(-plus.F2_N, rel=1e-9)


def test_every_method_saturates_and_agrees_at_small_creepage():
    results = {}
    for method in railcontact.METHODS:
        solver = railcontact.Solver(method, mu=MU, elements=500)
        solver.set_ellipse(6e-3, 4e-3, F3)
        assert solver.method == method
        results[method] = solver.solve(xi=1e-3, eta=5e-4).F1_N
        assert solver.solve(xi=0.1).F1_N == pytest.approx(-MU * F3, rel=2e-2)
    exact = results["exact"]
    for method, F1 in results.items():
        assert F1 == pytest.approx(exact, rel=0.15), method


def test_result_normal_and_tractions(circle):
    r = circle.solve(xi=1e-3, eta=5e-4, phi=0.3, tractions=True)
    n = r.normal
    assert isinstance(r, railcontact.Result)
    assert n.area_m2 == pytest.approx(math.pi * 25e-6, rel=0.03)
    assert n.normal_force_N == pytest.approx(F3, rel=1e-9)
    t = r.tractions
    assert t.p1_Pa.shape == (n.n2, n.n1) == t.slip.shape
    assert n.x1_m.shape == (n.n1,) and n.x2_m.shape == (n.n2,)
    dA = n.dx1_m * n.dx2_m
    assert t.p1_Pa.sum() * dA == pytest.approx(r.F1_N, rel=1e-9)
    assert t.p2_Pa.sum() * dA == pytest.approx(r.F2_N, rel=1e-9)
    assert t.p3_Pa.sum() * dA == pytest.approx(F3, rel=1e-9)
    assert int((t.p3_Pa > 0).sum()) == n.elements_in_contact
    # The pressure peak is near the centre (x = 0) on an ellipse.
    i2, i1 = np.unravel_index(np.argmax(t.p3_Pa), t.p3_Pa.shape)
    assert abs(n.x1_m[i1]) < 3 * n.dx1_m and abs(n.x2_m[i2]) < 3 * n.dx2_m


def test_result_normal_follows_the_patch():
    # Solver.normal is made once per patch: a new patch, or settings that discard it, renew it.
    s = railcontact.Solver("nh-fastsim", elements=500)
    first = s.set_ellipse(a=5e-3, b=5e-3, normal_force=F3)
    assert s.solve(xi=1e-3).normal is first
    second = s.set_ellipse(a=6e-3, b=4e-3, normal_force=F3)
    assert s.solve(xi=1e-3).normal == second != first
    s.configure(elements=1500)  # a new mesh discards the patch
    with pytest.raises(railcontact.InvalidInputError, match="no contact patch is set"):
        s.solve(xi=1e-3)
    third = s.set_ellipse(a=6e-3, b=4e-3, normal_force=F3)
    assert third.elements_in_contact > 2 * second.elements_in_contact
    assert s.solve(xi=1e-3).normal == third
    s.configure(mu=0.2)  # friction alone keeps the patch and its normal result
    assert s.solve(xi=1e-3).normal == third


def test_jacobian(circle):
    r = circle.solve(xi=1e-5, jacobian=True)
    J = r.jacobian
    assert J.shape == (3, 3)
    assert J[0, 0] == pytest.approx(r.F1_N / 1e-5, rel=1e-6)  # linear: F1 = J11 xi
    assert J[1, 1] < 0 and J[0, 0] < 0


def test_hertz_and_grid_geometries():
    A, B = 5.0, 8.0
    solver = railcontact.Solver(elements=800)
    hz = solver.set_hertz(A, B, F3)
    assert hz.a_m > hz.b_m  # the longer axis along the smaller curvature
    n1, n2 = 40, 32
    dx1, dx2 = 3 * hz.a_m / n1, 3 * hz.b_m / n2
    x1 = (np.arange(n1) - 0.5 * (n1 - 1)) * dx1
    x2 = (np.arange(n2) - 0.5 * (n2 - 1)) * dx2
    h = A * x1[np.newaxis, :] ** 2 + B * x2[:, np.newaxis] ** 2  # shape (n2, n1)
    grid = solver.set_grid(h, dx1, dx2, F3)
    assert grid.area_m2 == pytest.approx(math.pi * hz.a_m * hz.b_m, rel=0.05)
    assert grid.approach_m == pytest.approx(hz.approach_m, rel=0.02)
    assert grid.max_pressure_Pa == pytest.approx(hz.max_pressure_Pa, rel=0.05)


def test_errors_by_kind(circle, tmp_path):
    with pytest.raises(railcontact.InvalidInputError, match="a = nan"):
        railcontact.Solver().set_ellipse(float("nan"), 4e-3, F3)
    with pytest.raises(ValueError):  # InvalidInputError is a ValueError
        circle.solve(xi=float("inf"))
    with pytest.raises(railcontact.InvalidInputError, match="friction_coefficient"):
        railcontact.Solver(mu=-1)
    with pytest.raises(railcontact.InvalidInputError, match="method = 'fastest' is not one of"):
        railcontact.Solver("fastest")
    with pytest.raises(railcontact.InvalidInputError, match="no contact patch"):
        railcontact.Solver().solve(xi=1e-3)
    with pytest.raises(railcontact.RailcontactIOError) as error:
        railcontact.FlexibilityTable.load(tmp_path / "missing.json")
    assert isinstance(error.value, OSError)
    # Two bumps: two patches.
    n1, n2, dx = 40, 20, 1e-3
    x1 = (np.arange(n1) - 0.5 * (n1 - 1)) * dx
    x2 = (np.arange(n2) - 0.5 * (n2 - 1)) * dx
    h = 5 * (np.abs(x1[np.newaxis, :]) - 10e-3) ** 2 + 5 * x2[:, np.newaxis] ** 2
    with pytest.raises(railcontact.SeveralPatchesError):
        railcontact.Solver().set_grid(h, dx, dx, F3)
    assert issubclass(railcontact.NotConvergedError, railcontact.RailcontactError)
    # The solver still works after errors.
    assert circle.solve(xi=0.05).F1_N == pytest.approx(-MU * F3, rel=1e-3)


def test_batch_equals_the_loop(circle):
    rng = np.random.default_rng(7)
    creepages = np.column_stack([rng.uniform(-3e-3, 3e-3, 40), rng.uniform(-3e-3, 3e-3, 40),
                                 rng.uniform(-1, 1, 40)])
    loop = np.array([[r.F1_N, r.F2_N, r.M3_Nm, r.adhesion_fraction]
                     for r in (circle.solve(*c) for c in creepages)])
    for threads in (1, 3):
        batch = circle.batch(creepages, threads=threads)
        assert batch.shape == (40, 4)
        np.testing.assert_array_equal(batch, loop)


def test_batch_of_patches_and_failed_states():
    solver = railcontact.Solver("fastsim", elements=400)
    patches = np.array([[6e-3, 4e-3, F3], [4e-3, 6e-3, F3], [5e-3, 5e-3, 5e4]])
    creepages = np.array([[1e-3, 0, 0], [0, 1e-3, 0], [np.nan, 0, 0]])
    with pytest.raises(railcontact.InvalidInputError, match="state 2"):
        solver.batch(creepages, patches=patches)
    forces = solver.batch(creepages, patches=patches, errors="nan", threads=2)
    assert np.isnan(forces[2]).all() and np.isfinite(forces[:2]).all()
    solver.set_ellipse(*patches[1])
    assert forces[1, 1] == solver.solve(0, 1e-3, 0).F2_N
    forces, J = solver.batch(creepages[:2], patches=patches[:2], jacobian=True)
    assert J.shape == (2, 3, 3) and J[0, 0, 0] < 0


def test_the_c_api_gives_the_same_numbers(c_library):
    """The shared library's C API, called through ctypes, against the Python module."""
    lib = c_library
    assert lib.rc_version_string.restype is not None
    lib.rc_version_string.restype = ctypes.c_char_p
    assert lib.rc_version_string().decode() == railcontact.__version__

    class Creepage(ctypes.Structure):
        _fields_ = [("xi", ctypes.c_double), ("eta", ctypes.c_double), ("phi", ctypes.c_double)]

    class Forces(ctypes.Structure):
        _fields_ = [(name, ctypes.c_double) for name in ("F1", "F2", "M3", "adhesion")]

    handle = ctypes.c_void_p()
    assert lib.rc_solver_create(ctypes.byref(handle)) == 0
    lib.rc_solver_set_ellipse.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_double]
    assert lib.rc_solver_set_ellipse(handle, 6e-3, 4e-3, F3) == 0
    forces = Forces()
    lib.rc_solver_solve.argtypes = [ctypes.c_void_p, ctypes.POINTER(Creepage), ctypes.POINTER(Forces)]
    assert lib.rc_solver_solve(handle, Creepage(1e-3, -5e-4, 0.4), ctypes.byref(forces)) == 0
    lib.rc_solver_destroy.argtypes = [ctypes.c_void_p]
    lib.rc_solver_destroy(handle)
    solver = railcontact.Solver()  # the defaults of rc_settings_default
    solver.set_ellipse(6e-3, 4e-3, F3)
    r = solver.solve(1e-3, -5e-4, 0.4)
    assert (r.F1_N, r.F2_N, r.M3_Nm) == (forces.F1, forces.F2, forces.M3)


def test_slip_direction():
    """slip_direction reaches nH-FastSim: radial (Eq 8) by default; flexibility-weighted turns the
    slipping traction in deep slip with spin; anything else is refused, naming the setting."""
    radial = railcontact.Solver(elements=600)
    weighted = railcontact.Solver(elements=600, slip_direction="flexibility-weighted")
    assert radial.settings["slip_direction"] == railcontact.SLIP_DIRECTIONS["radial"] == 0
    assert weighted.settings["slip_direction"] == railcontact.SLIP_DIRECTIONS["flexibility-weighted"] == 1
    for solver in (radial, weighted):
        solver.set_ellipse(6e-3, 4e-3, F3)
    a, b = radial.solve(3e-3, -2e-3, 2.0), weighted.solve(3e-3, -2e-3, 2.0)
    assert abs(a.F1_N - b.F1_N) > 1e-3 * MU * F3
    small = radial.solve(1e-6)
    # No slip: the same tractions, but the radial and the weighted limiting are different
    # instantiations of the march, which the compiler may vectorise and fuse (FMA) differently on
    # another CPU: within 1e-12 of mu F3 (tests/different_paths.hpp), not to the last bit.
    assert small.adhesion_fraction == 1.0
    assert small.F1_N == pytest.approx(weighted.solve(1e-6).F1_N, rel=0, abs=1e-12 * MU * F3)
    with pytest.raises(railcontact.InvalidInputError, match="slip_direction = 'weighted' is not one of"):
        railcontact.Solver(slip_direction="weighted")


def test_solvers_on_threads_equal_serial():
    def run(index, out):
        solver = railcontact.Solver("exact", elements=300 + 100 * index)
        solver.set_ellipse(6e-3, 4e-3, F3)
        out[index] = solver.solve(1e-3, 5e-4, 0.3).F1_N
    serial, parallel = {}, {}
    for i in range(3):
        run(i, serial)
    threads = [threading.Thread(target=run, args=(i, parallel)) for i in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert parallel == serial


def test_flexibility_table(tmp_path):
    calls = []
    table = railcontact.FlexibilityTable.build([-1e-3, 0.0, 1e-3], [98100.0], elements=300,
                                               progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1][0] == calls[-1][1]
    assert table.info["y_count"] >= 3 and table.info["target_elements"] == 300
    path = tmp_path / "table.json"
    table.save(path)
    loaded = railcontact.FlexibilityTable.load(path)
    v, built = loaded.lookup(0.5e-3, 98100.0), table.lookup(0.5e-3, 98100.0)
    assert v.L1_m_per_Pa == pytest.approx(built.L1_m_per_Pa, rel=1e-12)
    assert v.f22_N == pytest.approx(built.f22_N, rel=1e-12)
    assert 0 < v.L1_m_per_Pa < 1e-6 and v.f11_N > 0 and v.normal_force_N > 98100.0
    solver = railcontact.Solver()
    n = solver.set_flextable_patch(loaded, 0.5e-3, 98100.0)
    assert n.contact_angle_rad > 0 and n.normal_force_N == pytest.approx(v.normal_force_N, rel=0.01)
    assert solver.solve(xi=0.1).F1_N == pytest.approx(-MU * n.normal_force_N, rel=1e-2)
    with pytest.raises(railcontact.InvalidInputError):
        loaded.lookup(5e-3, 98100.0)
    with pytest.raises(railcontact.CancelledError):
        railcontact.FlexibilityTable.build([0.0, 1e-3], [98100.0], elements=300, progress=lambda d, t: False)
