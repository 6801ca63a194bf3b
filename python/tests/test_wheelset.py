"""Tests of railcontact.Wheelset (docs/PYTHON.md "Wheelset"), run by ctest python.pytest: the same
numbers as the C API called through ctypes, the mirror symmetry of the two wheels, the batch
against the loop, the exceptions; and the single patch with the approach given. Coarse elements
(0.5 mm) keep them fast.
"""
import ctypes
import math
import os
import threading
import time

import numpy as np
import pytest

import railcontact

COARSE = 0.5e-3


@pytest.fixture(scope="module")
def wheelset():
    return railcontact.Wheelset(element_size=COARSE, warm_start=False)


def test_default_wheelset_carries_the_loads(wheelset):
    r = wheelset.evaluate(y=3e-3, yaw=1e-3)
    assert len(r.wheels) == 2 and r.right.side == "right" and r.left.side == "left"
    for wheel in r.wheels:
        assert wheel.force_track_N.shape == (3,)
        assert wheel.force_track_N[2] == pytest.approx(98.1e3, rel=1e-3)
        assert len(wheel.patches) >= 1
        p = wheel.patches[0]
        assert p.side == wheel.side
        assert p.reference_point_track_m.shape == (3,)
        assert p.normal_force_N > 0 and p.area_m2 > 0 and p.max_pressure_Pa > 0
        assert p.F1_N == p.solvers["nh-fastsim"].F1_N
        assert np.array_equal(p.force_track_N, p.solvers["nh-fastsim"].force_track_N)
        assert math.isfinite(p.xi) and math.isfinite(p.phi_per_m)
    assert np.allclose(r.force_track_N, r.right.force_track_N + r.left.force_track_N, rtol=0, atol=1e-6)
    assert wheelset.track["nominal_axle_height_m"] > 0.4


# The C structs as ctypes sees them (railcontact/railcontact.h). A field missing here lets the
# library write past the Python object (it once corrupted the heap: a later garbage collection
# crashed); _guarded catches that as a failed assertion.
class _Options(ctypes.Structure):
    _fields_ = ([(n, ctypes.c_double) for n in ("E", "nu", "mu", "element", "right", "left")]
                + [(n, ctypes.c_int) for n in ("mode", "balance", "tangential", "lift", "warm", "slip", "count")]
                + [("solvers", ctypes.c_int * 4)]
                + [(n, ctypes.c_int) for n in ("balance_solver", "reference_weighting", "contact_surface")])


class _State(ctypes.Structure):
    _fields_ = ([(n, ctypes.c_double) for n in ("y", "z", "roll", "yaw", "V", "vy", "vz", "roll_rate",
                                                  "yaw_rate", "omega", "xi0")]
                + [("rotation", ctypes.c_int), ("reserved", ctypes.c_int)])


class _Result(ctypes.Structure):
    _fields_ = [("force", ctypes.c_double * 3), ("wheel_force", (ctypes.c_double * 3) * 2),
                ("wheel_z", ctypes.c_double * 2), ("z", ctypes.c_double), ("roll", ctypes.c_double),
                ("patch_count", ctypes.c_int * 2), ("load_iterations", ctypes.c_int * 2)]


_GUARD = 64  # bytes of a known pattern after each struct


def _guarded(struct):
    """An instance of `struct` followed by _GUARD bytes of 0xA5, and a check that they are intact."""
    buffer = ctypes.create_string_buffer(b"\xa5" * (ctypes.sizeof(struct) + _GUARD))
    value = struct.from_buffer(buffer)

    def intact():
        return buffer.raw[ctypes.sizeof(struct):] == b"\xa5" * _GUARD + b"\x00"
    return value, intact


