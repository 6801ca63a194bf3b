#!/usr/bin/python3
"""The linear critical speed of the hunting example's wheelset (examples/hunting_simulation.py,
docs/PYTHON.md "Hunting: the linear critical speed"): the eigenvalues of its linearised equations of
motion against speed, beside the onset of hunting that the time-domain simulation finds.

The vehicle is the simulation's own (its constants are imported from hunting_simulation.py). The
linear critical speed is that of the textbook linearisation about the centred wheelset:

- creep forces with Kalker's linear theory, f11 = G c² C11, f22 = G c² C22, f23 = G c³ C23,
  f33 = G c⁴ C33 (c² = ab), on the local Hertz ellipse of the centred patch (`railcontact patch`,
  its defaults: y = 0 and the example's 98.1 kN) with the wheelset's shear modulus and Poisson's
  ratio; the coefficients are the exact solver's at zero creepage (railcontact.Solver("exact"),
  the numbers of `railcontact coefficients` to 1.2 %);
- the rolling-radius difference, the gravitational stiffness and the contact-angle (spin)
  parameter from the rigid geometry of `railcontact geometry` (its defaults: S1002/UIC60 1:40, y
  within ±6 mm), each linearised harmonically over a sinusoidal motion of amplitude A as EN 15302's
  regression (Annex C) does for Δr, at A = 3 mm (the geometry's default amplitude).

The equations (y to the left, ψ the yaw, b the half distance of the contact points, r0 the
rolling radius, W the wheel load, λ the conicity, ε_t and ε_s the harmonic slopes of
(tan γ_left − tan γ_right)/2 and (sin γ_left − sin γ_right)/2):

    m y''  + (c_y + 2 f22/V) y' + 2 f23/V ψ' + (k_y + 2 W ε_t − 2 f23 ε_s/r0) y − 2 f22 ψ = 0
    Iz ψ'' + 2 b² f11/V ψ' + 2 b f11 λ/r0 y + k_ψ ψ = 0

The simulation's yaw moment is that of the patches' forces about the wheelset centre, without
their spin moments M3 (hunting_simulation.Contact.forces, Wheelset.table_forces): f33 and the
f23 term of M3 are not felt, and the linear model leaves them out as well (the variant with them
is printed too).

To explain the difference from the simulation, two more linearisations:

- Kalker's coefficients with the contact model's own (elastic) geometry: Δr, tan γ and sin γ of
  the patches of Wheelset.evaluate, which the simulation's table holds;
- the contact model's own forces (hunting_simulation.Contact.forces on the fly): Fy and Mz over y
  (harmonically, at zero yaw and velocities), their derivatives by ψ, y' and ψ' at the centre.
  Centred (over the table's first y interval, ±0.1 mm) this is the simulation's linearisation.

Each is also given against the amplitude A (0.1 … 6 mm). `--simulate` runs the simulation itself
(its table and its simulate(), 20 s) near the critical speeds: the growth or decay rate and the
frequency while the motion is linear (|y| < 0.08 mm), and the limit cycle.

Usage: /usr/bin/python3 examples/hunting_linear.py [--out DIR] [--simulation DIR] [--simulate] [--cli PATH]
Writes hunting_linear.json, hunting_linear.csv (the least-damped eigenvalue against speed),
hunting_linear_amplitudes.csv (the critical speed against amplitude), hunting_linear_runs.csv (with
--simulate) and the figure hunting_linear.png into DIR. The simulation's output directory (default
DIR) gives its hunting.csv (its onset and amplitudes, printed and drawn beside) and, for
--simulate, its wheelset table.
"""
import argparse
import copy
import csv
import dataclasses
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
from typing import Optional

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hunting_simulation as simulation  # noqa: E402 -- the vehicle, and railcontact found as it finds it

railcontact = simulation.railcontact

REFERENCE_AMPLITUDE_M = 3e-3  # `railcontact geometry`'s default amplitude (EN 15302's usual one)
SMALL_AMPLITUDE_M = 1e-3  # up to which the contact model's own forces are linearised over y alone


