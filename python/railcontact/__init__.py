"""railcontact: wheel-rail rolling contact (creep forces with nH-FastSim, FastSim and the exact
steady-state solvers) from Python. docs/PYTHON.md.

Units are SI throughout: m, N, Pa, N m; creepages xi, eta dimensionless, spin phi in 1/m. Frame
and signs as in the library (docs/CONVENTIONS.md): X1 rolling direction, X2 lateral, X3 normal
into the wheel; forces on the wheel, Kalker's convention (F1 = -G c^2 C11 xi at small creepage).

    import railcontact
    solver = railcontact.Solver("nh-fastsim", mu=0.3)
    solver.set_ellipse(a=6e-3, b=4e-3, normal_force=80e3)
    result = solver.solve(xi=1e-3, eta=0.0, phi=0.0, tractions=True)
    result.F1_N, result.tractions.p1_Pa      # N; 2-D array (n2, n1) in Pa

Every object may be shared between threads: each call holds the object's lock, so one call on an
object runs at a time, and solves release the GIL, so Solvers on different threads run in
parallel. Arguments are checked (railcontact._checks): a wrong type is a TypeError, a bad value an
InvalidInputError, each naming the argument. Errors raise the classes of railcontact._errors (InvalidInputError is a
ValueError, RailcontactIOError an OSError, ...).
"""
from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _checks as _check
from . import _core
from ._errors import (CancelledError, InternalError, InvalidInputError, NoContactError, NotConvergedError,
                      RailcontactError, RailcontactIOError, SeveralPatchesError)

__version__ = _core.version_string()
#: The C API's ABI version of the library inside the module.
abi_version = _core.abi_version()

METHODS = {"nh-fastsim": 0, "fastsim": 1, "exact": 2, "exact-regularised": 3}
#: nH-FastSim's slipping traction (the C API's rc_slip_direction; docs/FASTSIM.md "The slip direction").
SLIP_DIRECTIONS = {"radial": 0, "flexibility-weighted": 1, "rigid-slip": 2, "elastic-slip": 3}
#: how a wheelset patch's reference point and contact angle are averaged (rc_reference_weighting).
REFERENCE_WEIGHTINGS = {"squared-gap": 0, "depth": 1}
#: each wheelset patch's contact surface (rc_contact_surface, docs/WHEELSET.md §4).
CONTACT_SURFACES = {"planar": 0, "conformal": 1, "auto": 2}
#: where the wheel's radius is the nominal radius (rc_nominal_radius_datum).
NOMINAL_RADIUS_DATUMS = {"profile-origin": 0, "taping-line": 1}
_GEOMETRIES = {"ellipse": 0, "hertz": 1}

__all__ = ["Solver", "Result", "NormalResult", "Tractions", "FlexibilityTable", "FlexibilityTableValues",
           "creep_forces", "METHODS", "SLIP_DIRECTIONS", "REFERENCE_WEIGHTINGS", "CONTACT_SURFACES", "NOMINAL_RADIUS_DATUMS", "Wheelset", "WheelsetResult", "WheelResult", "WheelsetPatch", "SolverForces",
           "WHEELSET_STATE_COLUMNS", "abi_version", "RailcontactError", "InvalidInputError", "NoContactError",
           "SeveralPatchesError", "NotConvergedError", "RailcontactIOError", "InternalError", "CancelledError"]


@dataclass(frozen=True)
class NormalResult:
    """The normal problem of a patch (SI units)."""
    normal_force_N: float     #: F3 carried by the discrete patch (N)
    area_m2: float            #: elements in contact x element area (m^2)
    max_pressure_Pa: float    #: largest p3 (Pa)
    approach_m: float         #: mutual approach (m): Hertz's for ellipses, the normal solver's otherwise
    a_m: float                #: semi-axis along X1, or of the equivalent ellipse (m)
    b_m: float                #: semi-axis along X2 (m)
    dx1_m: float              #: element length along X1 (m)
    dx2_m: float              #: element width along X2 (m)
    x1_first_m: float         #: x1 of mesh column 0, origin at the pressure centre (m)
    x2_first_m: float         #: x2 of mesh row 0 (m)
    contact_angle_rad: float  #: wheel-rail patches: contact angle (rad); else 0
    spin_per_m: float         #: wheel-rail patches: spin from conicity, Eq 24 (1/m); else 0
    n1: int                   #: mesh elements along X1
    n2: int                   #: mesh elements along X2
    elements_in_contact: int

    @property
    def x1_m(self) -> np.ndarray:
        """Element-centre coordinates along X1 (m), length n1 (columns of the traction arrays)."""
        return self.x1_first_m + self.dx1_m * np.arange(self.n1)

    @property
    def x2_m(self) -> np.ndarray:
        """Element-centre coordinates along X2 (m), length n2 (rows of the traction arrays)."""
        return self.x2_first_m + self.dx2_m * np.arange(self.n2)


@dataclass(frozen=True)
class Tractions:
    """Traction fields on the patch's mesh, 2-D arrays of shape (n2, n1): row i2 (along X2),
    column i1 (along X1); zero outside contact. Plot e.g. with
    plt.pcolormesh(normal.x1_m, normal.x2_m, tractions.p1_Pa)."""
    p1_Pa: np.ndarray  #: tangential traction on the wheel along X1 (Pa)
    p2_Pa: np.ndarray  #: along X2 (Pa)
    p3_Pa: np.ndarray  #: normal pressure (Pa)
    slip: np.ndarray   #: 1 where the element slips, 0 in adhesion or outside contact


@dataclass(frozen=True)
class Result:
    """Creep forces of one solve (forces on the wheel, contact frame)."""
    F1_N: float                 #: longitudinal force (N)
    F2_N: float                 #: lateral force (N)
    M3_Nm: float                #: spin moment Mz about X3 through the pressure centre (N m)
    adhesion_fraction: float    #: elements in adhesion / elements in contact
    normal: NormalResult
    tractions: Optional[Tractions] = None  #: when asked for (tractions=True)
    #: d(F1, F2, M3)/d(xi, eta, phi), 3 x 3 (N, N m; per 1/m for phi), when asked for (jacobian=True)
    jacobian: Optional[np.ndarray] = None