def test_same_numbers_as_the_c_api(c_library):
    """The shared library's rc_wheelset, called through ctypes, against the module."""
    lib = c_library
    handle = ctypes.c_void_p()
    assert lib.rc_wheelset_create(ctypes.byref(handle)) == 0
    lib.rc_wheelset_set_default_track.argtypes = [ctypes.c_void_p]
    assert lib.rc_wheelset_set_default_track(handle) == 0
    options, options_intact = _guarded(_Options)
    lib.rc_wheelset_options_default(ctypes.byref(options))
    assert options_intact(), "rc_wheelset_options has fields that _Options lacks"
    options.element = COARSE
    options.mu = 0.25
    lib.rc_wheelset_set_options.argtypes = [ctypes.c_void_p, ctypes.POINTER(_Options)]
    assert lib.rc_wheelset_set_options(handle, ctypes.byref(options)) == 0
    state, state_intact = _guarded(_State)
    lib.rc_wheelset_state_default(ctypes.byref(state))
    assert state_intact(), "rc_wheelset_state has fields that _State lacks"
    state.y, state.yaw, state.vy = -4e-3, 2e-3, 0.05
    result, result_intact = _guarded(_Result)
    lib.rc_wheelset_evaluate.argtypes = [ctypes.c_void_p, ctypes.POINTER(_State), ctypes.POINTER(_Result)]
    assert lib.rc_wheelset_evaluate(handle, ctypes.byref(state), ctypes.byref(result)) == 0
    assert result_intact(), "rc_wheelset_result has fields that _Result lacks"
    lib.rc_wheelset_destroy.argtypes = [ctypes.c_void_p]
    lib.rc_wheelset_destroy(handle)

    r = railcontact.Wheelset(element_size=COARSE, mu=0.25).evaluate(y=-4e-3, yaw=2e-3, lateral_velocity=0.05)
    assert list(r.force_track_N) == list(result.force)
    for w in range(2):
        assert list(r.wheels[w].force_track_N) == list(result.wheel_force[w])
        assert len(r.wheels[w].patches) == result.patch_count[w]
    assert r.vertical_displacement_m == result.z


def test_mirror_symmetry(wheelset):
    """Forces at y are the mirror image of those at -y: per wheel, Fx and Fz equal, Fy opposite."""
    for y in (2.5e-3, -6.5e-3):
        a = wheelset.evaluate(y=y, yaw=1e-3, lateral_velocity=0.01)
        b = wheelset.evaluate(y=-y, yaw=-1e-3, lateral_velocity=-0.01)
        for w in range(2):
            f, m = a.wheels[w].force_track_N, b.wheels[1 - w].force_track_N
            scale = f[2]
            assert f[0] == pytest.approx(m[0], abs=1e-8 * scale)
            assert f[1] == pytest.approx(-m[1], abs=1e-8 * scale)
            assert f[2] == pytest.approx(m[2], abs=1e-8 * scale)
            assert len(a.wheels[w].patches) == len(b.wheels[1 - w].patches)


def test_batch_equals_the_loop_and_threads(wheelset):
    states = np.array([[y, 0.0, 0.0, 0.5e-3] for y in (-6e-3, -2e-3, 0.0, 4e-3)])
    loop = [wheelset.evaluate(*row) for row in states]
    batch = wheelset.batch(states, threads=2)
    assert len(batch) == len(loop)
    for a, b in zip(batch, loop):
        assert np.array_equal(a.force_track_N, b.force_track_N)
        for w in range(2):
            assert len(a.wheels[w].patches) == len(b.wheels[w].patches)
            for p, q in zip(a.wheels[w].patches, b.wheels[w].patches):
                assert (p.F1_N, p.F2_N, p.M3_Nm, p.normal_force_N) == (q.F1_N, q.F2_N, q.M3_Nm, q.normal_force_N)
                assert np.array_equal(p.reference_point_track_m, q.reference_point_track_m)
    # A failing state: raised, or None with errors="none".
    bad = states[:2].copy()
    bad[0, 0] = np.nan
    with pytest.raises(railcontact.InvalidInputError, match="state 0: rc_wheelset_state.y_m = nan"):
        wheelset.batch(bad, threads=1)
    out = wheelset.batch(bad, threads=1, errors="none")
    assert out[0] is None
    assert np.array_equal(out[1].force_track_N, loop[1].force_track_N)


