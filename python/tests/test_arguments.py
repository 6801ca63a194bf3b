"""The argument checks of every public call of the package railcontact (python/railcontact/_checks.py,
docs/PYTHON.md "Arguments").

The public calls are enumerated from railcontact.__all__: every function, constructor, method and
classmethod of a public class (the frozen result dataclasses and the exceptions take no input).
Each must have an entry in CALLS below that lists every one of its parameters with its kind, so
that a new public call, or a new parameter, without checks fails test_every_public_call_is_listed.
For every parameter the tests pass a wrong type (TypeError), a non-finite value and an
out-of-range value (ValueError), and expect the parameter's name in the message.
"""
import inspect

import numpy as np
import pytest

import railcontact

COARSE = 1.0e-3  # m: wheelset elements


# ---- The objects the calls are made on (built once) -----------------------------------------------

class Objects:
    _cache = {}

    @classmethod
    def get(cls, name):
        if name not in cls._cache:
            cls._cache[name] = getattr(cls, "_" + name)()
        return cls._cache[name]

    @staticmethod
    def _solver():
        s = railcontact.Solver(elements=300)
        s.set_ellipse(6e-3, 4e-3, 80e3)
        return s

    @staticmethod
    def _table():
        return railcontact.FlexibilityTable.build([-1e-3, 0.0, 1e-3], [80e3, 100e3], elements=300)

    @staticmethod
    def _wheelset():
        w = railcontact.Wheelset(element_size=COARSE, warm_start=False)
        w.build_table([-1e-3, 0.0, 1e-3], (0.0,), (98.1e3,))
        return w


def solver_call(method):
    return lambda: getattr(Objects.get("solver"), method)


def table_call(method):
    return lambda: getattr(Objects.get("table"), method)


def wheelset_call(method):
    return lambda: getattr(Objects.get("wheelset"), method)


# ---- The kinds of parameters ---------------------------------------------------------------------
# Each kind gives (value, exception) cases: wrong types, a non-finite value, an out-of-range value.

NAN, INF = float("nan"), float("inf")


def number(out_of_range=None, optional=False):
    """A real number; out_of_range None: every finite value is allowed (a displacement, a
    velocity, a creepage)."""
    cases = [("0.3", TypeError), (True, TypeError), (0.3 + 0j, TypeError), ([0.3], TypeError), (NAN, ValueError),
             (INF, ValueError)]
    if not optional:
        cases.append((None, TypeError))
    if out_of_range is not None:
        cases.append((out_of_range, ValueError))
    return cases


def integer(out_of_range):
    return [("3", TypeError), (True, TypeError), (2.5, TypeError), (None, TypeError), (NAN, ValueError),
            (out_of_range, ValueError)]


def flag():
    """True or False: no non-finite or out-of-range value beyond a wrong type."""
    return [(1, TypeError), ("yes", TypeError), (None, TypeError), (NAN, TypeError)]


def choice(optional=False):
    cases = [(3, TypeError), (b"exact", TypeError), ("no-such-name", ValueError), (NAN, TypeError)]
    if not optional:
        cases.append((None, TypeError))
    return cases


def path(optional=False):
    cases = [(3, TypeError), (3.5, TypeError), ("", ValueError), (NAN, TypeError)]
    if not optional:
        cases.append((None, TypeError))
    return cases


def callback():
    return [(3, TypeError), ("print", TypeError), (NAN, TypeError)]


def array(wrong_shape, nonfinite=None, out_of_range=None, optional=False):
    """An array; wrong_shape: a value of the right type and the wrong shape (a ValueError stating
    the shape); nonfinite: an array with NaN where NaN is refused."""
    cases = [("abc", TypeError), (np.array(wrong_shape) + 0j, TypeError), (np.array(wrong_shape) > 0, TypeError),
             (wrong_shape, ValueError)]
    if not optional:
        cases.append((None, TypeError))
    if nonfinite is not None:
        cases.append((nonfinite, ValueError))
    if out_of_range is not None:
        cases.append((out_of_range, ValueError))
    return cases


