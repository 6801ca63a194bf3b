#!/usr/bin/env python3
"""Figures of a sweep (`railcontact sweep FILE --out DIR`, sweep.csv and sweep.json in DIR) ->
sweep_forces.png: against the sweep's innermost varied value (the last of sweep.json's "varied", e.g. y_mm),
each wheel's forces in the track frame (Fx, Fy, Fz) and, per solver, the creep forces F1, F2 of each wheel's
patches, one line per combination of the other varied values (at most 8 drawn). Failed cases are left out."""
import csv
import json
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    d = Path(sys.argv[1])
    meta = json.loads((d / "sweep.json").read_text())
    with open(d / "sweep.csv", newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "ok"]
    varied = meta.get("varied") or ["y_mm"]
    x_key = varied[-1] if varied[-1] != "wheel_load_N" else "right_wheel_N"
    others = [("right_wheel_N" if k == "wheel_load_N" else k) for k in varied[:-1]]
    solvers = [s for s in meta["recipe"]["solvers"]]
    groups = defaultdict(list)  # (other values, side) -> rows
    for r in rows:
        groups[(tuple(r[k] for k in others), r["side"])].append(r)
    keys = sorted(groups)[:16]
    panels = [("wheel_Fx_N", "wheel Fx (N, track)"), ("wheel_Fy_N", "wheel Fy (N, track)"),
              ("wheel_Fz_N", "wheel Fz (N, track)"), ("normal_force_N", "patch normal force F3 (N)")]
    for s in solvers:
        panels += [(f"{s}_F1_N", f"patch F1 (N), {s}"), (f"{s}_F2_N", f"patch F2 (N), {s}")]
    ncols = 2
    nrows = (len(panels) + 1) // 2
    fig, axes = plt.subplots(nrows, ncols, figsize=(11, 3 * nrows), sharex=True, squeeze=False)
    for ax, (key, label) in zip(axes.flat, panels):
        for g in keys:
            rs = groups[g]
            other = ", ".join(f"{k}={v}" for k, v in zip(others, g[0]))
            ax.plot([float(r[x_key]) for r in rs], [float(r[key]) for r in rs], ".", ms=3,
                    label=f"{g[1]}{', ' + other if other else ''}")
        ax.set_ylabel(label, fontsize=9)
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel(x_key)
    if keys:
        axes.flat[0].legend(fontsize=7)
    fig.suptitle(f"sweep {meta['sweep_file']['file']}: {meta['cases']} cases, {meta.get('failed_cases', 0)} failed",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(d / "sweep_forces.png", dpi=110)


if __name__ == "__main__":
    main()