def test_reset_warm_start_gives_a_fresh_wheelsets_numbers():
    options = dict(element_size=COARSE, loads=None, allow_wheel_lift=True)
    used = railcontact.Wheelset(**options)
    used.evaluate(y=0.0, z=-0.02e-3)
    used.evaluate(y=0.3e-3, z=-0.02e-3, yaw=1e-3)
    used.reset_warm_start()
    a = used.evaluate(y=0.3e-3, z=-0.02e-3, yaw=1e-3)
    b = railcontact.Wheelset(**options).evaluate(y=0.3e-3, z=-0.02e-3, yaw=1e-3)
    assert np.array_equal(a.force_track_N, b.force_track_N)
    for w in range(2):
        assert len(a.wheels[w].patches) == len(b.wheels[w].patches) > 0
        for p, q in zip(a.wheels[w].patches, b.wheels[w].patches):
            assert (p.F1_N, p.F2_N, p.M3_Nm, p.normal_force_N, p.normal_iterations) == \
                (q.F1_N, q.F2_N, q.M3_Nm, q.normal_force_N, q.normal_iterations)


def test_stage_times_add_up_to_the_evaluations_and_change_no_number():
    timed, plain = railcontact.Wheelset(element_size=COARSE), railcontact.Wheelset(element_size=COARSE)
    assert timed.stage_times()["evaluations"] == 0
    timed.time_stages(True)
    wall = 0.0
    for k in range(3):
        start = time.perf_counter()
        a = timed.evaluate(y=-3e-3 + 1e-6 * k)
        wall += time.perf_counter() - start
        b = plain.evaluate(y=-3e-3 + 1e-6 * k)
        assert np.array_equal(a.force_track_N, b.force_track_N)
    t = timed.stage_times()
    assert t["evaluations"] == 3
    stages = ("search_s", "area_s", "normal_s", "height_s", "kinematics_s", "tangential_s", "assembly_s")
    assert all(t[name] > 0.0 for name in stages)  # by load: every stage runs
    assert t["total_s"] == pytest.approx(sum(t[name] for name in stages))
    assert 0.8 * wall <= t["total_s"] <= wall  # the rest of the time is Python's and the binding's
    timed.time_stages(False)
    assert timed.stage_times()["evaluations"] == 0 and timed.stage_times()["total_s"] == 0.0
    assert plain.stage_times()["evaluations"] == 0


def test_two_wheelsets_on_two_threads_equal_serial():
    ys = (-3e-3, 1e-3)
    serial = [railcontact.Wheelset(element_size=COARSE).evaluate(y=y).force_track_N for y in ys]
    out = [None, None]

    def run(k):
        out[k] = railcontact.Wheelset(element_size=COARSE).evaluate(y=ys[k]).force_track_N

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(out, serial):
        assert np.array_equal(a, b)