@dataclasses.dataclass
class LinearWheelset:
    """The linearised wheelset on tangent track (SI units), two degrees of freedom q = (y, ψ):

        M q'' + (C_s + D/V) q' + (K_s + K) q = 0,

    M = diag(m, Iz), C_s and K_s the suspension's, and the contact's forces (Fy, Mz) linearised as
    −K q − D q'/V (K, D: 2 × 2, independent of V)."""
    mass_kg: float
    yaw_inertia_kg_m2: float
    lateral_stiffness_N_per_m: float
    lateral_damping_N_s_per_m: float
    yaw_stiffness_N_m_per_rad: float
    contact_stiffness: np.ndarray  # K: N/m, N/rad; N m/m, N m/rad
    contact_damping: np.ndarray  # D: V times the N s/m, N s/rad; N m s/m, N m s/rad
    half_contact_distance_m: float = 0.0  # for the Klingel frequency
    rolling_radius_m: float = 0.0
    conicity: float = 0.0
    lateral_parts_N_per_m: Optional[dict] = None  # K_yy's parts, where known

    def matrices(self, speed):
        """M, C, K of M q'' + C q' + K q = 0 at speed V (m/s)."""
        mass = np.diag([self.mass_kg, self.yaw_inertia_kg_m2])
        damping = np.diag([self.lateral_damping_N_s_per_m, 0.0]) + np.asarray(self.contact_damping) / speed
        stiffness = np.diag([self.lateral_stiffness_N_per_m, self.yaw_stiffness_N_m_per_rad]) + \
            np.asarray(self.contact_stiffness)
        return mass, damping, stiffness

    def eigenvalues(self, speed):
        """The four eigenvalues (1/s) of the first-order system at speed V."""
        mass, damping, stiffness = self.matrices(speed)
        inverse = np.linalg.inv(mass)
        system = np.block([[np.zeros((2, 2)), np.eye(2)], [-inverse @ stiffness, -inverse @ damping]])
        return np.linalg.eigvals(system)

    def least_damped(self, speed):
        """The eigenvalue with the largest real part."""
        values = self.eigenvalues(speed)
        return values[np.argmax(values.real)]

    def klingel_frequency_Hz(self, speed):
        """The kinematic (Klingel) frequency V sqrt(λ / (b r0)) / 2π."""
        return speed * math.sqrt(self.conicity / (self.half_contact_distance_m * self.rolling_radius_m)) / (2 * math.pi)

    def critical_speed(self, lowest=1.0, highest=300.0, step=1.0, tolerance=1e-6):
        """The lowest speed (m/s) in [lowest, highest] where the least-damped eigenvalue's real part
        crosses zero upwards (a scan in `step`, then bisection to `tolerance` m/s), and that
        eigenvalue there; (None, None) when it stays negative, (lowest, …) when it is positive
        already at `lowest`."""
        previous = None
        for v in np.arange(lowest, highest + 0.5 * step, step):
            if self.least_damped(v).real > 0.0:
                if previous is None:
                    return float(v), self.least_damped(v)
                low, high = previous, float(v)
                while high - low > tolerance:
                    middle = 0.5 * (low + high)
                    if self.least_damped(middle).real > 0.0:
                        high = middle
                    else:
                        low = middle
                return high, self.least_damped(high)
            previous = float(v)
        return None, None


def kalker_contact(*, half_contact_distance_m, rolling_radius_m, conicity, f11_N, f22_N, f23_N_m=0.0, f33_N_m2=0.0,
                   wheel_load_N=0.0, tan_gamma_slope_per_m=0.0, sin_gamma_slope_per_m=0.0, spin_moment=False):
    """K and D of both wheels' contact with Kalker's linear creep coefficients (module docstring):
    ε_t = d(tan γ_left − tan γ_right)/dy / 2, ε_s the same of sin γ; `spin_moment` adds the
    patches' spin moments M3 to the yaw moment."""
    b, r0 = half_contact_distance_m, rolling_radius_m
    stiffness = np.array([[2 * wheel_load_N * tan_gamma_slope_per_m - 2 * f23_N_m * sin_gamma_slope_per_m / r0,
                           -2 * f22_N],
                          [2 * b * f11_N * conicity / r0, 0.0]])
    damping = np.array([[2 * f22_N, 2 * f23_N_m], [0.0, 2 * b * b * f11_N]])
    if spin_moment:
        stiffness += np.array([[0.0, 0.0], [-2 * f33_N_m2 * sin_gamma_slope_per_m / r0, 2 * f23_N_m]])
        damping += np.array([[0.0, 0.0], [-2 * f23_N_m, 2 * f33_N_m2]])
    return stiffness, damping


def find_cli(given=None):
    """The `railcontact` command: `given`, RAILCONTACT_CLI, the build's (BUILD/railcontact next to
    BUILD/python/railcontact) or the one on PATH."""
    candidates = [given, os.environ.get("RAILCONTACT_CLI"),
                  os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(railcontact.__file__)), "..", "..",
                                                "railcontact")),
                  shutil.which("railcontact")]
    for path in candidates:
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    raise SystemExit("hunting_linear: error: the railcontact command is neither given (--cli), nor RAILCONTACT_CLI, "
                     "nor next to the module's build, nor on PATH")


