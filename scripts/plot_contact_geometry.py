#!/usr/bin/env python3
"""Figures of the rigid contact geometry (`railcontact geometry --out DIR`; geometry.csv, conicity.csv and
profiles.csv in DIR, docs/CONTACT_GEOMETRY.md):
- contact_points.png: the contact-point distribution on wheel and rail, for each wheel the wheel profile
  drawn above its rail and each y's contact points on the two joined by a line;
- delta_r.png: the rolling-radius difference Δr(y) = r_left - r_right and the roll angle;
- contact_angles.png: the contact angles γ(y) of both wheels;
- conicity.png: the equivalent conicity tan γe against the amplitude, both methods."""
import csv
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The wheel profile is drawn this far above the rail (mm) in the contact-point figure.
LIFT_MM = 12.0


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def column(rows, key):
    return [float(r[key]) for r in rows]


def contact_points(d, rows, profiles):
    shapes = defaultdict(lambda: ([], []))
    for p in profiles:
        ys, zs = shapes[(p["side"], p["body"])]
        ys.append(float(p["y_mm"]))
        zs.append(-float(p["z_mm"]))  # z_p points down: draw it up
    centre = min(rows, key=lambda r: abs(float(r["y_mm"])))
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    for ax, side in zip(axes, ("right", "left")):
        # The wheel in rail coordinates: shifted by its offset at the centred position.
        shift = float(centre[f"{side}_rail_profile_y_mm"]) - float(centre[f"{side}_wheel_profile_y_mm"])
        wy, wz = shapes[(side, "wheel")]
        ry, rz = shapes[(side, "rail")]
        ax.plot(ry, rz, "k-", lw=1.2, label=f"{side} rail")
        ax.plot([y + shift for y in wy], [z + LIFT_MM for z in wz], "b-", lw=1.2, label=f"{side} wheel (lifted)")
        cmap = plt.get_cmap("coolwarm")
        ys = column(rows, "y_mm")
        span = max(abs(min(ys)), abs(max(ys)), 1e-9)
        for r in rows:
            y = float(r["y_mm"])
            wyc = float(r[f"{side}_wheel_profile_y_mm"]) + shift
            wzc = -float(r[f"{side}_wheel_profile_z_mm"]) + LIFT_MM
            ryc = float(r[f"{side}_rail_profile_y_mm"])
            rzc = -float(r[f"{side}_rail_profile_z_mm"])
            ax.plot([ryc, wyc], [rzc, wzc], "-", color=cmap(0.5 + 0.5 * y / span), lw=0.5)
        ax.set_xlim(min(ry) - 2, max(ry) + 2)
        ax.set_ylim(min(rz) - 5 if len(rz) else -20, LIFT_MM + 12)
        ax.set_aspect("equal")
        ax.set_xlabel(f"{side} rail profile y_p (mm, + field side)")
        ax.set_ylabel("height (mm)")
        ax.set_title(f"{side} wheel and rail: contact points, y = {min(ys):g} ... {max(ys):g} mm "
                     "(blue: y < 0, red: y > 0)", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(d / "contact_points.png", dpi=110)
    plt.close(fig)


def delta_r(d, rows):
    y = column(rows, "y_mm")
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    ax1.plot(y, column(rows, "delta_r_mm"), "b-")
    ax1.set_ylabel("Δr = r_left − r_right (mm)")
    ax1.grid(alpha=0.3)
    ax1.set_title("Rolling-radius difference and roll of the rigid wheelset")
    ax2.plot(y, column(rows, "roll_mrad"), "g-")
    ax2.set_ylabel("roll φ (mrad, + left wheel up)")
    ax2.set_xlabel("wheelset lateral displacement y (mm, + left)")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(d / "delta_r.png", dpi=110)
    plt.close(fig)


def contact_angles(d, rows):
    y = column(rows, "y_mm")
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(y, column(rows, "right_contact_angle_rad"), "r-", label="right wheel γ_right")
    ax.plot(y, column(rows, "left_contact_angle_rad"), "b-", label="left wheel γ_left")
    ax.set_xlabel("wheelset lateral displacement y (mm, + left)")
    ax.set_ylabel("contact angle γ (rad, + towards the track centre)")
    ax.set_yscale("symlog", linthresh=0.1)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(d / "contact_angles.png", dpi=110)
    plt.close(fig)


def conicity(d, rows):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    if rows:
        a = column(rows, "amplitude_mm")
        ax.plot(a, column(rows, "tan_gamma_e_wavelength"), "k-", label="kinematic wavelength (EN 15302 Annex B)")
        ax.plot(a, column(rows, "tan_gamma_e_regression"), "r--", label="linear regression (EN 15302 Annex C)")
    ax.set_xlabel("amplitude ŷ (mm)")
    ax.set_ylabel("equivalent conicity tan γe")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(d / "conicity.png", dpi=110)
    plt.close(fig)


def main():
    d = Path(sys.argv[1])
    rows = read(d / "geometry.csv")
    contact_points(d, rows, read(d / "profiles.csv"))
    delta_r(d, rows)
    contact_angles(d, rows)
    conicity(d, read(d / "conicity.csv"))


if __name__ == "__main__":
    main()