def test_slip_direction_on_the_flange():
    """The wheelset's default is the elastic-slip direction; "rigid-slip" leaves out Coulomb's law
    along the elastic slip where a patch slips everywhere, "flexibility-weighted" also the turn to
    the rigid slip, and "radial" gives Eq 8: on the flange (y = -7 mm, deep slip with spin) the
    right wheel's force differs by more than 100 N between each two."""
    default = railcontact.Wheelset(element_size=COARSE, warm_start=False)
    elastic = railcontact.Wheelset(element_size=COARSE, warm_start=False, slip_direction="elastic-slip")
    rigid = railcontact.Wheelset(element_size=COARSE, warm_start=False, slip_direction="rigid-slip")
    weighted = railcontact.Wheelset(element_size=COARSE, warm_start=False, slip_direction="flexibility-weighted")
    radial = railcontact.Wheelset(element_size=COARSE, warm_start=False, slip_direction="radial")
    d = default.evaluate(y=-7e-3).right.force_track_N
    e = elastic.evaluate(y=-7e-3).right.force_track_N
    r = rigid.evaluate(y=-7e-3).right.force_track_N
    a = weighted.evaluate(y=-7e-3).right.force_track_N
    b = radial.evaluate(y=-7e-3).right.force_track_N
    assert list(d) == list(e)
    assert math.hypot(e[0] - r[0], e[1] - r[1]) > 100.0
    assert math.hypot(a[0] - b[0], a[1] - b[1]) > 100.0
    assert math.hypot(r[0] - a[0], r[1] - a[1]) > 100.0
    with pytest.raises(railcontact.InvalidInputError, match="slip_direction = 'sideways' is not one of radial"):
        railcontact.Wheelset(element_size=COARSE, slip_direction="sideways")


def test_contact_surface():
    """contact_surface="conformal" and "auto" solve the flange patch at y = -6.5 mm on the curved
    surface (conformal weight 1, its pressure resultant off the contact normal, a lateral force
    that differs from the planar one by more than 10 % of mu Fz); on the tread at y = 0 "auto"
    keeps the left wheel's planar patch within the switch's band or below it; a wrong name is
    refused, naming the option."""
    planar = railcontact.Wheelset(element_size=COARSE, warm_start=False)
    conformal = railcontact.Wheelset(element_size=COARSE, warm_start=False, contact_surface="conformal")
    automatic = railcontact.Wheelset(element_size=COARSE, warm_start=False, contact_surface="auto")
    assert automatic.options["contact_surface"] == railcontact.CONTACT_SURFACES["auto"]
    p, c, a = (w.evaluate(y=-6.5e-3).right for w in (planar, conformal, automatic))
    assert p.patches[0].conformal_weight == 0.0
    assert c.patches[0].conformal_weight == 1.0 and a.patches[0].conformal_weight == 1.0
    assert a.patches[0].contact_angle_spread_rad > 0.01
    assert np.allclose(a.force_track_N, c.force_track_N, rtol=1e-9, atol=1e-6)
    assert abs(c.force_track_N[1] - p.force_track_N[1]) > 0.1 * 0.3 * 98100.0
    n = c.patches[0].pressure_force_track_N
    assert abs(np.dot(n, c.patches[0].x3_axis) / np.linalg.norm(n) - 1.0) > 1e-5
    assert automatic.evaluate(y=-3e-3).left.patches[0].conformal_weight == 0.0
    with pytest.raises(railcontact.InvalidInputError, match="contact_surface = 'curved' is not one of planar"):
        railcontact.Wheelset(element_size=COARSE, contact_surface="curved")


def test_a_table_on_the_automatic_surface():
    """A table built with contact_surface="auto" keeps the flange patch on the conformal surface: at
    its nodes (y = -6.5 mm) its lookup is the wheelset on the fly to 1e-6 of the load, where a planar
    table misses the lateral force by more than 10 % of mu Fz; a planar wheelset refuses the table,
    naming the contact surface."""
    on_the_fly = {}
    for surface in ("auto", "planar"):
        w = railcontact.Wheelset(element_size=COARSE, loads=(98.1e3, 98.1e3), contact_surface="auto",
                                 tangential_in_balance=False)
        on_the_fly[surface] = w.evaluate(-6.5e-3, speed=25.0, lateral_velocity=0.01)
        tabled = railcontact.Wheelset(element_size=COARSE, loads=(98.1e3, 98.1e3), contact_surface=surface,
                                      tangential_in_balance=False)
        tabled.build_table((-6.6e-3, -6.5e-3), (0.0,), (98.1e3,))
        table = tabled.evaluate_table(-6.5e-3, speed=25.0, lateral_velocity=0.01)
        if surface == "auto":
            assert table.right.patches[0].conformal_weight == 1.0
            assert np.allclose(table.right.force_track_N, on_the_fly["auto"].right.force_track_N, atol=1e-6 * 98.1e3)
            path = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"railcontact_pytest_auto_table_{os.getpid()}.json")
            tabled.save_table(path)
            try:
                with pytest.raises(railcontact.InvalidInputError, match="contact-surface planar .* differs from the "
                                                                        "table's auto"):
                    railcontact.Wheelset(element_size=COARSE).load_table(path)
            finally:
                os.remove(path)
        else:
            assert abs(table.right.force_track_N[1] - on_the_fly["auto"].right.force_track_N[1]) > 0.1 * 0.3 * 98.1e3


