#!/usr/bin/env python3
"""Pressure map of `railcontact patch --out DIR`: DIR/pressure.csv (x1_m, x2_m, pressure_Pa per
contact element, contact frame, origin at the centre of pressure) and DIR/patch.json (element
sizes, title data) -> DIR/pressure.png with the patch outline (element edges). With
--contact-surface conformal or auto, patch.json lists the wheel's patches, each with its
pressure_K.csv (x2 along the developed surface): one map per patch."""
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402


def read_elements(path):
    with open(path, newline="") as f:
        return [(float(r["x1_m"]), float(r["x2_m"]), float(r["pressure_Pa"])) for r in csv.DictReader(f)]


def grid(elements, dx1, dx2):
    """Integer indices of the elements on their regular mesh and the mesh origin."""
    x1_0 = min(e[0] for e in elements)
    x2_0 = min(e[1] for e in elements)
    cells = {}
    for x1, x2, p in elements:
        cells[(round((x1 - x1_0) / dx1), round((x2 - x2_0) / dx2))] = p
    return cells, x1_0, x2_0


def outline_segments(cells, x1_0, x2_0, dx1, dx2, scale=1e3):
    """Element edges between a contact element and a non-contact neighbour (the staircase outline)."""
    segs = []
    for (i, j) in cells:
        xl, xr = x1_0 + (i - 0.5) * dx1, x1_0 + (i + 0.5) * dx1
        yb, yt = x2_0 + (j - 0.5) * dx2, x2_0 + (j + 0.5) * dx2
        if (i - 1, j) not in cells:
            segs.append([(xl, yb), (xl, yt)])
        if (i + 1, j) not in cells:
            segs.append([(xr, yb), (xr, yt)])
        if (i, j - 1) not in cells:
            segs.append([(xl, yb), (xr, yb)])
        if (i, j + 1) not in cells:
            segs.append([(xl, yt), (xr, yt)])
    return [[(a * scale, b * scale) for a, b in s] for s in segs]


def draw_patch(ax, elements, dx1, dx2, vmax=None, colorbar=True):
    """Pressure map (MPa) of one patch in mm, with its outline; returns the image."""
    cells, x1_0, x2_0 = grid(elements, dx1, dx2)
    n1 = max(i for i, _ in cells) + 1
    n2 = max(j for _, j in cells) + 1
    values = [[float("nan")] * n1 for _ in range(n2)]
    for (i, j), p in cells.items():
        values[j][i] = p * 1e-6
    x1_edges = [(x1_0 + (i - 0.5) * dx1) * 1e3 for i in range(n1 + 1)]
    x2_edges = [(x2_0 + (j - 0.5) * dx2) * 1e3 for j in range(n2 + 1)]
    image = ax.pcolormesh(x1_edges, x2_edges, values, cmap="viridis", vmin=0, vmax=vmax, shading="flat")
    ax.add_collection(LineCollection(outline_segments(cells, x1_0, x2_0, dx1, dx2), colors="k", linewidths=0.8))
    ax.plot([0], [0], marker="+", color="r", ms=8)
    ax.set_aspect("equal")
    if colorbar:
        plt.colorbar(image, ax=ax, label="pressure p3 (MPa)", shrink=0.85)
    return image


def main_patches(d, info):
    """One map per patch of a wheelset's wheel (the developed surface of a conformal patch)."""
    patches = [p for p in info["patches"] if (d / p["pressure_csv"]).exists()]
    if not patches:
        return
    fig, axes = plt.subplots(1, len(patches), figsize=(6.5 * len(patches), 6), squeeze=False)
    for ax, p in zip(axes[0], patches):
        draw_patch(ax, read_elements(d / p["pressure_csv"]), p["mesh"]["dx1_m"], p["mesh"]["dx2_m"])
        ax.set_xlabel("x1 (mm), rolling direction")
        ax.set_ylabel("x2 (mm)" + (", developed along the surface" if p["contact_surface"] == "conformal" else ""))
        ax.set_title(
            f"{p['contact_surface']} (weight {p['conformal_weight']:.2f}): gamma = {p['contact_angle_rad']:.4f} rad, "
            f"F3 = {p['normal_force_N'] / 1e3:.2f} kN\n"
            f"area {p['area_m2'] * 1e6:.1f} mm2, {p['elements_in_contact']} elements, "
            f"p max {p['max_pressure_Pa'] * 1e-6:.0f} MPa (+: centre of pressure)",
            fontsize=10)
        ax.grid(alpha=0.2)
    fig.suptitle(f"right wheel at y = {info['y'] * 1e3:.2f} mm, contact surface {info['contact_surface']}")
    fig.tight_layout()
    fig.savefig(d / "pressure.png", dpi=120)


def main(d):
    info = json.loads((d / "patch.json").read_text())
    if info.get("contact_surface", "planar") != "planar":  # a wheelset wheel's patches
        main_patches(d, info)
        return
    elements = read_elements(d / "pressure.csv")
    dx1, dx2 = info["mesh"]["dx1_m"], info["mesh"]["dx2_m"]
    aspect = info["extent_x2_m"] / info["extent_x1_m"]  # the map's height / width
    fig, ax = plt.subplots(figsize=(min(11.0, max(6.5, 2.5 + 5.0 / aspect)), 6))
    draw_patch(ax, elements, dx1, dx2)
    ax.set_xlabel("x1 (mm), rolling direction")
    ax.set_ylabel("x2 (mm), towards the flange / gauge side")
    ax.set_title(
        f"y = {info['y'] * 1e3:.2f} mm: gamma = {info['contact_angle_rad']:.4f} rad, "
        f"F3 = {info['normal_force_N'] / 1e3:.2f} kN\n"
        f"area {info['area_m2'] * 1e6:.1f} mm2, {info['elements_in_contact']} elements, "
        f"p max {info['max_pressure_Pa'] * 1e-6:.0f} MPa (+: centre of pressure)",
        fontsize=10)
    ax.grid(alpha=0.2)
    fig.tight_layout()
    fig.savefig(d / "pressure.png", dpi=120)


if __name__ == "__main__":
    main(Path(sys.argv[1]))