def grid(out_of_range):
    """A grid: one number or a 1-D list, increasing."""
    return [("abc", TypeError), (None, TypeError), ([1e-3 + 0j], TypeError), ([True], TypeError),
            ([[0.0, 1e-3]], ValueError), ([], ValueError), ([0.0, NAN], ValueError), (out_of_range, ValueError)]


def instance():
    return [(3, TypeError), (None, TypeError), ("table", TypeError)]


# The Solver's settings (constructor, configure, creep_forces): out-of-range values from the
# library's ranges (docs/C_API.md "Settings").
SETTINGS = {
    "mu": number(-0.1), "youngs_modulus": number(-1.0), "poisson_ratio": number(0.7), "elements": number(5),
    "elements_across": integer(1), "element_size": number(2.0), "bound_skew": number(2.0),
    "flexibility_coarsening": integer(-1), "slip_direction": choice(), "collocation_offset": number(5.0),
    "tolerance": number(-1.0), "max_newton_iterations": integer(0), "krylov_tolerance": number(-1.0),
    "max_krylov_iterations": integer(0), "regularisation": number(-1.0), "normal_tolerance": number(1.0),
    "normal_max_iterations": integer(0), "jacobian_step_creepage": number(1.0), "jacobian_step_spin": number(10.0),
}

STATE = {"speed": number(0.0), "lateral_velocity": number(), "yaw_rate": number(),
         "wheel_angular_velocity": number(None, optional=True), "extra_creepage": number(2.0, optional=True)}

