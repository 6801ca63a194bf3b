#!/usr/bin/env python3
"""Figure of `railcontact study surfaces` (surfaces.csv, smoothness.csv in DIR) -> contact_surfaces.png:
(top) per patch, how far the planar surface's lateral and vertical forces are from the conformal
surface's (% of mu Fz) against the automatic surface's measure, contact angle spread / cos(gamma),
with its blend band; (bottom) the right wheel's lateral force on the three surfaces in the fine
window where the blend adds most to the step between two positions."""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MU_FZ = 0.3 * 98100.0


def largest_step(rows, surface):
    return max((max(abs(float(b[f"{surface}_{k}_N"]) - float(a[f"{surface}_{k}_N"])) for k in ("Fx", "Fy", "Fz"))
                for a, b in zip(rows, rows[1:])), default=0.0)


def blend_excess(fine, setup):
    """How much larger the automatic surface's largest step is than the planar and conformal ones'."""
    rows = [r for r in fine if r["setup"] == setup]
    return largest_step(rows, "automatic") - max(largest_step(rows, "planar"), largest_step(rows, "conformal"))


def main():
    d = Path(sys.argv[1])
    with open(d / "surfaces.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    with open(d / "smoothness.csv", newline="") as f:
        fine = list(csv.DictReader(f))
    fig, axes = plt.subplots(2, 1, figsize=(9, 9))
    ax = axes[0]
    measure = [max(float(r["measure"]), 1e-4) for r in rows]
    for key, label, marker in (("Fy", "lateral Fy", "o"), ("Fz", "vertical Fz", "x")):
        diff = [abs(float(r[f"conformal_{key}_N"]) - float(r[f"planar_{key}_N"])) / MU_FZ * 100 for r in rows]
        ax.plot(measure, diff, marker, ms=3, alpha=0.5, mfc="none", label=f"{label}: |conformal - planar|")
    blended = [float(r["measure"]) for r in rows if 0.0 < float(r["conformal_weight"]) < 1.0]
    if blended:
        ax.axvspan(min(blended), max(blended), color="0.85", label="automatic surface: blended patches")
    ax.axhline(1.0, color="k", lw=0.6, ls="--")
    ax.set_xscale("log")
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("contact angle spread / cos(contact angle) (rad)")
    ax.set_ylabel("% of mu Fz")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title("Planar against conformal surface, every patch of every set-up (exact solver)", fontsize=10)
    ax = axes[1]
    if fine:
        first = max({r["setup"] for r in fine}, key=lambda setup: blend_excess(fine, setup))
        rs = [r for r in fine if r["setup"] == first]
        ys = [float(r["y_mm"]) for r in rs]
        for surface, style in (("planar", "--"), ("conformal", ":"), ("automatic", "-")):
            ax.plot(ys, [float(r[f"{surface}_Fy_N"]) / 1e3 for r in rs], style, label=surface)
        ax.set_xlabel("wheelset lateral displacement y (mm)")
        ax.set_ylabel("right wheel Fy (kN, track)")
        twin = ax.twinx()
        twin.plot(ys, [float(r["conformal_weight"]) for r in rs], color="0.5", lw=0.8)
        twin.set_ylabel("conformal weight", color="0.4")
        ax.legend(fontsize=8)
        ax.set_title(f"{first}: the window where the automatic surface blends", fontsize=10)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(d / "contact_surfaces.png", dpi=110)


if __name__ == "__main__":
    main()
