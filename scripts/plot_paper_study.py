#!/usr/bin/env python3
"""Figures of `railcontact study paper` (the paper's Fig 5-8) from the CSV files in DIR."""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def fig5(d):
    rows = read(d / "fig5.csv")
    titles = {"A": "(A) pure xi'", "B": "(B) eta' with spin", "C": "(C) xi' = eta' with spin"}
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.3), sharey=True)
    levels = sorted({r["xi_n"] if r["family"] != "B" else r["eta_n"] for r in rows}, key=float)
    colors = plt.cm.viridis(np.linspace(0, 0.9, 5))
    for ax, family in zip(axes, "ABC"):
        # nh-fastsim-default: in the CSV only
        for solver, line in [("nh-fastsim", "-"), ("nh-fastsim-paper", "--"), ("fastsim", ":")]:
            for color, level in zip(colors, [0.1, 0.25, 0.5, 0.75, 1.0]):
                key = "eta_n" if family == "B" else "xi_n"
                pts = sorted((1e3 * float(r["y"]), 100 * float(r["rel_error"])) for r in rows
                             if r["family"] == family and r["solver"] == solver and abs(float(r[key]) - level) < 1e-9)
                if pts:
                    ax.plot(*zip(*pts), line, color=color, marker="o" if solver == "nh-fastsim" else None, ms=3,
                            label=f"{solver}, {level}" if family == "A" else None)
        ax.set_title(titles[family])
        ax.set_xlabel("wheelset lateral displacement y (mm)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("|F - F_exact| / F_exact (%)")
    axes[0].legend(fontsize=6, ncol=2)
    fig.suptitle("Fig 5: total tangential force error: railcontact's nH-FastSim (solid), the paper's nH-FastSim "
                 "(parabolic bound, dashed), equivalent-ellipse FastSim (dotted)")
    fig.tight_layout()
    fig.savefig(d / "fig5.png", dpi=110)


def grid(x1, x2, values):
    dx1 = np.min(np.diff(np.unique(x1))) if len(np.unique(x1)) > 1 else 1
    dx2 = np.min(np.diff(np.unique(x2))) if len(np.unique(x2)) > 1 else 1
    i1 = np.rint((x1 - x1.min()) / dx1).astype(int)
    i2 = np.rint((x2 - x2.min()) / dx2).astype(int)
    g = np.full((i2.max() + 1, i1.max() + 1), np.nan)
    g[i2, i1] = values
    return g, (1e3 * (x1.min() - dx1 / 2), 1e3 * (x1.max() + dx1 / 2), 1e3 * (x2.min() - dx2 / 2), 1e3 * (x2.max() + dx2 / 2))


def fig6(d):
    cases = [("A_xi0.5", "xi' = 0.5"), ("B_eta0.5_spin", "eta' = 0.5, spin"), ("C_xi0.5_eta0.5_spin", "xi' = eta' = 0.5, spin")]
    fig, axes = plt.subplots(2, 3, figsize=(12, 9), sharex=True, sharey=True)
    for j, (name, title) in enumerate(cases):
        for i, solver in enumerate(["nh-fastsim", "exact"]):
            rows = read(d / f"fig6_{name}_{solver}.csv")
            x1 = np.array([float(r["x1_m"]) for r in rows])
            x2 = np.array([float(r["x2_m"]) for r in rows])
            p = np.array([1e-6 * float(r["p_abs_Pa"]) for r in rows])
            slip = np.array([float(r["slip"]) for r in rows])
            g, extent = grid(x1, x2, p)
            s, _ = grid(x1, x2, slip)
            ax = axes[i][j]
            im = ax.imshow(g, origin="lower", extent=extent, cmap="magma", aspect="equal")
            ax.contourf(np.nan_to_num(s), levels=[0.5, 1.5], colors="none", hatches=["////"], extent=extent, origin="lower")
            ax.contour(np.nan_to_num(s), levels=[0.5], colors="cyan", linewidths=0.8, extent=extent, origin="lower")
            ax.set_title(f"{solver}: {title}\nadhesion {100 * (1 - slip.mean()):.0f}% (slip hatched)", fontsize=9)
            fig.colorbar(im, ax=ax, shrink=0.7, label="|p| (MPa)")
            if i == 1:
                ax.set_xlabel("x1 (mm), rolling ->")
            if j == 0:
                ax.set_ylabel("x2 (mm)")
    fig.suptitle("Fig 6: tangential tractions at y = 0, nH-FastSim (top) and exact (bottom)")
    fig.tight_layout()
    fig.savefig(d / "fig6.png", dpi=110)


def fig7(d):
    rows = read(d / "fig7.csv")
    fig, axes = plt.subplots(2, 2, figsize=(10, 8), sharex=True)
    for i, eta in enumerate(["0.0", "0.5"]):
        for j, y in enumerate(sorted({r["y"] for r in rows}, key=float)):
            ax = axes[i][j]
            for solver, style in [("exact", "k-o"), ("nh-fastsim", "r--s")]:
                pts = [(float(r["xi_n"]), -1e-3 * float(r["F1"])) for r in rows
                       if r["y"] == y and r["eta_n"] == eta and r["solver"] == solver]
                ax.plot(*zip(*pts), style, ms=3, label=solver)
            ax.set_title(f"y = {1e3 * float(y):.0f} mm, eta' = {eta}" + (" with spin" if eta != "0.0" else ""))
            ax.grid(alpha=0.3)
            ax.set_ylabel("-F1 (kN)")
            if i == 1:
                ax.set_xlabel("xi'")
    axes[0][0].legend()
    fig.suptitle("Fig 7: longitudinal creep curves")
    fig.tight_layout()
    fig.savefig(d / "fig7.png", dpi=110)


def fig8(d):
    rows = read(d / "fig8.csv")
    n = np.array([float(r["elements"]) for r in rows])
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    series = [("exact", "time_exact_s", None, "ko"),
              ("nH-FastSim as `run` computes it (coarsened flexibilities)", "time_nh_fastsim_default_s",
               "ratio_default", "rs"),
              ("nH-FastSim, flexibilities from the full patch", "time_nh_fastsim_full_resolution_s",
               "ratio_full_resolution", "gD"),
              ("nH-FastSim, flexibilities known", "time_nh_fastsim_flexibilities_known_s",
               "ratio_flexibilities_known", "b^")]
    for label, time_key, ratio_key, style in series:
        axes[0].loglog(n, [1e3 * float(r[time_key]) for r in rows], style, ms=4, label=label)
        if ratio_key:
            axes[1].loglog(n, [float(r[ratio_key]) for r in rows], style, ms=4, label="exact / " + label)
    axes[1].axhline(20, color="grey", ls="--", lw=1)
    axes[1].axhline(50, color="grey", ls=":", lw=1)
    axes[0].set_xlabel("elements in contact")
    axes[0].set_ylabel("time (ms), faster of two runs")
    axes[0].legend(fontsize=8)
    axes[0].grid(alpha=0.3, which="both")
    axes[1].set_xlabel("elements in contact")
    axes[1].set_ylabel("time ratio (20x target, 50x aim)")
    axes[1].legend(fontsize=8)
    axes[1].grid(alpha=0.3, which="both")
    fig.suptitle("Fig 8: computing time (random y and creepages, single thread)")
    fig.tight_layout()
    fig.savefig(d / "fig8.png", dpi=110)


def main():
    d = Path(sys.argv[1])
    fig5(d)
    fig6(d)
    fig7(d)
    fig8(d)


if __name__ == "__main__":
    main()
