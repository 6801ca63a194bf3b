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

A Solver is used by one thread at a time; solves release the GIL, so Solvers on different
threads run in parallel. Errors raise the classes of railcontact._errors (InvalidInputError is a
ValueError, RailcontactIOError an OSError, ...).
"""
from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core
from ._errors import (CancelledError, InternalError, InvalidInputError, NoContactError, NotConvergedError,
                      RailcontactError, RailcontactIOError, SeveralPatchesError)

__version__ = _core.version_string()
#: The C API's ABI version of the library inside the module.
abi_version = _core.abi_version()

METHODS = {"nh-fastsim": 0, "fastsim": 1, "exact": 2, "exact-regularised": 3}
_GEOMETRIES = {"ellipse": 0, "hertz": 1}

__all__ = ["Solver", "Result", "NormalResult", "Tractions", "FlexibilityTable", "FlexibilityTableValues",
           "creep_forces", "METHODS", "abi_version", "RailcontactError", "InvalidInputError", "NoContactError",
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


def _finite(name, value):
    value = float(value)
    if not np.isfinite(value):
        raise InvalidInputError(f"{name} = {value} must be finite")
    return value


class Solver:
    """A contact patch with its prepared tangential solver (the C API's rc_solver).

    method: "nh-fastsim" (default), "fastsim" (Kalker's flexibilities of the (equivalent)
    ellipse, parabolic bound), "exact" (Coulomb friction) or "exact-regularised" (Eq A1).
    Keywords (SI units; defaults in brackets; ranges in docs/C_API.md "Settings"):
      mu [0.3] friction coefficient; youngs_modulus [2.1e11 Pa]; poisson_ratio [0.3];
      mesh of ellipse/Hertz patches, one of: elements [2800] (about this many in contact),
      elements_across (n x n over the bounding box), element_size (m);
      bound_skew [0.45] (nh-fastsim's traction bound; 0 = parabola); flexibility_coarsening [0 = auto];
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

    def __init__(self, method: str = "nh-fastsim", **settings):
        self._core = _core.Solver()
        self._patch = None  # the ellipse or Hertz patch set, for batch(patches=None)
        self.configure(method=method, **settings)

    def configure(self, method: Optional[str] = None, **settings):
        """Changes settings (keywords as for the constructor). Changing the material, the mesh or
        the method discards the prepared patch; set it again."""
        values = {}
        if method is not None:
            if method not in METHODS:
                raise InvalidInputError(f"unknown method {method!r}; one of {', '.join(METHODS)}")
            values["method"] = METHODS[method]
        meshes = [k for k in ("elements", "elements_across", "element_size") if k in settings]
        if len(meshes) > 1:
            raise InvalidInputError(f"give one of elements, elements_across, element_size (got {', '.join(meshes)})")
        for mode, key in enumerate(("elements", "elements_across", "element_size")):
            if key in settings:
                values["mesh_mode"] = mode
                values["mesh_value"] = settings.pop(key)
        for key, value in settings.items():
            if key not in self._KEYWORDS:
                raise InvalidInputError(f"unknown setting {key!r}")
            values[self._KEYWORDS[key]] = value
        self._core.set_settings(values)

    @property
    def settings(self) -> dict:
        """All settings as the C API's rc_settings fields (SI units)."""
        return self._core.settings()

    @property
    def method(self) -> str:
        return {v: k for k, v in METHODS.items()}[self._core.settings()["method"]]

    def set_ellipse(self, a: float, b: float, normal_force: float) -> NormalResult:
        """Elliptical patch with semi-axes a (along X1) and b (m), Hertzian pressure under the
        normal force F3 (N). Prepares the method (nh-fastsim: K2, the costly part)."""
        self._patch = None
        self._core.set_ellipse(float(a), float(b), float(normal_force))
        self._patch = (np.array([[a, b, normal_force]], dtype=float), _GEOMETRIES["ellipse"])
        return self.normal

    def set_hertz(self, A: float, B: float, normal_force: float) -> NormalResult:
        """Hertz's patch for the undeformed distance h = A x1^2 + B x2^2 (A, B in 1/m) under F3 (N)."""
        self._patch = None
        self._core.set_hertz(float(A), float(B), float(normal_force))
        self._patch = (np.array([[A, B, normal_force]], dtype=float), _GEOMETRIES["hertz"])
        return self.normal

    def set_grid(self, h, dx1: float, dx2: float, normal_force: float) -> NormalResult:
        """Non-Hertzian patch: the undeformed distance h (m) on a regular grid, a 2-D array of shape
        (n2, n1) (row i2 along X2, column i1 along X1; h > 0 separated), element sizes dx1, dx2 (m),
        normal force F3 (N). The normal problem is solved; it must give one patch."""
        self._patch = None
        self._core.set_grid(np.ascontiguousarray(h, dtype=float), float(dx1), float(dx2), float(normal_force))
        return self.normal

    def set_flextable_patch(self, table: "FlexibilityTable", y: float, vertical_load: float) -> NormalResult:
        """The wheel-rail patch of the table's profile pair at wheelset lateral displacement y (m)
        and vertical wheel load Fz (N); nh-fastsim takes its flexibilities from the table."""
        self._patch = None
        self._core.set_flextable_patch(table._core, float(y), float(vertical_load))
        return self.normal

    @property
    def normal(self) -> NormalResult:
        """The normal results of the patch set."""
        return NormalResult(**self._core.normal())

    def solve(self, xi: float = 0.0, eta: float = 0.0, phi: float = 0.0, *, tractions: bool = False,
              jacobian: bool = False) -> Result:
        """Creep forces for creepages xi, eta (-) and spin phi (1/m) on the patch set; with
        tractions=True the traction fields, with jacobian=True d(F1, F2, M3)/d(xi, eta, phi) by
        central differences (6 more solves)."""
        if jacobian:
            (F1, F2, M3, adhesion), J = self._core.jacobian(float(xi), float(eta), float(phi))
        else:
            F1, F2, M3, adhesion = self._core.solve(float(xi), float(eta), float(phi))
            J = None
        fields = Tractions(**self._core.tractions()) if tractions else None
        return Result(F1, F2, M3, adhesion, self.normal, fields, J)

    def batch(self, creepages, *, patches=None, geometry: str = "ellipse", threads: int = 0,
              jacobian: bool = False, errors: str = "raise"):
        """Many states at once on `threads` threads (0: all hardware threads); the numbers equal
        those of a loop of solve().

        creepages: array (N, 3) of xi, eta (-), phi (1/m).
        patches: None (the patch set, given as an ellipse or Hertz patch the same way) or an array
        (N, 3) or (1, 3) of [a, b, F3] (geometry "ellipse") or [A, B, F3] (geometry "hertz").
        Returns an array (N, 4) of F1 (N), F2 (N), M3 (N m), adhesion fraction; with jacobian=True
        also an array (N, 3, 3). errors="raise" raises the first failed state's error;
        errors="nan" gives NaN rows for failed states instead.
        """
        c = np.ascontiguousarray(creepages, dtype=float)
        if c.ndim == 1 and c.shape[0] == 3:
            c = c.reshape(1, 3)
        if patches is None:
            if self._patch is None:
                raise InvalidInputError("batch without patches= uses the patch of set_ellipse or set_hertz; none set")
            p, kind = self._patch
        else:
            if geometry not in _GEOMETRIES:
                raise InvalidInputError(f"geometry must be 'ellipse' or 'hertz' (got {geometry!r})")
            p, kind = np.ascontiguousarray(np.atleast_2d(patches), dtype=float), _GEOMETRIES[geometry]
        if errors not in ("raise", "nan"):
            raise InvalidInputError(f"errors must be 'raise' or 'nan' (got {errors!r})")
        forces, statuses, J, (status, message) = self._core.batch(p, kind, c, int(threads), bool(jacobian))
        if status != 0 and errors == "raise":
            _raise(status, message)
        return (forces, J) if jacobian else forces


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
        table = cls()
        table._core.load(str(path), None if setup is None else str(setup))
        return table

    @classmethod
    def build(cls, y, loads, *, setup=None, elements: int = 3000, youngs_modulus: float = 2.1e11,
              poisson_ratio: float = 0.3, progress=None) -> "FlexibilityTable":
        """Builds the table over lateral displacements y (m, increasing) and vertical loads (N,
        increasing) with about `elements` elements in contact per patch. progress(done, total) is
        called after each node; returning False stops the build (CancelledError)."""
        table = cls()
        table._core.build(None if setup is None else str(setup), np.ascontiguousarray(y, dtype=float),
                          np.ascontiguousarray(np.atleast_1d(loads), dtype=float), int(elements),
                          float(youngs_modulus), float(poisson_ratio), progress)
        return table

    def save(self, path):
        """Writes the table file (JSON, docs/FLEXTABLE.md §3)."""
        self._core.save(str(path))

    @property
    def info(self) -> dict:
        """Grid ranges (m, N), counts, and the material and elements of the build."""
        return self._core.info()

    def lookup(self, y: float, vertical_load: float) -> FlexibilityTableValues:
        """The interpolated values at wheelset lateral displacement y (m) and vertical load Fz (N)."""
        return FlexibilityTableValues(**self._core.lookup(float(y), float(vertical_load)))


def creep_forces(a: float, b: float, normal_force: float, xi: float = 0.0, eta: float = 0.0, phi: float = 0.0,
                 *, method: str = "nh-fastsim", tractions: bool = False, **settings) -> Result:
    """One-shot creep forces on an elliptical patch: semi-axes a (along X1), b (m), normal force
    F3 (N), creepages xi, eta (-), spin phi (1/m). Keywords as for Solver."""
    solver = Solver(method, **settings)
    solver.set_ellipse(a, b, normal_force)
    return solver.solve(xi, eta, phi, tractions=tractions)