# For every public call: how to get it, valid arguments, and every parameter's cases. The keys of
# `params` must be the call's parameters (**settings: the keywords it takes).
CALLS = {
    "Solver": dict(get=lambda: railcontact.Solver, base={}, params={"method": choice(), **SETTINGS}),
    "Solver.configure": dict(get=lambda: railcontact.Solver(elements=300).configure, base={},
                             params={"method": choice(optional=True), **SETTINGS}),
    "Solver.set_ellipse": dict(get=solver_call("set_ellipse"), base={"a": 6e-3, "b": 4e-3, "normal_force": 80e3},
                               params={"a": number(-1e-3), "b": number(-1e-3), "normal_force": number(-1.0, True),
                                       "approach": number(-1e-6, True)}),
    "Solver.set_hertz": dict(get=solver_call("set_hertz"), base={"A": 0.5, "B": 0.1, "normal_force": 80e3},
                             params={"A": number(-0.5), "B": number(-0.1), "normal_force": number(-1.0, True),
                                     "approach": number(-1e-6, True)}),
    "Solver.set_grid": dict(get=solver_call("set_grid"),
                            base={"h": np.full((8, 8), -1e-6), "dx1": 1e-3, "dx2": 1e-3, "normal_force": 1e3},
                            params={"h": array(np.zeros(8), np.full((8, 8), NAN)), "dx1": number(-1e-3),
                                    "dx2": number(-1e-3), "normal_force": number(-1.0, True),
                                    "approach": number(None, True)}),  # h - approach > 0: no contact
    "Solver.set_flextable_patch": dict(get=lambda: railcontact.Solver(elements=300).set_flextable_patch,
                                       base={"table": None, "y": 0.0, "vertical_load": 90e3},
                                       params={"table": instance(), "y": number(0.5), "vertical_load": number(-1.0)}),
    "Solver.solve": dict(get=solver_call("solve"), base={},
                         params={"xi": number(), "eta": number(), "phi": number(), "tractions": flag(),
                                 "jacobian": flag()}),
    "Solver.batch": dict(get=solver_call("batch"), base={"creepages": np.zeros((2, 3))},
                         needs={"geometry": {"patches": np.array([[6e-3, 4e-3, 80e3]])}},
                         params={"creepages": array(np.zeros(3)),
                                 "patches": array(np.zeros(3), optional=True,
                                                  out_of_range=np.array([[6e-3, 4e-3, 80e3]] * 3)),
                                 "geometry": choice(optional=True), "threads": integer(-1), "jacobian": flag(),
                                 "errors": choice()}),
    "creep_forces": dict(get=lambda: railcontact.creep_forces, base={"a": 6e-3, "b": 4e-3, "normal_force": 80e3,
                                                                     "elements": 300},
                         needs={key: {"elements": None} for key in ("elements_across", "element_size")},
                         params={"a": number(-1e-3), "b": number(-1e-3), "normal_force": number(-1.0),
                                 "xi": number(), "eta": number(), "phi": number(), "method": choice(),
                                 "tractions": flag(), **SETTINGS}),
    "FlexibilityTable": dict(get=lambda: railcontact.FlexibilityTable, base={}, params={}),
    "FlexibilityTable.load": dict(get=lambda: railcontact.FlexibilityTable.load, base={"path": "no-such-table.json"},
                                  params={"path": path(), "setup": path(optional=True)}),
    "FlexibilityTable.build": dict(get=lambda: railcontact.FlexibilityTable.build,
                                   base={"y": [0.0, 1e-3], "loads": [90e3, 100e3], "elements": 300,
                                         "progress": lambda done, total: False},
                                   params={"y": grid([1e-3, 0.0]), "loads": grid([-1.0, 100e3]),
                                           "setup": path(optional=True), "elements": integer(0),
                                           "youngs_modulus": number(-1.0), "poisson_ratio": number(0.7),
                                           "progress": callback()}),
    "FlexibilityTable.save": dict(get=table_call("save"), base={}, params={"path": path()}),
    "FlexibilityTable.lookup": dict(get=table_call("lookup"), base={"y": 0.0, "vertical_load": 90e3},
                                    params={"y": number(0.5), "vertical_load": number(-1.0)}),
    "Wheelset": dict(get=lambda: railcontact.Wheelset, base={"element_size": COARSE},
                     params={"wheel": path(optional=True), "rail": path(optional=True),
                             "right_wheel": path(optional=True), "left_wheel": path(optional=True),
                             "right_rail": path(optional=True), "left_rail": path(optional=True),
                             "gauge": number(-1.0, True), "measuring_depth": number(-1.0, True),
                             "flange_back_distance": number(-1.0, True), "flange_back_y": number(10.0, True),
                             "taping_line_distance": number(-1.0, True), "nominal_radius": number(-1.0, True),
                             "rail_cant": number(40.0, True),
                             "mu": number(-0.1), "youngs_modulus": number(-1.0), "poisson_ratio": number(0.7),
                             "element_size": number(-1e-3), "solvers": choice(),
                             "loads": array([[98.1e3, 98.1e3]], [NAN, 98.1e3], [-1.0, 98.1e3], optional=True),
                             "balance_roll": flag(), "tangential_in_balance": flag(), "allow_wheel_lift": flag(),
                             "warm_start": flag(), "slip_direction": choice(),
                             "balance_solver": choice(optional=True), "reference_weighting": choice(),
                             "contact_surface": choice(),
                             "nominal_radius_at": choice(optional=True)}),
    "Wheelset.evaluate": dict(get=wheelset_call("evaluate"), base={},
                              params={"y": number(), "z": number(), "roll": number(), "yaw": number(),
                                      "vertical_velocity": number(), "roll_rate": number(), **STATE,
                                      "free_rolling": flag()}),
    "Wheelset.reset_warm_start": dict(get=wheelset_call("reset_warm_start"), base={}, params={}),
    "Wheelset.time_stages": dict(get=wheelset_call("time_stages"), base={}, params={"on": flag()}),
    "Wheelset.stage_times": dict(get=wheelset_call("stage_times"), base={}, params={}),
    "Wheelset.batch": dict(get=wheelset_call("batch"), base={"states": np.zeros((1, 4))},
                           params={"states": array(np.zeros(4), out_of_range=np.zeros((1, 12))),
                                   "threads": integer(-1), "errors": choice()}),
    "Wheelset.build_table": dict(get=lambda: railcontact.Wheelset(element_size=COARSE).build_table,
                                 base={"y": [0.0, 1e-3], "progress": lambda done, total: False},
                                 params={"y": grid([1e-3, 0.0]), "yaw": grid([1e-3, 0.0]),
                                         "loads": grid([-1.0]), "progress": callback(),
                                         "refine_lateral_force_fraction": number(out_of_range=1.5)}),
    "Wheelset.load_table": dict(get=lambda: railcontact.Wheelset(element_size=COARSE).load_table, base={},
                                params={"path": path()}),
    "Wheelset.save_table": dict(get=wheelset_call("save_table"), base={}, params={"path": path()}),
    "Wheelset.evaluate_table": dict(get=wheelset_call("evaluate_table"), base={},
                                    params={"y": number(0.5), "yaw": number(1.0), **STATE}),
    "Wheelset.table_forces": dict(get=wheelset_call("table_forces"), base={"y": 0.0, "yaw": 0.0, "speed": 20.0},
                                  params={"y": number(0.5), "yaw": number(1.0), **STATE}),
}