@dataclass(frozen=True)
class FlexibilityTableValues:
    """A flexibility table's values at (y, Fz) (docs/FLEXTABLE.md)."""
    L1_m_per_Pa: float
    L2_m_per_Pa: float
    L3_m_per_Pa: float
    f11_N: float
    f22_N: float
    f23_Nm: float
    normal_force_N: float     #: F3 = Fz / cos(gamma) (N)
    contact_angle_rad: float
    spin_per_m: float         #: Eq 24, signed (right wheel) (1/m)
    area_m2: float


def _slip_direction(name):
    return SLIP_DIRECTIONS[_check.choice("slip_direction", name, SLIP_DIRECTIONS)]


class Solver:
    """A contact patch with its prepared tangential solver (the C API's rc_solver).

    method: "nh-fastsim" (default), "fastsim" (Kalker's flexibilities of the (equivalent)
    ellipse, parabolic bound), "exact" (Coulomb friction) or "exact-regularised" (Eq A1).
    Keywords (SI units; defaults in brackets; ranges in docs/C_API.md "Settings"):
      mu [0.3] friction coefficient; youngs_modulus [2.1e11 Pa]; poisson_ratio [0.3];
      mesh of ellipse/Hertz patches, one of: elements [2800] (about this many in contact),
      elements_across (n x n over the bounding box), element_size (m);
      bound_skew [0.45] (nh-fastsim's traction bound; 0 = parabola); flexibility_coarsening [0 = auto];
      slip_direction ["radial"] (nh-fastsim's slipping traction: "radial", Eq 8, or
      "flexibility-weighted", for flange patches);
      collocation_offset [0]; tolerance [1e-9], max_newton_iterations [100], krylov_tolerance [1e-6],
      max_krylov_iterations [300], regularisation [1e-8] (exact solvers); normal_tolerance [1e-10],
      normal_max_iterations [1000] (grids); jacobian_step_creepage [1e-6], jacobian_step_spin [1e-4 1/m].
    """

    _KEYWORDS = {"mu": "friction_coefficient", "youngs_modulus": "youngs_modulus_Pa",
                 "poisson_ratio": "poisson_ratio", "bound_skew": "bound_skew",
                 "flexibility_coarsening": "flexibility_coarsening", "collocation_offset": "collocation_offset",
                 "tolerance": "tolerance", "max_newton_iterations": "max_newton_iterations",
                 "krylov_tolerance": "krylov_tolerance", "max_krylov_iterations": "max_krylov_iterations",
                 "regularisation": "regularisation", "normal_tolerance": "normal_tolerance",
                 "normal_max_iterations": "normal_max_iterations", "jacobian_step_creepage": "jacobian_step_creepage",
                 "jacobian_step_spin": "jacobian_step_spin_per_m"}

    _INTEGERS = ("flexibility_coarsening", "max_newton_iterations", "max_krylov_iterations", "normal_max_iterations",
                 "elements_across")
    _MESHES = ("elements", "elements_across", "element_size")
    #: the library's names of the keywords, for its messages
    _LIBRARY_NAMES = {**{field: key for key, field in _KEYWORDS.items()}, "method": "method",
                      "slip_direction": "slip_direction"}

    def __init__(self, method: str = "nh-fastsim", **settings):
        _check.choice("method", method, METHODS)
        self._core = _core.Solver()
        self._normal = (-1, None)  # (serial number of the patch set, its NormalResult)
        self.configure(method=method, **settings)

    def configure(self, method: Optional[str] = None, **settings):
        """Changes settings (keywords as for the constructor). Changing the material, the mesh or
        the method discards the prepared patch; set it again."""
        values = {}
        if method is not None:
            values["method"] = METHODS[_check.choice("method", method, METHODS)]
        for key in settings:
            if key not in self._KEYWORDS and key not in self._MESHES and key != "slip_direction":
                raise TypeError(f"unknown setting {key!r}; one of {', '.join([*self._KEYWORDS, *self._MESHES])}, "
                                "slip_direction")
        _check.at_most_one(**{k: settings.get(k) for k in self._MESHES})
        names = dict(self._LIBRARY_NAMES)
        for mode, key in enumerate(self._MESHES):
            if key in settings:
                values["mesh_mode"] = mode
                value = settings.pop(key)
                values["mesh_value"] = (_check.integer if key in self._INTEGERS else _check.number)(key, value)
                names["mesh_value"] = key
        if "slip_direction" in settings:
            values["slip_direction"] = _slip_direction(settings.pop("slip_direction"))
        for key, value in settings.items():
            values[self._KEYWORDS[key]] = (_check.integer if key in self._INTEGERS else _check.number)(key, value)
        with _check.library_names(names):
            self._core.set_settings(values)

    @property
    def settings(self) -> dict:
        """All settings as the C API's rc_settings fields (SI units)."""
        return self._core.settings()

    @property
    def method(self) -> str:
        return {v: k for k, v in METHODS.items()}[self._core.settings()["method"]]

    def set_ellipse(self, a: float, b: float, normal_force: Optional[float] = None, *,
                    approach: Optional[float] = None) -> NormalResult:
        """Elliptical patch with semi-axes a (along X1) and b (m), Hertzian pressure under the
        normal force F3 (N), or, with approach= instead (m, > 0), under the load whose Hertzian
        approach that is. Prepares the method (nh-fastsim: K2, the costly part)."""
        force, approach = _normal_input(normal_force, approach)
        with _check.library_names({"a_m": "a", "b_m": "b", **_PATCH_LIBRARY_NAMES}):
            return self._set_normal(self._core.set_ellipse(_check.number("a", a), _check.number("b", b), force,
                                                           approach))

    def set_hertz(self, A: float, B: float, normal_force: Optional[float] = None, *,
                  approach: Optional[float] = None) -> NormalResult:
        """Hertz's patch for the undeformed distance h = A x1^2 + B x2^2 (A, B in 1/m) under F3 (N),
        or at the approach (penetration) approach= (m, > 0), F3 following."""
        force, approach = _normal_input(normal_force, approach)
        with _check.library_names({"A_per_m": "A", "B_per_m": "B", **_PATCH_LIBRARY_NAMES}):
            return self._set_normal(self._core.set_hertz(_check.number("A", A), _check.number("B", B), force,
                                                         approach))

    def set_grid(self, h, dx1: float, dx2: float, normal_force: Optional[float] = None, *,
                 approach: Optional[float] = None) -> NormalResult:
        """Non-Hertzian patch: the undeformed distance h (m) on a regular grid, a 2-D array of shape
        (n2, n1) (row i2 along X2, column i1 along X1; h > 0 separated), element sizes dx1, dx2 (m),
        normal force F3 (N); or approach= (m) instead of the force: h - approach + u >= 0 is solved
        with the approach prescribed (h measured at the bodies' position, negative where they
        overlap: approach=0 is the position-driven problem) and F3 follows (NoContactError when no
        element touches). The normal problem must give one patch."""
        force, approach = _normal_input(normal_force, approach)
        h = _check.array("h", h, (None, None))
        with _check.library_names({"grid_dx1_m": "dx1", "grid_dx2_m": "dx2", "grid_h_m": "h", "grid_n1": "h",
                                   "grid_n2": "h", **_PATCH_LIBRARY_NAMES}):
            return self._set_normal(self._core.set_grid(h, _check.number("dx1", dx1), _check.number("dx2", dx2),
                                                        force, approach))

    def set_flextable_patch(self, table: "FlexibilityTable", y: float, vertical_load: float) -> NormalResult:
        """The wheel-rail patch of the table's profile pair at wheelset lateral displacement y (m)
        and vertical wheel load Fz (N); nh-fastsim takes its flexibilities from the table."""
        if not isinstance(table, FlexibilityTable):
            raise TypeError(f"table must be a railcontact.FlexibilityTable (got {type(table).__name__})")
        y, vertical_load = _check.number("y", y), _check.number("vertical_load", vertical_load)
        with _check.library_names({"y_m": "y", "vertical_load_N": "vertical_load", "Fz": "vertical_load"}):
            return self._set_normal(self._core.set_flextable_patch(table._core, y, vertical_load))

    def _set_normal(self, serial_and_normal):
        serial, normal = serial_and_normal
        result = NormalResult(**normal)
        self._normal = (serial, result)
        return result

    def _normal_of(self, known, serial, normal):
        """The NormalResult of the patch with this serial number: `known` (serial number,
        NormalResult), read before the call, when it is that patch's, else made from the core's
        dict. self._normal is one tuple, replaced whole: safe between threads."""
        if serial == known[0]:
            return known[1]
        result = NormalResult(**normal)
        self._normal = (serial, result)
        return result

    @property
    def normal(self) -> NormalResult:
        """The normal results of the patch set (made once per patch: solve() returns it with every
        result at no cost)."""
        known = self._normal
        return self._normal_of(known, *self._core.normal())

    def solve(self, xi: float = 0.0, eta: float = 0.0, phi: float = 0.0, *, tractions: bool = False,
              jacobian: bool = False) -> Result:
        """Creep forces for creepages xi, eta (-) and spin phi (1/m) on the patch set; with
        tractions=True the traction fields, with jacobian=True d(F1, F2, M3)/d(xi, eta, phi) by
        central differences (6 more solves)."""
        xi, eta, phi = _check.number("xi", xi), _check.number("eta", eta), _check.number("phi", phi)
        tractions, jacobian = _check.flag("tractions", tractions), _check.flag("jacobian", jacobian)
        known = self._normal  # serial numbers start at 1: 0 asks for the normal results
        (F1, F2, M3, adhesion), J, fields, serial, normal = self._core.solve(xi, eta, phi, tractions, jacobian,
                                                                            max(known[0], 0))
        return Result(F1, F2, M3, adhesion, self._normal_of(known, serial, normal),
                      Tractions(**fields) if tractions else None, J)

    def batch(self, creepages, *, patches=None, geometry: Optional[str] = None, threads: int = 0,
              jacobian: bool = False, errors: str = "raise"):
        """Many states at once on `threads` threads (0: all hardware threads); the numbers equal
        those of a loop of solve().

        creepages: array (N, 3) of xi, eta (-), phi (1/m).
        patches: None (the patch set, given as an ellipse or Hertz patch the same way) or an array
        (N, 3) or (1, 3) of [a, b, F3] (geometry "ellipse", the default) or [A, B, F3] (geometry
        "hertz"); geometry goes with patches only.
        Returns an array (N, 4) of F1 (N), F2 (N), M3 (N m), adhesion fraction; with jacobian=True
        also an array (N, 3, 3). errors="raise" raises the first failed state's error;
        errors="nan" gives NaN rows for failed states instead.
        """
        c = _check.array("creepages", creepages, (None, 3), finite=False)  # a NaN row is a failed state
        kind = _GEOMETRIES["ellipse"]
        if patches is None:
            if geometry is not None:
                raise InvalidInputError("geometry and patches=None contradict each other: geometry describes the "
                                        "rows of patches; without patches the patch set is used")
            p = None
        else:
            p = _check.array("patches", patches, (None, 3), finite=False)
            if p.shape[0] not in (1, c.shape[0]):
                raise InvalidInputError(f"patches must be an array of shape (1, 3) or (N, 3) with N = {c.shape[0]}, "
                                        f"the rows of creepages (got shape {p.shape})")
            if geometry is not None:
                kind = _GEOMETRIES[_check.choice("geometry", geometry, _GEOMETRIES)]
        threads = _check.integer("threads", threads, minimum=0)
        jacobian = _check.flag("jacobian", jacobian)
        _check.choice("errors", errors, ("raise", "nan"))
        forces, statuses, J, (status, message) = self._core.batch(p, kind, c, threads, jacobian)
        if status != 0 and errors == "raise":
            _raise(status, message)
        return (forces, J) if jacobian else forces