def test_a_table_refined_where_the_flange_comes_in():
    """refine_lateral_force_fraction adds y nodes where the flange contact comes in (the progress
    callback's total grows beyond the grid's 7 nodes); a fraction outside [0, 1] is refused, naming
    the argument."""
    w = railcontact.Wheelset(element_size=COARSE)
    calls = []
    w.build_table(np.linspace(-7.1e-3, -6.5e-3, 7), (0.0,), (98.1e3,), progress=lambda done, total: calls.append(total),
                  refine_lateral_force_fraction=0.01)
    assert calls[0] == 7 and calls[-1] > 7
    with pytest.raises(railcontact.InvalidInputError, match="refine_lateral_force_fraction.*must lie in \\[0, 1\\]"):
        w.build_table((0.0, 1e-3), (0.0,), (98.1e3,), refine_lateral_force_fraction=2.0)


def test_balance_solver_reference_weighting_and_radius_datum():
    """balance_solver moves the wheel heights (the exact solver's vertical force components carry
    the load); reference_weighting="depth" moves the contact angle of the two-lobe patch at
    y = -5.5 mm by more than 3 mrad; nominal_radius_at="taping-line" with a taping line 1 mm off the
    profile origin moves xi. Wrong names are refused, naming the option."""
    solvers = ("nh-fastsim", "exact")
    first = railcontact.Wheelset(element_size=COARSE, warm_start=False, solvers=solvers)
    by_exact = railcontact.Wheelset(element_size=COARSE, warm_start=False, solvers=solvers, balance_solver="exact")
    assert by_exact.options["balance_solver"] == railcontact.METHODS["exact"]
    a, b = first.evaluate(y=-6e-3), by_exact.evaluate(y=-6e-3)
    assert abs(a.right.vertical_displacement_m - b.right.vertical_displacement_m) > 1e-9
    with pytest.raises(railcontact.InvalidInputError, match="balance_solver = 'fastsim' is not one of solvers"):
        railcontact.Wheelset(element_size=COARSE, solvers=solvers, balance_solver="fastsim")

    squared = railcontact.Wheelset(element_size=COARSE, warm_start=False)
    depth = railcontact.Wheelset(element_size=COARSE, warm_start=False, reference_weighting="depth")
    gamma_squared = squared.evaluate(y=-5.5e-3).right.patches[0].contact_angle_rad
    gamma_depth = depth.evaluate(y=-5.5e-3).right.patches[0].contact_angle_rad
    assert abs(gamma_depth - gamma_squared) > 3e-3
    with pytest.raises(railcontact.InvalidInputError, match="reference_weighting = 'mean' is not one of squared-gap"):
        railcontact.Wheelset(element_size=COARSE, reference_weighting="mean")

    profiles = os.path.join(os.path.dirname(__file__), "..", "..", "data", "profiles")
    wheel = os.path.join(profiles, "MBench_S1002_v3.prw")
    rail = os.path.join(profiles, "MBench_UIC60_v3.prr")
    origin = railcontact.Wheelset(wheel, rail, taping_line_distance=0.071, element_size=COARSE, warm_start=False)
    taping = railcontact.Wheelset(wheel, rail, taping_line_distance=0.071, nominal_radius_at="taping-line",
                                  element_size=COARSE, warm_start=False)
    assert origin.track["nominal_radius_at"] == "profile-origin"
    assert taping.track["nominal_radius_at"] == "taping-line"
    xi_origin = origin.evaluate().right.patches[0].xi
    xi_taping = taping.evaluate().right.patches[0].xi
    assert abs(xi_taping - xi_origin) > 1e-5
    with pytest.raises(railcontact.InvalidInputError, match="nominal_radius_at = 'flange' is not one of profile-origin"):
        railcontact.Wheelset(wheel, rail, nominal_radius_at="flange")
    with pytest.raises(railcontact.InvalidInputError, match="nominal_radius_at: track dimensions need profile files"):
        railcontact.Wheelset(nominal_radius_at="taping-line")