def public_calls():
    """{name: callable} of every public function, constructor, method and classmethod."""
    calls = {}
    for name in railcontact.__all__:
        obj = getattr(railcontact, name)
        if inspect.isfunction(obj):
            calls[name] = obj
        elif inspect.isclass(obj) and not issubclass(obj, BaseException) and not hasattr(obj, "__dataclass_fields__"):
            calls[name] = obj
            for attr, member in vars(obj).items():
                if attr.startswith("_"):
                    continue
                if isinstance(member, (staticmethod, classmethod)):
                    calls[f"{name}.{attr}"] = getattr(obj, attr)
                elif inspect.isfunction(member):
                    calls[f"{name}.{attr}"] = member
    return calls


def parameters(call):
    """The parameter names a call takes (without self and **settings)."""
    signature = inspect.signature(call)
    return [p.name for p in signature.parameters.values()
            if p.name not in ("self", "cls") and p.kind is not inspect.Parameter.VAR_KEYWORD]


def test_every_public_call_is_listed():
    """A new public call, or a new parameter of one, needs its entry in CALLS (its checks)."""
    calls = public_calls()
    assert set(calls) == set(CALLS), ("public calls without an entry in CALLS", set(calls) - set(CALLS),
                                      "entries of no public call", set(CALLS) - set(calls))
    for name, call in calls.items():
        missing = set(parameters(call)) - set(CALLS[name]["params"])
        assert not missing, f"{name}: parameters without cases: {missing}"
        signature = inspect.signature(call)
        if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in signature.parameters.values()):  # **settings
            assert set(SETTINGS) <= set(CALLS[name]["params"]), name


CASES = [(name, param, k) for name, entry in CALLS.items() for param, cases in entry["params"].items()
         for k in range(len(cases))]


def _show(value):
    text = repr(value)
    return text if len(text) < 30 else text[:27] + "..."


@pytest.mark.parametrize("name,param,k", CASES,
                         ids=[f"{n}-{p}-{_show(CALLS[n]['params'][p][k][0])}" for n, p, k in CASES])
def test_a_bad_argument_raises_an_error_naming_it(name, param, k):
    entry = CALLS[name]
    value, expected = entry["params"][param][k]
    kwargs = dict(entry["base"])
    for key, needed in entry.get("needs", {}).get(param, {}).items():  # what the parameter goes with
        if needed is None:
            kwargs.pop(key, None)
        else:
            kwargs[key] = needed
    if name == "Solver.set_flextable_patch" and kwargs.get("table") is None and param != "table":
        kwargs["table"] = Objects.get("table")
    if param == "approach":  # the normal force and the approach exclude each other
        kwargs.pop("normal_force", None)
        if value is None:
            kwargs["normal_force"] = 80e3
    kwargs[param] = value
    call = entry["get"]()
    with pytest.raises(expected) as raised:
        call(**kwargs)
    assert param in str(raised.value), (name, param, value, str(raised.value))
    if expected is ValueError:
        assert isinstance(raised.value, railcontact.InvalidInputError), type(raised.value)


