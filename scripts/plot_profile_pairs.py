#!/usr/bin/env python3
"""Figure of `railcontact study profiles` (profile_pairs.csv in DIR) -> profile_pairs.png: per set-up, at
yaw 0, nH-FastSim's miss against the exact solver (F1, F2 as a share of mu F3) and the right wheel's
lateral force against the wheelset's lateral displacement y."""
import csv
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    d = Path(sys.argv[1])
    with open(d / "profile_pairs.csv", newline="") as f:
        rows = [r for r in csv.DictReader(f) if float(r["yaw_mrad"]) == 0.0]
    by_setup = defaultdict(list)
    for r in rows:
        by_setup[r["setup"]].append(r)
    fig, axes = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    for setup, rs in sorted(by_setup.items()):
        ys = [float(r["y_mm"]) for r in rs]
        axes[0].plot(ys, [float(r["dF1_percent_mu_F3"]) for r in rs], ".", ms=3, label=setup)
        axes[1].plot(ys, [float(r["dF2_percent_mu_F3"]) for r in rs], ".", ms=3, label=setup)
        right = {}
        for r in rs:
            if r["side"] == "right":
                right[float(r["y_mm"])] = float(r["wheel_Fy_N"]) / 1e3
        axes[2].plot(sorted(right), [right[y] for y in sorted(right)], "-", label=setup)
    for ax, label in zip(axes, ["F1: nH-FastSim − exact (% of μF3)", "F2: nH-FastSim − exact (% of μF3)",
                                "right wheel Fy (kN, track)"]):
        ax.set_ylabel(label, fontsize=9)
        ax.grid(alpha=0.3)
    for ax in axes[:2]:
        ax.axhline(3.0, color="k", lw=0.5, ls="--")
        ax.axhline(-3.0, color="k", lw=0.5, ls="--")
    axes[2].set_xlabel("wheelset lateral displacement y (mm, + left)")
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle("Profile pairs: nH-FastSim against the exact solver, yaw 0")
    fig.tight_layout()
    fig.savefig(d / "profile_pairs.png", dpi=110)


if __name__ == "__main__":
    main()