def test_rail_cant_inclines_the_rail_profile():
    """rail_cant (rad) cants the rail profile as the set-up key track.rail_cant_rad does: on the upright
    UIC60 canted 1:40 the crown faces the track centre, the contact lies further to the field side
    and its angle is smaller than on the vertical rail; track["rail_cant_rad"] tells the cant, and a
    ratio's denominator is refused."""
    profiles = os.path.join(os.path.dirname(__file__), "..", "..", "data", "profiles")
    wheel = os.path.join(profiles, "MBench_S1002_v3.prw")
    upright = os.path.join(profiles, "UIC60_upright.prr")
    cant = math.atan(1.0 / 40.0)
    canted = railcontact.Wheelset(wheel, upright, rail_cant=cant, element_size=COARSE, warm_start=False)
    vertical = railcontact.Wheelset(wheel, upright, element_size=COARSE, warm_start=False)
    assert canted.track["rail_cant_rad"] == cant
    assert vertical.track["rail_cant_rad"] == 0.0
    a = canted.evaluate(y=-2e-3).right.patches[0]
    b = vertical.evaluate(y=-2e-3).right.patches[0]
    assert a.contact_angle_rad < b.contact_angle_rad - 5e-3  # the crown faces the centre: contact further out
    with pytest.raises(railcontact.InvalidInputError,
                       match=r"rail_cant: rc_track_parameters.rail_cant_rad = 40 rad must lie in \[-0.1, 0.1\] rad"):
        railcontact.Wheelset(wheel, upright, rail_cant=40)
    with pytest.raises(railcontact.InvalidInputError, match="rail_cant: track dimensions need profile files"):
        railcontact.Wheelset(rail_cant=cant)


def test_exceptions(wheelset):
    with pytest.raises(railcontact.InvalidInputError, match="y = nan"):
        wheelset.evaluate(y=float("nan"))
    with pytest.raises(ValueError, match=r"forward_speed_m_per_s = 0 m/s must lie in \(0, 200\] m/s"):
        wheelset.evaluate(speed=0.0)
    with pytest.raises(railcontact.RailcontactIOError, match="no-such-wheel.prw") as e:
        railcontact.Wheelset(wheel="/tmp/no-such-wheel.prw", rail="/tmp/no-such-rail.prr")
    assert isinstance(e.value, OSError)
    with pytest.raises(railcontact.InvalidInputError, match="solvers = 'fastest' is not one of"):
        railcontact.Wheelset(solvers=("fastest",))
    with pytest.raises(railcontact.InvalidInputError, match="mu = inf must be finite"):
        railcontact.Wheelset(mu=float("inf"))
    with pytest.raises(railcontact.InvalidInputError, match="give wheel= and rail="):
        railcontact.Wheelset(wheel="w.prw")
    with pytest.raises(railcontact.InvalidInputError, match="need profile files"):
        railcontact.Wheelset(gauge=1.5)
    # By position, lifted well above the rails: no contact (allowed with allow_wheel_lift).
    lifted = railcontact.Wheelset(element_size=COARSE, loads=None)
    with pytest.raises(railcontact.NoContactError, match="does not touch"):
        lifted.evaluate(z=1e-3)
    free = railcontact.Wheelset(element_size=COARSE, loads=None, allow_wheel_lift=True)
    r = free.evaluate(z=1e-3)
    assert r.wheels[0].patches == [] and r.force_track_N[2] == 0.0
    with pytest.raises(railcontact.InvalidInputError, match="shape"):
        wheelset.batch(np.zeros((2, 12)))