def test_contradictions_name_both_arguments():
    solver = Objects.get("solver")
    wheelset = Objects.get("wheelset")
    cases = [
        (lambda: wheelset.evaluate(wheel_angular_velocity=40.0, extra_creepage=0.3),
         ("wheel_angular_velocity", "extra_creepage")),
        (lambda: wheelset.evaluate(wheel_angular_velocity=40.0, extra_creepage=0.0),
         ("wheel_angular_velocity", "extra_creepage")),
        (lambda: wheelset.evaluate_table(wheel_angular_velocity=40.0, extra_creepage=0.3),
         ("wheel_angular_velocity", "extra_creepage")),
        (lambda: wheelset.table_forces(0.0, 0.0, speed=20.0, wheel_angular_velocity=40.0, extra_creepage=0.3),
         ("wheel_angular_velocity", "extra_creepage")),
        (lambda: solver.set_ellipse(6e-3, 4e-3, 80e3, approach=1e-5), ("normal_force", "approach")),
        (lambda: railcontact.Solver(elements=300, element_size=1e-4), ("elements", "element_size")),
        (lambda: solver.batch(np.zeros((1, 3)), geometry="hertz"), ("geometry", "patches")),
        (lambda: railcontact.Wheelset(wheel="w.prw", right_rail="r.prr"), ("wheel", "right_rail")),
        (lambda: railcontact.Wheelset(gauge=1.5), ("gauge", "wheel")),
    ]
    for call, names in cases:
        with pytest.raises(railcontact.InvalidInputError) as raised:
            call()
        for n in names:
            assert n in str(raised.value), (names, str(raised.value))


def test_one_dimensional_arrays_are_refused_with_the_shape_expected():
    solver = Objects.get("solver")
    with pytest.raises(railcontact.InvalidInputError, match=r"creepages must be an array of shape \(N, 3\)"):
        solver.batch(np.array([1e-3, 0.0, 0.0]))
    with pytest.raises(railcontact.InvalidInputError, match=r"states must be an array of shape \(N, M\)"):
        Objects.get("wheelset").batch(np.zeros(4))
    with pytest.raises(railcontact.InvalidInputError, match=r"h must be an array of shape \(N, M\)"):
        solver.set_grid(np.zeros(8), 1e-3, 1e-3, 1e3)


def test_the_reported_cases():
    """The cases of the report: mu=True is not mu = 1, mu="0.3" a TypeError (not a bare
    RuntimeError), a range error of the library a ValueError with its message."""
    solver = railcontact.Solver(elements=300)
    with pytest.raises(TypeError, match="mu must be a real number"):
        solver.configure(mu=True)
    with pytest.raises(TypeError, match="mu must be a real number"):
        solver.configure(mu="0.3")
    with pytest.raises(ValueError, match=r"mu: rc_settings.friction_coefficient = -1 is outside \(0, 10\]"):
        solver.configure(mu=-1)
    assert solver.settings["friction_coefficient"] == 0.3  # a refused call changes nothing
    with pytest.raises(TypeError, match="xi must be a real number"):
        solver.solve(xi=1e-3 + 1e-4j)
    # NumPy numbers are numbers; NumPy bools are not.
    solver.configure(mu=np.float32(0.25), max_newton_iterations=np.int64(50))
    with pytest.raises(TypeError, match="tractions"):
        solver.solve(tractions=np.float64(1.0))
    solver.set_ellipse(np.float64(6e-3), 4e-3, np.int32(80000))
    assert solver.solve(xi=np.float64(1e-3), tractions=np.bool_(True)).tractions is not None
