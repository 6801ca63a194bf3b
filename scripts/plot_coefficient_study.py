#!/usr/bin/env python3
"""Figures of `railcontact study coefficients` (paper §3) from the CSV files in DIR."""
import csv
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def ratio_label(r):
    return f"a/b = {r:g}" if r >= 1 else f"a/b = {r:.1f}"


def fig3(d):
    rows = read(d / "fig3.csv")
    fig, axes = plt.subplots(1, 3, figsize=(13, 4), sharex=True)
    ratios = sorted({float(r["a_over_b"]) for r in rows})
    for k, name in enumerate(["C11", "C22", "C23"]):
        ax = axes[k]
        for ratio in ratios:
            pts = [(float(r["alpha"]), 100 * float(r["err_" + name])) for r in rows
                   if float(r["a_over_b"]) == ratio and r["err_" + name] != "nan"]
            ax.plot(*zip(*pts), marker="o", ms=3, label=ratio_label(ratio))
        ax.axhline(0, color="k", lw=0.5)
        ax.set_title(f"{name}")
        ax.set_xlabel("collocation offset alpha")
        ax.set_ylabel("relative error (%)")
        ax.set_ylim(-6, 6)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("Fig 3: error of the creepage coefficients vs collocation point (80 x 80 mesh, nu = 0.25)")
    fig.tight_layout()
    fig.savefig(d / "fig3.png", dpi=120)


def fig4(d):
    rows = read(d / "fig4.csv")
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5), sharex=True)
    ratios = sorted({float(r["a_over_b"]) for r in rows})
    for i, config in enumerate(["paper", "railcontact"]):
        for k, name in enumerate(["C11", "C22", "C23"]):
            ax = axes[i][k]
            for ratio in ratios:
                pts = [(int(r["elements"]), 100 * float(r["err_" + name])) for r in rows
                       if r["config"] == config and float(r["a_over_b"]) == ratio]
                ax.plot(*zip(*pts), marker="o", ms=3, label=ratio_label(ratio))
            ax.axhline(0, color="k", lw=0.5)
            ax.set_xscale("log")
            ax.set_ylim(-4, 6)
            ax.grid(alpha=0.3, which="both")
            ax.set_title(f"{name} ({config})")
            if i == 1:
                ax.set_xlabel("elements in contact")
            ax.set_ylabel("relative error (%)")
    axes[0][0].legend(fontsize=8)
    fig.suptitle("Fig 4: error vs mesh size. Top: the paper's set-up (n x n mesh, alpha = 0, c = sqrt(ab)); "
                 "bottom: rolling-resolved mesh, alpha_spin = 0.5, c from the discrete area", fontsize=9)
    fig.tight_layout()
    fig.savefig(d / "fig4.png", dpi=120)


def table_figure(d):
    tables = [("table1_paper.csv", "paper set-up"), ("table1.csv", "railcontact defaults"),
              ("table1_fine.csv", "refined")]
    tables = [(f, t) for f, t in tables if (d / f).exists()]
    fig, axes = plt.subplots(1, 3, figsize=(13, 4), sharey=True)
    for k, name in enumerate(["C11", "C22", "C23"]):
        ax = axes[k]
        for f, title in tables:
            rows = read(d / f)
            for nu, marker in [("0.00", "o"), ("0.25", "s"), ("0.50", "^")]:
                pts = [(float(r["a_over_b"]), 100 * abs(float(r["err_" + name]))) for r in rows if r["nu"] == nu]
                ax.plot(*zip(*pts), marker=marker, ms=3, lw=0.8,
                        label=f"{title}, nu = {nu}" if k == 0 else None)
        ax.set_xscale("log")
        ax.set_title(f"|error| of {name} vs Kalker's table")
        ax.set_xlabel("a/b")
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("relative error (%)")
    fig.legend(loc="lower center", ncol=3, fontsize=7)
    fig.tight_layout(rect=(0, 0.15, 1, 1))
    fig.savefig(d / "table1.png", dpi=120)


def main():
    d = Path(sys.argv[1])
    fig3(d)
    fig4(d)
    table_figure(d)


if __name__ == "__main__":
    main()