def run_json(command):
    """The JSON object a railcontact command prints with --json."""
    r = subprocess.run(command + ["--json"], capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        raise SystemExit(f"hunting_linear: error: {' '.join(command)} exited {r.returncode}: {r.stderr.strip()}")
    return json.loads(r.stdout)


def read_columns(path):
    """A CSV file as a dict of float arrays by column name."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {key: np.array([float(row[key]) for row in rows]) for key in rows[0]}


def harmonic_slope(y, values, amplitude):
    """The least-squares slope of values(y) (linear between samples) over one cycle y = A sin θ,
    θ uniform: each y weighted by the time spent there (EN 15302 Annex C's regression of Δr)."""
    theta = (np.arange(4000) + 0.5) * (2 * math.pi / 4000)
    ys = amplitude * np.sin(theta)
    fs = np.interp(ys, y, values)
    return float(np.sum((ys - ys.mean()) * (fs - fs.mean())) / np.sum((ys - ys.mean()) ** 2))


def contact_data(cli, work):
    """The centred patch, Kalker's coefficients and the rigid geometry, from railcontact."""
    patch = run_json([cli, "patch"])  # defaults: y = 0, the 98.1 kN wheel load
    if abs(patch["vertical_load_N"] - simulation.WHEEL_LOAD_N) > 1e-6 * simulation.WHEEL_LOAD_N:
        raise SystemExit("hunting_linear: error: `railcontact patch` loads the wheel with "
                         f"{patch['vertical_load_N']} N, "
                         f"the simulation with {simulation.WHEEL_LOAD_N} N")
    geometry = run_json([cli, "geometry", "--out", work])  # defaults: S1002/UIC60 1:40, y within ±6 mm
    wheelset = simulation_wheelset()
    youngs, nu = wheelset.options["youngs_modulus_Pa"], wheelset.options["poisson_ratio"]
    shear = youngs / (2 * (1 + nu))
    a, b = patch["local_hertz"]["a_m"], patch["local_hertz"]["b_m"]
    solver = railcontact.Solver("exact", mu=simulation.MU, youngs_modulus=youngs, poisson_ratio=nu)
    solver.set_ellipse(a, b, patch["normal_force_N"])
    jacobian = solver.solve(0.0, 0.0, 0.0, jacobian=True).jacobian  # ∂(F1, F2, M3)/∂(ξ, η, φ)
    c = math.sqrt(a * b)
    coefficients = {"C11": -jacobian[0, 0] / (shear * c ** 2), "C22": -jacobian[1, 1] / (shear * c ** 2),
                    "C23": -jacobian[1, 2] / (shear * c ** 3), "C33": -jacobian[2, 2] / (shear * c ** 4)}
    rows = read_columns(os.path.join(work, "geometry.csv"))
    conicity = read_columns(os.path.join(work, "conicity.csv"))

    return {"patch_a_m": a, "patch_b_m": b, "normal_force_N": patch["normal_force_N"],
            "contact_angle_rad": patch["contact_angle_rad"], "youngs_modulus_Pa": youngs, "poisson_ratio": nu,
            "shear_modulus_Pa": shear, "coefficients": coefficients,
            "f11_N": shear * c ** 2 * coefficients["C11"], "f22_N": shear * c ** 2 * coefficients["C22"],
            "f23_N_m": shear * c ** 3 * coefficients["C23"], "f33_N_m2": shear * c ** 4 * coefficients["C33"],
            "half_contact_distance_m": geometry["half_contact_distance_m"],
            "rolling_radius_m": geometry["nominal_rolling_radius_m"],
            "geometry_conicity_3mm_regression": geometry["tan_gamma_e_regression"],
            "geometry_conicity_3mm_wavelength": geometry["tan_gamma_e_wavelength"],
            "geometry_amplitude_m": geometry["amplitude_m"],
            "y_m": 1e-3 * rows["y_mm"], "delta_r_m": 1e-3 * rows["delta_r_mm"],
            "delta_tan_gamma": np.tan(rows["left_contact_angle_rad"]) - np.tan(rows["right_contact_angle_rad"]),
            "delta_sin_gamma": np.sin(rows["left_contact_angle_rad"]) - np.sin(rows["right_contact_angle_rad"]),
            "amplitudes_m": 1e-3 * conicity["amplitude_mm"],
            "conicity_regression": conicity["tan_gamma_e_regression"]}


def simulation_wheelset():
    """The simulation's wheelset (its on-the-fly nh-fastsim model: the table's nodes)."""
    return railcontact.Wheelset(element_size=0.5e-3, loads=(simulation.WHEEL_LOAD_N,) * 2, mu=simulation.MU)


def vehicle(contact, conicity=0.0, half_contact_distance_m=0.0, rolling_radius_m=0.0):
    """The example's wheelset and suspension with the contact's (K, D)."""
    return LinearWheelset(
        mass_kg=simulation.MASS_KG, yaw_inertia_kg_m2=simulation.YAW_INERTIA_KG_M2,
        lateral_stiffness_N_per_m=simulation.LATERAL_STIFFNESS_N_PER_M,
        lateral_damping_N_s_per_m=simulation.LATERAL_DAMPING_N_S_PER_M,
        yaw_stiffness_N_m_per_rad=simulation.LONGITUDINAL_STIFFNESS_N_PER_M * simulation.HALF_BOX_SPACING_M ** 2,
        contact_stiffness=contact[0], contact_damping=contact[1], half_contact_distance_m=half_contact_distance_m,
        rolling_radius_m=rolling_radius_m, conicity=conicity)


def kalker_model(data, y, delta_r, delta_tan_gamma, delta_sin_gamma, amplitude, spin_moment=False):
    """Kalker's coefficients with the geometry Δr(y), Δtan γ(y), Δsin γ(y) linearised over a motion
    of amplitude A (m)."""
    conicity = 0.5 * harmonic_slope(y, delta_r, amplitude)
    tan_slope = 0.5 * harmonic_slope(y, delta_tan_gamma, amplitude)
    sin_slope = 0.5 * harmonic_slope(y, delta_sin_gamma, amplitude)
    geometry = {key: data[key] for key in ("half_contact_distance_m", "rolling_radius_m")}
    contact = kalker_contact(**geometry, conicity=conicity, f11_N=data["f11_N"], f22_N=data["f22_N"],
                             f23_N_m=data["f23_N_m"], f33_N_m2=data["f33_N_m2"], wheel_load_N=simulation.WHEEL_LOAD_N,
                             tan_gamma_slope_per_m=tan_slope, sin_gamma_slope_per_m=sin_slope, spin_moment=spin_moment)
    m = vehicle(contact, conicity, **geometry)
    m.lateral_parts_N_per_m = {"gravitational": 2 * simulation.WHEEL_LOAD_N * tan_slope,
                               "spin": -2 * data["f23_N_m"] * sin_slope / data["rolling_radius_m"]}
    return m


def contact_forces(wheelset, y=0.0, yaw=0.0, speed=50.0, lateral_velocity=0.0, yaw_rate=0.0):
    """(Fy, Mz) of the simulation's contact model (hunting_simulation.Contact.forces on the fly)."""
    contact = simulation.Contact("on the fly", wheelset, False)
    return np.array(contact.forces(y, yaw, speed, lateral_velocity, yaw_rate))


def contact_model_sweep(wheelset, largest_m=7e-3, step_m=0.1e-3):
    """The simulation's contact model over y (zero yaw and velocities), on the table's y nodes:
    y, Fy, Mz, and the elastic geometry Δr, Δtan γ, Δsin γ (each wheel's patches weighted by their
    normal forces), mirrored to negative y (the wheelset is symmetric)."""
    ys = np.round(np.arange(0.0, largest_m + 0.5 * step_m, step_m), 9)
    rows = []
    for y in ys:
        r = wheelset.evaluate(y)
        sides = []
        for wheel in r.wheels:
            load = sum(p.normal_force_N for p in wheel.patches)
            sides.append([sum(f(p) * p.normal_force_N for p in wheel.patches) / load
                          for f in (lambda p: p.rolling_radius_m, lambda p: math.tan(p.contact_angle_rad),
                                    lambda p: math.sin(p.contact_angle_rad))])
        fy, mz = contact_forces(wheelset, y)
        rows.append([fy, mz] + [left - right for right, left in zip(*sides)])
    rows = np.array(rows)
    full = np.concatenate([-rows[:0:-1], rows])
    return {"y_m": np.concatenate([-ys[:0:-1], ys]), "Fy_N": full[:, 0], "Mz_N_m": full[:, 1],
            "delta_r_m": full[:, 2], "delta_tan_gamma": full[:, 3], "delta_sin_gamma": full[:, 4]}


def contact_model_derivatives(wheelset, speed=50.0):
    """The columns of K for ψ and of D of the simulation's contact model at the centre, by central
    differences: ψ ± 0.1 mrad, y' and b ψ' ± 1e-4 V (creepages of 1e-4, linear; V only scales them)."""
    def column(step, **state):
        (key, value), = state.items()
        return (contact_forces(wheelset, speed=speed, **{key: value}) -
                contact_forces(wheelset, speed=speed, **{key: -value})) / (2 * step)

    k_yaw = -column(1e-4, yaw=1e-4)
    d_y = -speed * column(1e-4 * speed, lateral_velocity=1e-4 * speed)
    d_yaw = -speed * column(1e-4 * speed / 0.75, yaw_rate=1e-4 * speed / 0.75)
    return k_yaw, np.column_stack([d_y, d_yaw])


def contact_model(sweep, derivatives, amplitude):
    """The simulation's contact model linearised: Fy and Mz harmonically over y = A sin θ, the rest
    at the centre."""
    k_y = [-harmonic_slope(sweep["y_m"], sweep[key], amplitude) for key in ("Fy_N", "Mz_N_m")]
    k_yaw, damping = derivatives
    return vehicle((np.column_stack([k_y, k_yaw]), damping))


def simulated(directory):
    """The simulation's amplitudes (hunting.csv) and its onset: the lowest speed whose amplitude
    exceeds its hunting threshold, from the small and the large start; None without the file."""
    path = os.path.join(directory, "hunting.csv") if directory else None
    if not path or not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        rows = [{k: (float(v) if k.startswith(("speed", "amplitude")) else v) for k, v in r.items()}
                for r in csv.DictReader(f)]

    def onset(key):
        hunting = [r["speed_m_per_s"] for r in rows if r[key] > simulation.HUNTING_AMPLITUDE_M]
        return min(hunting) if hunting else None

    return {"file": path, "rows": rows, "onset_small_start_m_per_s": onset("amplitude_small_start_m"),
            "onset_large_start_m_per_s": onset("amplitude_large_start_m")}


SIMULATED_SPEEDS_M_PER_S = [float(v) for v in range(36, 61, 2)]
SIMULATED_STARTS_M = (0.01e-3, 5e-3)  # within the table's first y interval (linear there), and large
SIMULATED_DURATION_S = 20.0


LINEAR_RANGE_M = (1e-6, 0.08e-3)  # above the integrator's tolerance, within the table's first y interval


def linear_stretch(t, y):
    """The growth (+) or decay (−) rate (1/s) and the frequency (Hz) of the motion while it is
    linear: over the seconds after the first whose largest |y| lies in LINEAR_RANGE_M (the table is
    linear within its first y interval, ±0.1 mm), the slope of log(largest |y|) and the upward zero
    crossings; (None, None) with fewer than three such seconds."""
    seconds = np.arange(1, int(t[-1] + 1e-9))
    peaks = np.array([np.max(np.abs(y[(t >= k) & (t < k + 1)])) for k in seconds])
    chosen = (peaks > LINEAR_RANGE_M[0]) & (peaks < LINEAR_RANGE_M[1])
    if np.count_nonzero(chosen) < 3:
        return None, None
    rate = float(np.polyfit(seconds[chosen], np.log(peaks[chosen]), 1)[0])
    first, last = seconds[chosen][0], seconds[chosen][-1] + 1
    return rate, frequency_Hz(t, y, first, last)


def frequency_Hz(t, y, start_s, end_s):
    """The frequency of the motion between start_s and end_s from its upward zero crossings; None
    without two."""
    keep = (t >= start_s) & (t <= end_s)
    t, y = t[keep], y[keep] - np.mean(y[keep])
    up = np.nonzero((y[:-1] < 0.0) & (y[1:] >= 0.0))[0]
    if len(up) < 2:
        return None
    times = t[up] - y[up] * (t[up + 1] - t[up]) / (y[up + 1] - y[up])
    return float((len(times) - 1) / (times[-1] - times[0]))


def simulate_near(table_file):
    """Runs of the simulation (its table, its simulate()) of SIMULATED_DURATION_S at
    SIMULATED_SPEEDS_M_PER_S from SIMULATED_STARTS_M: the limit-cycle amplitude, the growth or
    decay rate and the frequency of each."""
    if not os.path.exists(table_file):
        raise SystemExit(f"hunting_linear: error: --simulate needs the simulation's wheelset table {table_file}: "
                         "run examples/hunting_simulation.py with --out the --simulation directory first")
    # As the simulation's table contact: one load, its lookups balanced by the normal forces alone.
    wheelset = railcontact.Wheelset(element_size=0.5e-3, loads=(simulation.WHEEL_LOAD_N,) * 2, mu=simulation.MU,
                                    tangential_in_balance=False)
    wheelset.load_table(table_file)
    contact = simulation.Contact("table", wheelset, True)
    rows = []
    for v in SIMULATED_SPEEDS_M_PER_S:
        for y0 in SIMULATED_STARTS_M:
            t, y, _, status = simulation.simulate(contact, v, y0, SIMULATED_DURATION_S)
            amplitude = simulation.amplitude(t, y, SIMULATED_DURATION_S)
            ok = status == "ok"
            rate, frequency = linear_stretch(t, y) if ok else (None, None)
            rows.append({"speed_m_per_s": v, "start_m": y0, "amplitude_m": amplitude, "linear_stretch_rate_per_s": rate,
                         "linear_stretch_frequency_Hz": frequency,
                         "limit_cycle_frequency_Hz":
                             frequency_Hz(t, y, SIMULATED_DURATION_S - 5.0, SIMULATED_DURATION_S)
                             if ok and amplitude > LINEAR_RANGE_M[0] else None, "status": status})
            print(f"  V = {v:g} m/s from {y0 * 1e3:g} mm: {status}", file=sys.stderr, flush=True)
    return rows


def crossing(m):
    """The model's critical speed (m/s), frequency there and Klingel frequency (Hz); Nones when
    it is stable up to 300 m/s."""
    v, value = m.critical_speed()
    if v is None:
        return {"critical_speed_m_per_s": None, "frequency_Hz": None, "klingel_frequency_Hz": None}
    return {"critical_speed_m_per_s": v, "frequency_Hz": abs(value.imag) / (2 * math.pi),
            "klingel_frequency_Hz": m.klingel_frequency_Hz(v) if m.conicity > 0 else None}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="railcontact-out/hunting", help="output directory")
    parser.add_argument("--simulation", default=None,
                        help="the simulation's output directory (its hunting.csv and wheelset table); default: --out")
    parser.add_argument("--simulate", action="store_true",
                        help=f"also run the simulation ({SIMULATED_DURATION_S:g} s, its table) at "
                             f"{SIMULATED_SPEEDS_M_PER_S[0]:g} ... {SIMULATED_SPEEDS_M_PER_S[-1]:g} m/s: the growth "
                             "or decay rates and limit cycles beside the eigenvalues (about a minute)")
    parser.add_argument("--cli", default=None, help="the railcontact command (default: found next to the module)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    simulation_dir = args.simulation or args.out
    cli = find_cli(args.cli)
    with tempfile.TemporaryDirectory(prefix="hunting_linear_") as work:
        data = contact_data(cli, os.path.join(work, "geometry"))
    wheelset = simulation_wheelset()
    sweep = contact_model_sweep(wheelset)
    derivatives = contact_model_derivatives(wheelset)
    # The spin coefficient −F2/φ of each wheel's patch, centred and at y = +0.1 mm.
    spin_coefficients = [[-w.patches[0].F2_N / w.patches[0].phi_per_m for w in wheelset.evaluate(y).wheels]
                         for y in (0.0, 0.1e-3)]

    def rigid(amplitude, spin_moment=False):
        return kalker_model(data, data["y_m"], data["delta_r_m"], data["delta_tan_gamma"], data["delta_sin_gamma"],
                            amplitude, spin_moment)

    def elastic(amplitude):
        return kalker_model(data, sweep["y_m"], sweep["delta_r_m"], sweep["delta_tan_gamma"], sweep["delta_sin_gamma"],
                            amplitude)

    # Centred: over the table's first y interval (±0.1 mm), where the simulation's forces are linear.
    models = {"kalker_rigid_3mm": rigid(REFERENCE_AMPLITUDE_M),
              "kalker_rigid_3mm_with_spin_moments": rigid(REFERENCE_AMPLITUDE_M, True),
              "kalker_elastic_centred": elastic(0.1e-3),
              "contact_model_centred": contact_model(sweep, derivatives, 0.1e-3)}
    labels = {"kalker_rigid_3mm": f"Kalker, rigid geometry at {REFERENCE_AMPLITUDE_M * 1e3:g} mm",
              "kalker_rigid_3mm_with_spin_moments": "  the same with the spin moments M3",
              "kalker_elastic_centred": "Kalker, the contact model's elastic geometry, centred",
              "contact_model_centred": "the contact model's own forces, centred (the simulation linearised)"}
    results = {name: dict(crossing(m), conicity=m.conicity or None) for name, m in models.items()}
    amplitudes = np.round(np.arange(0.1e-3, 6.0001e-3, 0.1e-3), 7)
    by_amplitude = []
    for amplitude in amplitudes:
        row = {"amplitude_m": float(amplitude)}
        for name, m in (("rigid", rigid(amplitude)), ("elastic", elastic(amplitude)),
                        ("contact_model", contact_model(sweep, derivatives, amplitude))):
            if name != "contact_model":
                row[f"{name}_conicity"] = m.conicity
            else:
                row["contact_model_K_yy_N_per_m"] = float(m.contact_stiffness[0, 0])
            c = crossing(m)
            row[f"{name}_critical_speed_m_per_s"] = c["critical_speed_m_per_s"]
            row[f"{name}_frequency_Hz"] = c["frequency_Hz"]
        by_amplitude.append(row)

    drawn = ("kalker_rigid_3mm", "kalker_elastic_centred", "contact_model_centred")
    speeds = np.arange(5.0, 120.01, 0.5)
    least = {name: [models[name].least_damped(v) for v in speeds] for name in drawn}
    sim = simulated(simulation_dir)
    runs = None
    if args.simulate:
        runs = simulate_near(os.path.join(simulation_dir, "wheelset_table_0.5mm.json"))
        for r in runs:
            value = models["contact_model_centred"].least_damped(r["speed_m_per_s"])
            r["linear_rate_per_s"], r["linear_frequency_Hz"] = value.real, abs(value.imag) / (2 * math.pi)
    growing = [r["speed_m_per_s"] for r in runs or [] if r["start_m"] == SIMULATED_STARTS_M[0] and
               r["linear_stretch_rate_per_s"] is not None and r["linear_stretch_rate_per_s"] > 0.0]
    stability_loss = min(growing) if growing else None

    with open(os.path.join(args.out, "hunting_linear.csv"), "w") as f:
        f.write("speed_m_per_s," + ",".join(f"{n}_real_part_per_s,{n}_frequency_Hz" for n in drawn) + "\n")
        for i, v in enumerate(speeds):
            f.write(f"{v:g}," + ",".join(f"{least[n][i].real:.6e},{abs(least[n][i].imag) / (2 * math.pi):.6f}"
                                         for n in drawn) + "\n")

    def write_rows(name, rows):
        with open(os.path.join(args.out, name), "w") as f:
            f.write(",".join(rows[0]) + "\n")
            for r in rows:
                f.write(",".join("" if v is None else f"\"{v}\"" if isinstance(v, str) else f"{v:.6g}"
                                 for v in r.values()) + "\n")

    write_rows("hunting_linear_amplitudes.csv", by_amplitude)
    if runs:
        write_rows("hunting_linear_runs.csv", runs)
    summary = {"railcontact_version": railcontact.__version__,
               "contact": {k: v for k, v in data.items() if not isinstance(v, np.ndarray)},
               "matrices": {name: {"K": models[name].contact_stiffness.tolist(),
                                   "D": models[name].contact_damping.tolist()} for name in models},
               "linear": results, "by_amplitude": by_amplitude, "runs": runs,
               "simulated_stability_loss_m_per_s": stability_loss,
               "simulation": None if sim is None else {k: v for k, v in sim.items() if k != "rows"}}
    with open(os.path.join(args.out, "hunting_linear.json"), "w") as f:
        json.dump(summary, f, indent=2)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5))
    for name, style in zip(drawn, ("C0-", "C0--", "C2-")):
        ax.plot(speeds, [value.real for value in least[name]], style, label=labels[name].strip())
    if runs:
        for y0, marker in zip(SIMULATED_STARTS_M, ("C3o", "C1s")):
            shown = [r for r in runs if r["start_m"] == y0 and r["linear_stretch_rate_per_s"] is not None]
            ax.plot([r["speed_m_per_s"] for r in shown], [r["linear_stretch_rate_per_s"] for r in shown], marker,
                    markerfacecolor="none", label=f"simulated growth or decay within ±0.08 mm, start {y0 * 1e3:g} mm")
    ax.axhline(0.0, color="black", linewidth=0.8)
    v_crit = results["kalker_rigid_3mm"]["critical_speed_m_per_s"]
    if v_crit:
        ax.axvline(v_crit, color="C0", linestyle=":", label=f"linear critical speed {v_crit:.1f} m/s")
    if sim and sim["onset_small_start_m_per_s"]:
        ax.axvline(sim["onset_small_start_m_per_s"], color="C3", linestyle=":",
                   label=f"simulated onset (> {simulation.HUNTING_AMPLITUDE_M * 1e3:g} mm) "
                         f"{sim['onset_small_start_m_per_s']:g} m/s")
    ax.set_xlim(speeds[0], speeds[-1])
    ax.set_ylim(-3.0, 3.0)
    ax.set_xlabel("speed V (m/s)")
    ax.set_ylabel("real part of the least-damped eigenvalue (1/s)")
    ax.set_title("Linearised wheelset: stability against speed")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    for name, label, style in (("rigid", "Kalker, rigid geometry (railcontact geometry)", "C0-"),
                               ("elastic", "Kalker, the contact model's elastic geometry", "C0--"),
                               ("contact_model", "the contact model's own forces (A ≤ 1 mm)", "C2-")):
        # The contact model's Fy(y), Mz(y) at zero yaw and velocities overstate the creep saturation at
        # large amplitudes (in the motion the yaw rate cancels most of Δr's longitudinal creepage).
        shown = [r for r in by_amplitude if r[f"{name}_critical_speed_m_per_s"] and
                 (name != "contact_model" or r["amplitude_m"] <= SMALL_AMPLITUDE_M + 1e-12)]
        bx.plot([r[f"{name}_critical_speed_m_per_s"] for r in shown], [1e3 * r["amplitude_m"] for r in shown], style,
                label=label)
    if sim:
        rows = [r for r in sim["rows"] if np.isfinite(r["amplitude_small_start_m"])]
        bx.plot([r["speed_m_per_s"] for r in rows], [1e3 * r["amplitude_small_start_m"] for r in rows], "C7x",
                linestyle="", label="simulated, 5 s from 0.5 mm (hunting.csv)")
    if runs:
        for y0, marker in zip(SIMULATED_STARTS_M, ("C3o", "C1s")):
            shown = [r for r in runs if r["start_m"] == y0 and np.isfinite(r["amplitude_m"])]
            bx.plot([r["speed_m_per_s"] for r in shown], [1e3 * r["amplitude_m"] for r in shown], marker,
                    linestyle="", markerfacecolor="none",
                    label=f"simulated, {SIMULATED_DURATION_S:g} s from {y0 * 1e3:g} mm")
    bx.set_xlim(25.0, 95.0)
    bx.set_xlabel("speed V (m/s)")
    bx.set_ylabel("amplitude A (mm)")
    bx.set_title("Critical speed at amplitude A, and the simulated limit cycles")
    bx.grid(True, alpha=0.3)
    bx.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "hunting_linear.png"), dpi=120)

    def number(value, form):
        return "-" if value is None else format(value, form)

    c = data["coefficients"]
    reference = models["kalker_rigid_3mm"]
    print(f"Linear stability of the hunting example's wheelset, {args.out}")
    print(f"  centred patch: a = {1e3 * data['patch_a_m']:.3f} mm, b = {1e3 * data['patch_b_m']:.3f} mm, "
          f"nu = {data['poisson_ratio']:g}; C11 {c['C11']:.3f}, C22 {c['C22']:.3f}, C23 {c['C23']:.3f}, "
          f"C33 {c['C33']:.3f}; f11 {data['f11_N'] / 1e6:.2f} MN, f22 {data['f22_N'] / 1e6:.2f} MN, "
          f"f23 {data['f23_N_m'] / 1e3:.2f} kN m, f33 {data['f33_N_m2']:.1f} N m^2")
    print(f"  railcontact geometry at {1e3 * data['geometry_amplitude_m']:g} mm: conicity "
          f"{data['geometry_conicity_3mm_regression']:.4f} (regression; this script's {reference.conicity:.4f}), "
          f"{data['geometry_conicity_3mm_wavelength']:.4f} (wavelength); "
          f"b = {1e3 * data['half_contact_distance_m']:.1f} mm, "
          f"r0 = {1e3 * data['rolling_radius_m']:g} mm")
    for name, r in results.items():
        k = models[name].contact_stiffness
        v = r["critical_speed_m_per_s"]
        text = f"{v:.2f} m/s, {r['frequency_Hz']:.2f} Hz" if v else "none up to 300 m/s"
        if v and r["klingel_frequency_Hz"]:
            text += f" (Klingel {r['klingel_frequency_Hz']:.2f} Hz, conicity {r['conicity']:.4f})"
        parts = models[name].lateral_parts_N_per_m
        parts = (f" (gravitational {parts['gravitational'] / 1e6:+.2f}, spin {parts['spin'] / 1e6:+.2f})"
                 if parts else "")
        print(f"  {labels[name]}: linear critical speed {text}; contact K_yy {k[0, 0] / 1e6:+.2f} MN/m{parts}")
    print(f"  the contact model's spin coefficient -F2/phi (kN m), right / left: {spin_coefficients[0][0] / 1e3:.2f} / "
          f"{spin_coefficients[0][1] / 1e3:.2f} centred, {spin_coefficients[1][0] / 1e3:.2f} / "
          f"{spin_coefficients[1][1] / 1e3:.2f} at y = +0.1 mm")
    steps = [("Kalker, elastic geometry", models["kalker_elastic_centred"])]
    own = models["contact_model_centred"]
    for label, rows, columns, matrix in (("the contact model's K_yy", 0, 0, "contact_stiffness"),
                                         ("its whole K", slice(None), slice(None), "contact_stiffness"),
                                         ("its D (the contact model)", slice(None), slice(None), "contact_damping")):
        m = copy.deepcopy(steps[-1][1])
        getattr(m, matrix)[rows, columns] = getattr(own, matrix)[rows, columns]
        steps.append((label, m))
    print("  centred, from Kalker's to the contact model's linearisation one part at a time: " + " -> ".join(
        f"{label} {number(m.critical_speed()[0], '.2f')} m/s" for label, m in steps))
    print("  by amplitude A (mm): conicity rigid / elastic; critical speed (m/s) rigid / elastic / contact model; "
          "the contact model's K_yy (MN/m)")
    for r in by_amplitude:
        mm = 1e3 * r["amplitude_m"]
        if min(abs(mm - x) for x in (0.1, 0.5, 1, 2, 3, 4, 5, 6)) < 1e-9:
            speeds_text = " / ".join(f"{r[f'{n}_critical_speed_m_per_s']:.1f}" if r[f"{n}_critical_speed_m_per_s"]
                                     else "-" for n in ("rigid", "elastic", "contact_model"))
            print(f"    {mm:.1f}: {r['rigid_conicity']:.3f} / {r['elastic_conicity']:.3f}; {speeds_text}; "
                  f"{r['contact_model_K_yy_N_per_m'] / 1e6:+.2f}")
    if sim:
        print(f"  simulated onset ({sim['file']}, amplitude > {simulation.HUNTING_AMPLITUDE_M * 1e3:g} mm): "
              f"{sim['onset_small_start_m_per_s']} m/s from a 0.5 mm start, {sim['onset_large_start_m_per_s']} m/s "
              "from a 5 mm start")
    else:
        print(f"  no simulation output ({os.path.join(simulation_dir, 'hunting.csv')}): "
              "run examples/hunting_simulation.py")
    if runs:
        print(f"  simulated, {SIMULATED_DURATION_S:g} s runs: growth (+) or decay (-) rate (1/s) and frequency while "
              "|y| < 0.08 mm | limit cycle (largest |y| over the last second, frequency over the last 5 s) | the "
              "contact model's centred eigenvalue")

        for r in runs:
            print(f"    V = {r['speed_m_per_s']:g} m/s from {r['start_m'] * 1e3:g} mm: "
                  f"{number(r['linear_stretch_rate_per_s'], '+.3f')}, "
                  f"{number(r['linear_stretch_frequency_Hz'], '.2f')} Hz"
                  f" | {r['amplitude_m'] * 1e3:.3f} mm, {number(r['limit_cycle_frequency_Hz'], '.2f')} Hz | "
                  f"{r['linear_rate_per_s']:+.3f}, {r['linear_frequency_Hz']:.2f} Hz")
        print(f"  the simulation's centre loses stability at {stability_loss} m/s (the lowest speed whose "
              f"{SIMULATED_STARTS_M[0] * 1e3:g} mm start grows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