#: the library's names of a patch's normal force and approach, for its messages
_PATCH_LIBRARY_NAMES = {"normal_force_N": "normal_force", "normal force": "normal_force", "approach_m": "approach",
                        "approach": "approach"}


def _normal_input(normal_force, approach):
    _check.exactly_one(normal_force=normal_force, approach=approach)
    if approach is None:
        return _check.number("normal_force", normal_force), None
    return 0.0, _check.number("approach", approach)


def _raise(status, message):
    classes = {1: InvalidInputError, 2: NoContactError, 3: SeveralPatchesError, 4: NotConvergedError,
               5: RailcontactIOError, 7: MemoryError, 9: CancelledError}
    raise classes.get(status, InternalError)(message)


class FlexibilityTable:
    """nH-FastSim's flexibilities of a wheel-rail profile pair over wheelset lateral displacement y
    and vertical wheel load Fz (docs/FLEXTABLE.md), with the pair it belongs to."""

    def __init__(self):
        self._core = _core.FlexTable()

    @classmethod
    def load(cls, path, setup=None) -> "FlexibilityTable":
        """Reads a table file (JSON) for the profiles of a wheel-rail set-up file (None: the shipped
        S1002/UIC60 set-up)."""
        path = _check.path("path", path)
        setup = None if setup is None else _check.path("setup", setup)
        table = cls()
        table._core.load(path, setup)
        return table

    @classmethod
    def build(cls, y, loads, *, setup=None, elements: int = 3000, youngs_modulus: float = 2.1e11,
              poisson_ratio: float = 0.3, progress=None) -> "FlexibilityTable":
        """Builds the table over lateral displacements y (m, increasing) and vertical loads (N,
        increasing) with about `elements` elements in contact per patch. progress(done, total) is
        called after each node; returning False stops the build (CancelledError)."""
        y, loads = _check.grid("y", y), _check.grid("loads", loads)
        setup = None if setup is None else _check.path("setup", setup)
        elements = _check.integer("elements", elements, minimum=1)
        youngs_modulus = _check.number("youngs_modulus", youngs_modulus)
        poisson_ratio = _check.number("poisson_ratio", poisson_ratio)
        progress = _check.callback("progress", progress)
        table = cls()
        with _check.library_names({"y_m": "y", "loads_N": "loads", "target_elements": "elements",
                                   "youngs_modulus_Pa": "youngs_modulus", "poisson_ratio": "poisson_ratio",
                                   "Young's modulus": "youngs_modulus", "Poisson's ratio": "poisson_ratio",
                                   "load": "loads"}):
            table._core.build(setup, y, loads, elements, youngs_modulus, poisson_ratio, progress)
        return table

    def save(self, path):
        """Writes the table file (JSON, docs/FLEXTABLE.md §3)."""
        self._core.save(_check.path("path", path))

    @property
    def info(self) -> dict:
        """Grid ranges (m, N), counts, and the material and elements of the build."""
        return self._core.info()

    def lookup(self, y: float, vertical_load: float) -> FlexibilityTableValues:
        """The interpolated values at wheelset lateral displacement y (m) and vertical load Fz (N)."""
        y, vertical_load = _check.number("y", y), _check.number("vertical_load", vertical_load)
        with _check.library_names({"y_m": "y", "Fz": "vertical_load", "load": "vertical_load"}):
            return FlexibilityTableValues(**self._core.lookup(y, vertical_load))


