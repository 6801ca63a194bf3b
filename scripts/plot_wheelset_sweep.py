#!/usr/bin/env python3
"""Figures of a wheelset sweep over y (`railcontact wheelset --sweep-y-m ... --out DIR`, wheelset_sweep.csv in
DIR) -> wheelset_sweep.png: for each wheel and patch against the wheelset's lateral displacement y, the
reference point on the rail, the contact angle, the creepages, the normal force and the creep forces."""
import csv
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    d = Path(sys.argv[1])
    with open(d / "wheelset_sweep.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    solver = next((k[: -len("_F1_N")] for k in rows[0] if k.endswith("_F1_N")), None) if rows else None
    series = defaultdict(list)  # (side, rail position class) -> rows
    for r in rows:
        # Patches are told apart by where they sit on the rail: tread (|y_p| < 25 mm) or gauge side.
        kind = "tread" if float(r["rail_profile_y_mm"]) > -25.0 else "flange side"
        series[(r["side"], kind)].append(r)
    panels = [("rail_profile_y_mm", "reference point on the rail y_p (mm)"),
              ("contact_angle_rad", "contact angle (rad)"),
              ("xi", "longitudinal creepage ξ (-)"),
              ("phi_per_m", "spin φ (1/m)"),
              ("normal_force_N", "normal force F3 (N)"),
              (f"{solver}_F1_N", f"F1 (N), {solver}"),
              (f"{solver}_F2_N", f"F2 (N), {solver}"),
              ("wheel_Fy_N", "wheel lateral force Fy (N, track)")]
    fig, axes = plt.subplots(4, 2, figsize=(11, 12), sharex=True)
    for ax, (key, label) in zip(axes.flat, panels):
        for (side, kind), rs in sorted(series.items()):
            ys = [float(r["y_mm"]) for r in rs]
            ax.plot(ys, [float(r[key]) for r in rs], ".", ms=2, label=f"{side} wheel, {kind}")
        ax.set_ylabel(label, fontsize=9)
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("wheelset lateral displacement y (mm, + left)")
    axes[0][0].legend(fontsize=8)
    fig.suptitle("Wheelset sweep over y: every patch of both wheels (docs/WHEELSET.md)")
    fig.tight_layout()
    fig.savefig(d / "wheelset_sweep.png", dpi=120)


if __name__ == "__main__":
    main()