def test_single_patch_at_an_approach():
    solver = railcontact.Solver(elements=600)
    by_force = solver.set_hertz(0.6, 1.4, 8e4)
    by_approach = solver.set_hertz(0.6, 1.4, approach=by_force.approach_m)
    assert by_approach.normal_force_N == pytest.approx(8e4, rel=1e-9)
    with pytest.raises(railcontact.InvalidInputError, match="given its normal force"):
        solver.batch([[1e-3, 0, 0]])  # batch(patches=None) needs a patch given by its force
    n1, n2, dx = 40, 30, 0.5e-3
    x1 = (np.arange(n1) - 0.5 * (n1 - 1)) * dx
    x2 = (np.arange(n2) - 0.5 * (n2 - 1)) * dx
    h = 0.6 * x1[None, :] ** 2 + 1.4 * x2[:, None] ** 2 - 40e-6
    normal = solver.set_grid(h, dx, dx, approach=0.0)
    assert normal.normal_force_N > 1e3
    assert solver.set_grid(h, dx, dx, normal.normal_force_N).approach_m == pytest.approx(0.0, abs=1e-9)
    with pytest.raises(railcontact.NoContactError):
        solver.set_grid(h, dx, dx, approach=-1e-3)
    with pytest.raises(railcontact.InvalidInputError, match="give one of normal_force, approach"):
        solver.set_hertz(0.6, 1.4)


# ---- The wheelset table (docs/WHEELSET_TABLE.md) -------------------------------------------------

@pytest.fixture(scope="module")
def tabled(tmp_path_factory):
    w = railcontact.Wheelset(element_size=0.5e-3, loads=(95e3, 105e3))
    calls = []
    w.build_table(np.arange(-1e-3, 1.001e-3, 0.5e-3), (-2e-3, 0.0, 2e-3), (90e3, 110e3),
                  progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (30, 30)
    return w


def test_table_forces_are_the_table_evaluation(tabled):
    r = tabled.evaluate_table(0.3e-3, 1e-3, speed=30.0, lateral_velocity=0.02, yaw_rate=0.01)
    f = tabled.table_forces(0.3e-3, 1e-3, speed=30.0, lateral_velocity=0.02, yaw_rate=0.01)
    assert np.array_equal(f[:3], r.right.force_track_N) and np.array_equal(f[3:6], r.left.force_track_N)
    # Mz about the wheelset centre from the patches' reference points and forces.
    mz = sum(p.reference_point_track_m[0] * p.force_track_N[1] - (p.reference_point_track_m[1] - 0.3e-3) *
             p.force_track_N[0] for wheel in r.wheels for p in wheel.patches)
    assert f[6] == pytest.approx(mz, rel=1e-12, abs=1e-9)
    # The wheels carry the loads of the options (the frictionless balance: F3 X3 sums to the load).
    assert sum(p.normal_force_N * p.x3_axis[2] for p in r.right.patches) == pytest.approx(95e3, rel=2e-3)


def test_table_is_close_to_the_wheelset_on_the_fly(tabled):
    fly = railcontact.Wheelset(element_size=0.5e-3, loads=(100e3, 100e3), tangential_in_balance=False)
    on_the_fly = fly.evaluate(-0.25e-3, yaw=1e-3, speed=25.0, lateral_velocity=0.01)
    tabled_100 = railcontact.Wheelset(element_size=0.5e-3, loads=(100e3, 100e3))
    path = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"railcontact_pytest_table_{os.getpid()}.json")
    tabled.save_table(path)
    try:
        tabled_100.load_table(path)
    finally:
        os.remove(path)
    table = tabled_100.evaluate_table(-0.25e-3, 1e-3, speed=25.0, lateral_velocity=0.01)
    for a, b in zip(on_the_fly.wheels, table.wheels):
        assert np.allclose(a.force_track_N[:2], b.force_track_N[:2], atol=0.02 * 0.3 * 100e3)


