#!/usr/bin/env python3
"""Creep curves of `railcontact study hertz` (creep_curves.csv in DIR) -> creep_curves.png."""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {"exact": ("k", "-", "o"), "exact-regularised": ("0.5", ":", None), "nh-fastsim": ("tab:red", "--", "s"),
         "fastsim": ("tab:blue", "-.", "^")}


def main():
    d = Path(sys.argv[1])
    with open(d / "creep_curves.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    families = ["xi", "eta", "phi", "combined"]
    ratios = sorted({r["a_over_b"] for r in rows}, key=float)
    fig, axes = plt.subplots(len(families), len(ratios), figsize=(4 * len(ratios), 3.1 * len(families)), sharex=True)
    for i, family in enumerate(families):
        for j, ratio in enumerate(ratios):
            ax = axes[i][j]
            for solver, (color, line, marker) in STYLE.items():
                pts = [(0.0, 0.0)] + [(float(r["creepage_normalised"]), float(r["F_over_muF3"])) for r in rows
                                      if r["family"] == family and r["a_over_b"] == ratio and r["solver"] == solver]
                ax.plot(*zip(*pts), color=color, ls=line, marker=marker, ms=3, label=solver)
            ax.set_title(f"a/b = {ratio}, {family}", fontsize=9)
            ax.grid(alpha=0.3)
            ax.set_ylim(0, 1.05)
            if j == 0:
                ax.set_ylabel("|F| / (mu F3)")
            if i == len(families) - 1:
                ax.set_xlabel("normalised creepage (Kalker)")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(d / "creep_curves.png", dpi=110)


if __name__ == "__main__":
    main()