def creep_forces(a: float, b: float, normal_force: float, xi: float = 0.0, eta: float = 0.0, phi: float = 0.0,
                 *, method: str = "nh-fastsim", tractions: bool = False, **settings) -> Result:
    """One-shot creep forces on an elliptical patch: semi-axes a (along X1), b (m), normal force
    F3 (N), creepages xi, eta (-), spin phi (1/m). Keywords as for Solver."""
    solver = Solver(method, **settings)
    if normal_force is None:
        raise TypeError("normal_force must be a real number (got None)")
    solver.set_ellipse(a, b, normal_force)
    return solver.solve(xi, eta, phi, tractions=tractions)


# ---- Wheelset (docs/WHEELSET.md, docs/PYTHON.md "Wheelset") ------------------------------------

#: The columns of a state row of Wheelset.batch, in this order (SI units; see Wheelset.evaluate).
WHEELSET_STATE_COLUMNS = ("y", "z", "roll", "yaw", "speed", "lateral_velocity", "vertical_velocity", "roll_rate",
                          "yaw_rate", "wheel_angular_velocity", "extra_creepage")
_STATE_DEFAULTS = (0.0, 0.0, 0.0, 0.0, 20.0, 0.0, 0.0, 0.0, 0.0, float("nan"), 0.0)
_TRACK_KEYWORDS = {"gauge": "track_gauge_m", "measuring_depth": "gauge_measuring_depth_m",
                   "flange_back_distance": "flange_back_distance_m", "flange_back_y": "flange_back_y_m",
                   "taping_line_distance": "taping_line_from_flange_back_m", "nominal_radius": "nominal_rolling_radius_m",
                   "rail_cant": "rail_cant_rad"}


#: the library's names of the state's fields (rc_wheelset_state), for its messages
_STATE_LIBRARY_NAMES = {"y_m": "y", "z_m": "z", "roll_rad": "roll", "yaw_rad": "yaw", "forward_speed_m_per_s": "speed",
                        "lateral_velocity_m_per_s": "lateral_velocity",
                        "vertical_velocity_m_per_s": "vertical_velocity", "roll_rate_rad_per_s": "roll_rate",
                        "yaw_rate_rad_per_s": "yaw_rate", "wheel_angular_velocity_rad_per_s": "wheel_angular_velocity",
                        "extra_longitudinal_creepage": "extra_creepage",
                        "extra longitudinal creepage": "extra_creepage", "forward speed": "speed"}


