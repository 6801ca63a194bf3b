#!/usr/bin/env python3
"""Traction maps of `railcontact run --out DIR` (like the paper's Fig 6): |p| per element for
every solver, the slip area marked, the patch outline; and the pressure map."""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def grid(x1, x2, values, dx1, dx2):
    i1 = np.rint((x1 - x1.min()) / dx1).astype(int)
    i2 = np.rint((x2 - x2.min()) / dx2).astype(int)
    g = np.full((i2.max() + 1, i1.max() + 1), np.nan)
    g[i2, i1] = values
    extent = (1e3 * (x1.min() - dx1 / 2), 1e3 * (x1.max() + dx1 / 2), 1e3 * (x2.min() - dx2 / 2), 1e3 * (x2.max() + dx2 / 2))
    return g, extent


def main():
    d = Path(sys.argv[1])
    mesh = read(d / "mesh.csv")
    dx1, dx2, mu = mesh["dx1_m"][0], mesh["dx2_m"][0], mesh["mu"][0]
    files = sorted(d.glob("tractions_*.csv"))
    order = ["nh-fastsim", "fastsim", "exact", "exact-regularised"]
    files.sort(key=lambda f: order.index(f.stem[len("tractions_"):]) if f.stem[len("tractions_"):] in order else 9)
    n = len(files) + 1
    fig, axes = plt.subplots(1, n, figsize=(3.6 * n, 3.8), sharey=True)
    p = read(d / "patch.csv")
    g, extent = grid(p["x1_m"], p["x2_m"], 1e-6 * p["p3_Pa"], dx1, dx2)
    im = axes[0].imshow(g, origin="lower", extent=extent, aspect="equal", cmap="viridis")
    axes[0].set_title("pressure p3 (MPa)")
    fig.colorbar(im, ax=axes[0], shrink=0.8)
    vmax = 1e-6 * mu * p["p3_Pa"].max()
    for ax, f in zip(axes[1:], files):
        t = read(f)
        g, extent = grid(t["x1_m"], t["x2_m"], 1e-6 * t["p_abs_Pa"], dx1, dx2)
        im = ax.imshow(g, origin="lower", extent=extent, aspect="equal", cmap="magma", vmin=0, vmax=vmax)
        s, _ = grid(t["x1_m"], t["x2_m"], t["slip"], dx1, dx2)
        slip = np.where(np.isnan(s), 0.0, s)
        ax.contourf(slip, levels=[0.5, 1.5], colors="none", hatches=["////"], extent=extent, origin="lower")
        ax.contour(slip, levels=[0.5], colors="cyan", linewidths=0.8, extent=extent, origin="lower")
        share = 100 * (1 - t["slip"].mean())
        ax.set_title(f"{f.stem[len('tractions_'):]}: |p| (MPa)\nadhesion {share:.0f}%, slip hatched", fontsize=9)
        fig.colorbar(im, ax=ax, shrink=0.8)
    for ax in axes:
        ax.set_xlabel("x1 (mm), rolling ->")
    axes[0].set_ylabel("x2 (mm)")
    fig.tight_layout()
    fig.savefig(d / "tractions.png", dpi=120)


if __name__ == "__main__":
    main()