def test_table_refuses_states_outside_and_cancels(tabled):
    with pytest.raises(railcontact.InvalidInputError, match="lies outside the table's range"):
        tabled.table_forces(1.5e-3, 0.0, speed=20.0)
    with pytest.raises(railcontact.InvalidInputError, match="yaw"):
        tabled.table_forces(0.0, 5e-3, speed=20.0)
    w = railcontact.Wheelset(element_size=0.5e-3)
    with pytest.raises(railcontact.CancelledError):
        w.build_table((0.0, 0.5e-3), (0.0,), (100e3,), progress=lambda done, total: False)
    with pytest.raises(railcontact.InvalidInputError, match="has no table"):
        w.table_forces(0.0, 0.0, speed=20.0)


def test_a_table_is_used_only_with_the_settings_it_was_built_for(tabled):
    # A wheelset of other material or element size refuses the table, naming the setting and both
    # values (the C API's rc_wheelset_table_load).
    path = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"railcontact_pytest_table_settings_{os.getpid()}.json")
    tabled.save_table(path)
    try:
        for options, message in (({"element_size": 0.2e-3}, "element-size 0.2 mm .* differs from the table's 0.5 mm"),
                                 ({"element_size": 0.5e-3, "youngs_modulus": 1e11},
                                  "material E = 1e\\+11 Pa, nu = 0.3 .* differs from the table's E = 2.1e\\+11 Pa"),
                                 ({"element_size": 0.5e-3, "slip_direction": "radial"},
                                  "slip-direction radial .* differs from the table's elastic-slip")):
            with pytest.raises(railcontact.InvalidInputError, match=message):
                railcontact.Wheelset(**options).load_table(path)
    finally:
        os.remove(path)


def test_free_rolling_balances_the_wheels_rotation(wheelset):
    # Free rolling: the angular velocity at which the wheels' tangential forces have no moment about
    # the axle; centred, each wheel's F1 vanishes with it (below 0.1 % of mu Fz). Pure rolling at r0
    # reports V / r0 and brakes the centred wheelset slightly (its contacts do not roll on r0).
    rolling = wheelset.evaluate(0.0)
    assert rolling.wheel_angular_velocity_rad_per_s == pytest.approx(20.0 / 0.46, rel=1e-12)
    free = wheelset.evaluate(0.0, free_rolling=True)
    omega = free.wheel_angular_velocity_rad_per_s
    assert abs(omega - 20.0 / 0.46) > 5e-6 * omega  # 8.6e-6 of it
    for wheel in free.wheels:
        assert abs(wheel.force_track_N[0]) < 1e-3 * 0.3 * 98.1e3
    given = wheelset.evaluate(0.0, wheel_angular_velocity=omega)
    assert given.right.force_track_N[0] == pytest.approx(free.right.force_track_N[0], abs=1e-6 * 0.3 * 98.1e3)
    with pytest.raises(ValueError, match="free_rolling=True solves the wheels' angular velocity; leave out "
                                         "wheel_angular_velocity"):
        wheelset.evaluate(0.0, free_rolling=True, wheel_angular_velocity=43.0)
    with pytest.raises(TypeError, match="free_rolling"):
        wheelset.evaluate(0.0, free_rolling=1)
    # A batch's infinite angular velocity is an error, not free rolling.
    results = wheelset.batch(np.array([[0.0, 0, 0, 0, 20, 0, 0, 0, 0, np.inf, 0]]), errors="none")
    assert results == [None]