_STATE_COLUMN = {name: k for k, name in enumerate(WHEELSET_STATE_COLUMNS)}
_OPTIONAL_STATE_COLUMNS = ("wheel_angular_velocity", "extra_creepage")  # None: not given


def _state_row(**values):
    """A checked state row (WHEELSET_STATE_COLUMNS) from evaluate()'s arguments; those not given
    take their defaults. wheel_angular_velocity and extra_creepage exclude each other."""
    if values.get("wheel_angular_velocity") is not None and values.get("extra_creepage") is not None:
        _check.at_most_one(wheel_angular_velocity=values["wheel_angular_velocity"],
                           extra_creepage=values["extra_creepage"])
    row = list(_STATE_DEFAULTS)
    for name, value in values.items():
        if value is not None or name not in _OPTIONAL_STATE_COLUMNS:
            row[_STATE_COLUMN[name]] = _check.number(name, value)
    return np.array(row)


@dataclass(frozen=True)
class SolverForces:
    """One tangential solver's forces on a patch (on the wheel)."""
    F1_N: float                #: longitudinal force, contact frame (N)
    F2_N: float                #: lateral force, contact frame (N)
    M3_Nm: float               #: spin moment about X3 through the centre of pressure (N m)
    adhesion_fraction: float   #: elements in adhesion / elements in contact
    force_track_N: np.ndarray  #: F1 X1 + F2 X2 + F3 X3 in the track frame (N), shape (3,)


@dataclass(frozen=True)
class WheelsetPatch:
    """One contact patch of a wheel (docs/WHEELSET.md §4-7). Track frame: x along the track, y to
    the left, z up. Contact frame: X1 = x, X3 the rail's normal into the wheel, X2 = X3 x X1."""
    side: str                          #: "right" or "left"
    reference_point_track_m: np.ndarray  #: the reference point on the rail surface, track frame (m), (3,)
    x2_axis: np.ndarray                #: the contact frame's X2 in the track frame, (3,)
    x3_axis: np.ndarray                #: the contact frame's X3 (the normal into the wheel), (3,)
    contact_angle_rad: float           #: gamma, + leaning towards the track centre (rad)
    rolling_radius_m: float            #: the wheel's radius at the patch (m)
    max_interpenetration_m: float      #: largest overlap of the undeformed bodies (m)
    xi: float                          #: longitudinal creepage at the reference point (-)
    eta: float                         #: lateral creepage (-)
    phi_per_m: float                   #: spin creepage (1/m)
    normal_force_N: float              #: F3 (N)
    area_m2: float                     #: contact area (m^2)
    max_pressure_Pa: float             #: largest p3 (Pa)
    pressure_centre_x1_m: float        #: centre of pressure from the reference point along X1 (m)
    pressure_centre_x2_m: float        #: ... along X2 (m)
    elements_in_contact: int
    normal_iterations: int             #: of the final normal solve
    pressure_force_track_N: np.ndarray  #: the pressure's resultant on the wheel, track frame (N), (3,)
    contact_angle_spread_rad: float    #: the rail normal angle's weighted standard deviation (rad)
    conformal_weight: float            #: 0 planar, 1 conformal, between: both surfaces blended
    F1_N: float                        #: the first solver's F1, contact frame (N)
    F2_N: float                        #: the first solver's F2 (N)
    M3_Nm: float                       #: the first solver's M3 about the centre of pressure (N m)
    adhesion_fraction: float           #: the first solver's
    force_track_N: np.ndarray          #: the first solver's force on the wheel, track frame (N), (3,)
    solvers: dict                      #: solver name -> SolverForces, every solver of the wheelset


@dataclass(frozen=True)
class WheelResult:
    """One wheel's patches (along the rail profile, gauge side first) and total force."""
    side: str                   #: "right" or "left"
    patches: list               #: of WheelsetPatch
    force_track_N: np.ndarray   #: sum over the patches (first solver), track frame (N), (3,)
    vertical_displacement_m: float  #: the height at which the wheel was solved (m)
    load_iterations: int        #: by load: normal solves of the height iteration, all balance passes


@dataclass(frozen=True)
class WheelsetResult:
    """One evaluation of a wheelset: both wheels (right, left) and the totals."""
    wheels: list                #: [right WheelResult, left WheelResult]
    force_track_N: np.ndarray   #: on the wheelset, both wheels, track frame (N), (3,)
    vertical_displacement_m: float  #: the state as solved: z of the centre (m; by load: found)
    roll_rad: float             #: the state as solved: roll (rad; balance_roll: found)
    #: the wheels' angular velocity used (rad/s; free rolling: found); None from a batch
    wheel_angular_velocity_rad_per_s: Optional[float] = None

    @property
    def right(self) -> WheelResult:
        return self.wheels[0]

    @property
    def left(self) -> WheelResult:
        return self.wheels[1]


def _wheelset_result(d, solver_names):
    wheels = []
    for w in d["wheels"]:
        patches = []
        for p in w["patches"]:
            solvers = {name: SolverForces(*forces) for name, forces in zip(solver_names, p.pop("solvers"))}
            first = solvers[solver_names[0]]
            patches.append(WheelsetPatch(**p, F1_N=first.F1_N, F2_N=first.F2_N, M3_Nm=first.M3_Nm,
                                         adhesion_fraction=first.adhesion_fraction,
                                         force_track_N=first.force_track_N, solvers=solvers))
        wheels.append(WheelResult(w["side"], patches, w["force_track_N"], w["vertical_displacement_m"],
                                  w["load_iterations"]))
    return WheelsetResult(wheels, d["force_track_N"], d["vertical_displacement_m"], d["roll_rad"],
                          d.get("wheel_angular_velocity_rad_per_s"))


class Wheelset:
    """Both wheels of a wheelset on their rails in 3-D (the C API's rc_wheelset; docs/WHEELSET.md).

    Profiles: none for the shipped S1002 / UIC60 1:40 set-up; wheel= and rail= (paths, one for both
    sides); or right_wheel=, left_wheel=, right_rail=, left_rail=. With profiles, the track's
    dimensions (m): gauge [1.435], measuring_depth [0.014], flange_back_distance [1.360],
    flange_back_y [-0.070], taping_line_distance [0.070] (flange back -> taping line),
    nominal_radius [0.46]; rail_cant [0 rad] (the rail's inclination towards the track centre,
    applied to the rail profile, |rail_cant| <= 0.1; 0: the profile as given; 1:40 is
    atan(1/40) = 0.0249948).
    Options (SI units): mu [0.3]; youngs_modulus [2.1e11 Pa]; poisson_ratio [0.3]; element_size
    [0.2e-3 m]; solvers [("nh-fastsim",)] run on every patch, the first makes the totals;
    loads [(98100, 98100) N, right and left]: by load, each wheel's height is solved to carry its
    load; loads=None: by position (the state's z and roll give the overlap); balance_roll [False];
    tangential_in_balance [True]; allow_wheel_lift [False] (else NoContactError for a lifted
    wheel); warm_start [True] (each evaluation starts from the previous one's pressures; False:
    every evaluation from a cold start, as in batch()); slip_direction ["elastic-slip"]
    (nh-fastsim's slipping traction: as "rigid-slip", and where a patch slips everywhere Coulomb's
    law along the elastic slip, within 0.5 % of the exact solver there;
    "rigid-slip": within 3 % on the flange, also in full slip under spin; "flexibility-weighted": without the turn to the rigid slip; "radial": Eq 8).
    balance_solver [None: the first of solvers] (the solver whose forces the load balance and free
    rolling use, one of solvers); reference_weighting ["squared-gap"] (each patch's reference point
    and contact angle as Kalker's CONTACT weights them; "depth": by the overlap depth, smoother onto
    the flange); contact_surface ["planar"] (each patch in the tangent plane at its reference point;
    "conformal": curved with the profiles across the rolling direction; "auto": planar where the
    contact angle hardly varies over a patch, conformal where it does, blended between; a table is
    built on this surface and used with it);
    nominal_radius_at ["profile-origin"] (where the wheel's radius is nominal_radius;
    "taping-line"; with profiles only).
    A Wheelset may be shared between threads (one call at a time); evaluations release the GIL.
    """

    #: the library's names of the options and dimensions, for its messages
    _LIBRARY_NAMES = {"friction_coefficient": "mu", "friction coefficient": "mu", "youngs_modulus_Pa": "youngs_modulus",
                      "Young's modulus": "youngs_modulus", "poisson_ratio": "poisson_ratio",
                      "Poisson's ratio": "poisson_ratio", "element_size_m": "element_size",
                      "element size": "element_size", "right_load_N": "loads", "left_load_N": "loads",
                      "vertical load": "loads", "solvers": "solvers", "slip_direction": "slip_direction",
                      "track_gauge_m": "gauge", "gauge_measuring_depth_m": "measuring_depth",
                      "flange_back_distance_m": "flange_back_distance", "flange_back_y_m": "flange_back_y",
                      "taping_line_from_flange_back_m": "taping_line_distance",
                      "nominal_rolling_radius_m": "nominal_radius", "rail_cant_rad": "rail_cant"}

    def __init__(self, wheel=None, rail=None, *, right_wheel=None, left_wheel=None, right_rail=None,
                 left_rail=None, gauge=None, measuring_depth=None, flange_back_distance=None, flange_back_y=None,
                 taping_line_distance=None, nominal_radius=None, rail_cant=None, mu: float = 0.3, youngs_modulus: float = 2.1e11,
                 poisson_ratio: float = 0.3, element_size: float = 0.2e-3, solvers=("nh-fastsim",),
                 loads=(98100.0, 98100.0), balance_roll: bool = False, tangential_in_balance: bool = True,
                 allow_wheel_lift: bool = False, warm_start: bool = True,
                 slip_direction: str = "elastic-slip", balance_solver=None,
                 reference_weighting: str = "squared-gap", contact_surface: str = "planar",
                 nominal_radius_at=None):
        if isinstance(solvers, str):
            solvers = (solvers,)
        if not isinstance(solvers, (tuple, list)) or not solvers:
            raise TypeError(f"solvers must be a solver name or a non-empty tuple of them (got {solvers!r})")
        self._solvers = tuple(_check.choice("solvers", name, METHODS) for name in solvers)
        options = {"friction_coefficient": _check.number("mu", mu),
                   "youngs_modulus_Pa": _check.number("youngs_modulus", youngs_modulus),
                   "poisson_ratio": _check.number("poisson_ratio", poisson_ratio),
                   "element_size_m": _check.number("element_size", element_size),
                   "solvers": [METHODS[n] for n in self._solvers],
                   "normal_mode": 1 if loads is None else 0,
                   "balance_roll": int(_check.flag("balance_roll", balance_roll)),
                   "tangential_in_balance": int(_check.flag("tangential_in_balance", tangential_in_balance)),
                   "allow_wheel_lift": int(_check.flag("allow_wheel_lift", allow_wheel_lift)),
                   "warm_start": int(_check.flag("warm_start", warm_start)),
                   "slip_direction": _slip_direction(slip_direction),
                   "reference_weighting": REFERENCE_WEIGHTINGS[_check.choice("reference_weighting",
                                                                             reference_weighting,
                                                                             REFERENCE_WEIGHTINGS)],
                   "contact_surface": CONTACT_SURFACES[_check.choice("contact_surface", contact_surface,
                                                                     CONTACT_SURFACES)],
                   "balance_solver": -1}
        if balance_solver is not None:
            named = _check.choice("balance_solver", balance_solver, METHODS)
            if named not in self._solvers:
                raise InvalidInputError(f"balance_solver = {named!r} is not one of solvers {self._solvers}")
            options["balance_solver"] = METHODS[named]
        if loads is not None:  # one load for both wheels, or (right, left)
            pair = _check.grid("loads", loads)
            if pair.size not in (1, 2):
                raise InvalidInputError(f"loads must be one load or (right, left) in N (got {pair.size} values)")
            options["right_load_N"], options["left_load_N"] = float(pair[0]), float(pair[-1])
        given = {"gauge": gauge, "measuring_depth": measuring_depth, "flange_back_distance": flange_back_distance,
                 "flange_back_y": flange_back_y, "taping_line_distance": taping_line_distance,
                 "nominal_radius": nominal_radius, "rail_cant": rail_cant}
        dimensions = {_TRACK_KEYWORDS[key]: _check.number(key, value) for key, value in given.items()
                      if value is not None}
        if nominal_radius_at is not None:
            given["nominal_radius_at"] = nominal_radius_at
            dimensions["nominal_radius_at"] = NOMINAL_RADIUS_DATUMS[_check.choice("nominal_radius_at",
                                                                                 nominal_radius_at,
                                                                                 NOMINAL_RADIUS_DATUMS)]
        profiles = {"wheel": wheel, "rail": rail, "right_wheel": right_wheel, "left_wheel": left_wheel,
                    "right_rail": right_rail, "left_rail": left_rail}
        paths = {key: _check.path(key, value) for key, value in profiles.items() if value is not None}
        two, four = ("wheel", "rail"), ("right_wheel", "left_wheel", "right_rail", "left_rail")
        if paths and not (set(paths) == set(two) or set(paths) == set(four)):
            raise InvalidInputError(f"{', '.join(paths)}: give wheel= and rail=, or right_wheel=, left_wheel=, "
                                    "right_rail= and left_rail=, or no profiles (the default S1002/UIC60 set-up)")
        if not paths and dimensions:
            named = ", ".join(k for k in given if given[k] is not None)
            raise InvalidInputError(f"{named}: track dimensions need profile files (wheel=, rail=); the default set-up "
                                    "has its own")
        self._core = _core.Wheelset()
        with _check.library_names(self._LIBRARY_NAMES):
            self._core.set_options(options)
            if not paths:
                self._core.set_default_track()
            else:
                self._core.set_track([paths[key] for key in (two if len(paths) == 2 else four)], dimensions)

    @property
    def track(self) -> dict:
        """The track's dimensions (m) and the nominal axle height H0 (m): the height of the wheelset
        centre at which, with y, roll and yaw zero, the first wheel touches its rail."""
        return self._core.track()

    @property
    def options(self) -> dict:
        """The options as the C API's rc_wheelset_options fields."""
        return self._core.options()

    @property
    def solvers(self) -> tuple:
        return self._solvers

    def evaluate(self, y: float = 0.0, z: float = 0.0, roll: float = 0.0, yaw: float = 0.0, *, speed: float = 20.0,
                 lateral_velocity: float = 0.0, vertical_velocity: float = 0.0, roll_rate: float = 0.0,
                 yaw_rate: float = 0.0, wheel_angular_velocity: Optional[float] = None,
                 extra_creepage: Optional[float] = None, free_rolling: bool = False) -> WheelsetResult:
        """Evaluates one state of the wheelset.

        Position: y lateral displacement of the centre (m, + to the left), z vertical displacement
        above the nominal height (m, + up; by position only), roll (rad, + the left wheel rises),
        yaw (rad, + the axle's left end moves backwards). Velocity: speed V (m/s, > 0),
        lateral_velocity, vertical_velocity (m/s), roll_rate, yaw_rate (rad/s),
        wheel_angular_velocity (rad/s about the axle, + rolling forward; None: pure rolling at the
        nominal radius with extra_creepage xi0 (None: 0), < 0 traction, > 0 braking; the two
        exclude each other). free_rolling=True solves the angular velocity at which the wheels'
        tangential forces have no moment about the axle (docs/WHEELSET.md §6; not with the other two).
        Returns a WheelsetResult (wheels[0] right, wheels[1] left, each with its patches, and the
        angular velocity used).
        """
        free_rolling = _check.flag("free_rolling", free_rolling)
        if free_rolling and (wheel_angular_velocity is not None or extra_creepage is not None):
            given = "wheel_angular_velocity" if wheel_angular_velocity is not None else "extra_creepage"
            raise ValueError(f"free_rolling=True solves the wheels' angular velocity; leave out {given}")
        row = _state_row(y=y, z=z, roll=roll, yaw=yaw, speed=speed, lateral_velocity=lateral_velocity,
                         vertical_velocity=vertical_velocity, roll_rate=roll_rate, yaw_rate=yaw_rate,
                         wheel_angular_velocity=wheel_angular_velocity, extra_creepage=extra_creepage)
        if free_rolling:
            row[_STATE_COLUMN["wheel_angular_velocity"]] = np.inf  # the extension's mark of free rolling
        with _check.library_names(_STATE_LIBRARY_NAMES):
            return _wheelset_result(self._core.evaluate(row), self._solvers)

    def reset_warm_start(self) -> None:
        """Forgets the warm start (the previous evaluation's pressures and the normal solvers'
        plans): the next evaluate() starts cold and gives the numbers of a fresh Wheelset with the
        same profiles and options, to the last digit. For a jump in the state (a new run, a
        restart)."""
        self._core.reset_warm_start()

    def time_stages(self, on: bool = True) -> None:
        """Times the stages of every evaluate() from now on (on=True) or stops (on=False); either
        way the times start again from zero (stage_times()). Off by default; batches and the
        wheelset table are not timed."""
        self._core.time_stages(_check.flag("on", on))

    def stage_times(self) -> dict:
        """Where the evaluate() calls since time_stages(True) spent their time, wall-clock
        seconds per stage (docs/WHEELSET.md §8 "Where a step's time goes"): search_s (contact
        search), area_s (potential areas and their undeformed distance), normal_s (normal
        problems), height_s (by load: the heights' and balances' own steps), kinematics_s,
        tangential_s (the tangential solvers), assembly_s (the rest), with evaluations (the calls
        timed) and total_s (their sum: each interval counts in one stage)."""
        times = dict(self._core.stage_times())
        times["total_s"] = sum(value for key, value in times.items() if key.endswith("_s"))
        return times

    def batch(self, states, *, threads: int = 0, errors: str = "raise") -> list:
        """Many states at once on `threads` threads (0: all hardware threads), one wheelset per
        thread, each state from a cold start: the numbers equal those of a loop of evaluate() with
        warm_start=False, whatever the threads.

        states: array (N, k), k <= 11, columns in the order of WHEELSET_STATE_COLUMNS (y, z, roll,
        yaw, speed, lateral_velocity, vertical_velocity, roll_rate, yaw_rate,
        wheel_angular_velocity, extra_creepage); missing columns take evaluate()'s defaults; NaN
        wheel_angular_velocity means pure rolling.
        Returns a list of N WheelsetResult; errors="raise" raises the first failed state's error,
        errors="none" gives None for failed states instead.
        """
        s = _check.array("states", states, (None, None), finite=False)  # NaN: pure rolling, or a failed state
        if not 1 <= s.shape[1] <= len(WHEELSET_STATE_COLUMNS):
            raise InvalidInputError(f"states must be an array of shape (N, k), 1 <= k <= 11 (got shape {s.shape})")
        threads = _check.integer("threads", threads, minimum=0)
        _check.choice("errors", errors, ("raise", "none"))
        full = np.tile(np.array(_STATE_DEFAULTS), (s.shape[0], 1))
        full[:, :s.shape[1]] = s
        with _check.library_names(_STATE_LIBRARY_NAMES):
            results, statuses, (status, message) = self._core.batch(np.ascontiguousarray(full), threads)
        if status != 0 and errors == "raise":
            _raise(status, message)
        return [None if r is None else _wheelset_result(r, self._solvers) for r in results]

    # ---- The wheelset table (docs/WHEELSET_TABLE.md) ---------------------------------------------

    def build_table(self, y, yaw=(0.0,), loads=tuple(80e3 + 5e3 * k for k in range(9)), *, progress=None,
                    refine_lateral_force_fraction: float = 0.01) -> None:  # kWheelsetTableRefinementDefault
        """Builds this wheelset's table (its track, material, element size and contact surface) over
        the grid y (m), yaw (rad; one value serves every yaw by turning the contact point) and loads
        (N per wheel), each strictly increasing; about 0.02-0.5 s per node. progress(done, total) is
        called after each node; returning False cancels (CancelledError). The default loads, 80-120 kN
        in 5 kN steps, keep the lookups that balance the tangential forces vertically within 2 % of
        muFz of the wheelset on the fly near the flange (docs/WHEELSET_TABLE.md §3 "The load grid").
        refine_lateral_force_fraction [0.01 by default; 0: none] adds y nodes where the contact jumps
        (docs/WHEELSET_TABLE.md §3; the total of progress grows as they are added). Replaces a table
        the wheelset had."""
        grids = [_check.grid(name, value) for name, value in (("y", y), ("yaw", yaw), ("loads", loads))]
        progress = _check.callback("progress", progress)
        refine = _check.number("refine_lateral_force_fraction", refine_lateral_force_fraction)
        with _check.library_names({"y_m": "y", "yaw_rad": "yaw", "loads_N": "loads", "wheel load": "loads",
                                   "lateral_force_fraction": "refine_lateral_force_fraction"}):
            self._core.build_table(*grids, progress, refine)

    def load_table(self, path) -> None:
        """Loads a table file (`railcontact wheelset-table build`, save_table), checked against this
        wheelset's track (its four profile files and dimensions) and the settings it was built with:
        youngs_modulus, poisson_ratio, element_size and slip_direction (and nH-FastSim's recipe);
        InvalidInputError names each that differs (docs/WHEELSET_TABLE.md "What a table is used
        with")."""
        self._core.load_table(_check.path("path", path))

    def save_table(self, path) -> None:
        """Writes this wheelset's table (JSON)."""
        self._core.save_table(_check.path("path", path))

    def evaluate_table(self, y: float = 0.0, yaw: float = 0.0, *, speed: float = 20.0, lateral_velocity: float = 0.0,
                       yaw_rate: float = 0.0, wheel_angular_velocity: Optional[float] = None,
                       extra_creepage: Optional[float] = None) -> WheelsetResult:
        """A state from the table (arguments as in evaluate(), zero roll; each wheel carries its load
        of the options, nh-fastsim only). Raises InvalidInputError outside the table's grid."""
        row = _state_row(y=y, yaw=yaw, speed=speed, lateral_velocity=lateral_velocity, yaw_rate=yaw_rate,
                         wheel_angular_velocity=wheel_angular_velocity, extra_creepage=extra_creepage)
        with _check.library_names(_STATE_LIBRARY_NAMES):
            return _wheelset_result(self._core.evaluate_table(row), ("nh-fastsim",))

    def table_forces(self, y: float, yaw: float, *, speed: float, lateral_velocity: float = 0.0,
                     yaw_rate: float = 0.0, wheel_angular_velocity: Optional[float] = None,
                     extra_creepage: Optional[float] = None) -> np.ndarray:
        """The fast path of a simulation step: from the table, the array [Fx, Fy, Fz of the right
        wheel, Fx, Fy, Fz of the left wheel (N, track frame: x forward, y left, z up), Mz (N m) about
        the wheelset centre], without result objects."""
        row = _state_row(y=y, yaw=yaw, speed=speed, lateral_velocity=lateral_velocity, yaw_rate=yaw_rate,
                         wheel_angular_velocity=wheel_angular_velocity, extra_creepage=extra_creepage)
        with _check.library_names(_STATE_LIBRARY_NAMES):
            return self._core.table_forces(row)
