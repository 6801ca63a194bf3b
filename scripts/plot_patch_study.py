#!/usr/bin/env python3
"""Figures of `railcontact study patches` from DIR/patches.csv and DIR/patch_y*mm.csv:
contact_position.png (contact position on rail and wheel, contact angle, against y),
patch_size.png (area and maximum pressure against Hertz), patch_shapes.png (the pressure maps)."""
import csv
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot_patch import draw_patch, read_elements  # noqa: E402


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def value(row, key, scale=1.0):
    text = row.get(key, "")
    return float(text) * scale if text not in ("", "nan") else math.nan


def solved(rows):
    return [r for r in rows if r["status"] != "error"]


def marked(ax, rows, xs, ys, **style):
    """Line through all solved points; several-patch positions get a red ring."""
    ax.plot(xs, ys, **style)
    several = [(x, y) for r, x, y in zip(rows, xs, ys) if r["status"] == "several_patches"]
    if several:
        ax.plot(*zip(*several), ls="none", marker="o", mfc="none", mec="r", ms=10, label="several patches")


def contact_position(d, rows):
    rows = solved(rows)
    y = [value(r, "y_m", 1e3) for r in rows]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    ax = axes[0]
    marked(ax, rows, y, [value(r, "y_rail_m", 1e3) for r in rows], marker="o", ms=4, label="first touch")
    ax.plot(y, [value(r, "centre_y_rail_m", 1e3) for r in rows], marker="x", ms=5, ls="--", label="centre of pressure")
    ax.set_title("contact position on the rail")
    ax.set_ylabel("y_rail (mm, rail profile frame; < 0 gauge side)")
    ax = axes[1]
    marked(ax, rows, y, [value(r, "y_wheel_m", 1e3) for r in rows], marker="o", ms=4, label="first touch")
    ax.plot(y, [value(r, "centre_y_wheel_m", 1e3) for r in rows], marker="x", ms=5, ls="--", label="centre of pressure")
    ax.set_title("contact position on the wheel")
    ax.set_ylabel("y_wheel (mm from the taping line; < 0 flange side)")
    ax = axes[2]
    marked(ax, rows, y, [value(r, "contact_angle_rad") for r in rows], marker="o", ms=4, label="gamma (first touch)")
    ax.plot(y, [value(r, "centre_contact_angle_rad") for r in rows], marker="x", ms=5, ls="--",
            label="rail slope at the centre of pressure")
    ax.set_title("contact angle")
    ax.set_ylabel("gamma (rad)")
    for ax in axes:
        ax.set_xlabel("wheelset lateral displacement y (mm; < 0 towards the flange)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("S1002 on UIC60 1:40: contact position and angle (right wheel)")
    fig.tight_layout()
    fig.savefig(d / "contact_position.png", dpi=120)


def patch_size(d, rows):
    rows = solved(rows)
    y = [value(r, "y_m", 1e3) for r in rows]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    ax = axes[0]
    marked(ax, rows, y, [value(r, "area_m2", 1e6) for r in rows], marker="o", ms=4, label="normal solution")
    ax.plot(y, [value(r, "hertz_area_m2", 1e6) for r in rows], marker="x", ls="--", label="Hertz, local curvatures")
    ax.set_ylabel("contact area (mm2)")
    ax = axes[1]
    marked(ax, rows, y, [value(r, "max_pressure_Pa", 1e-6) for r in rows], marker="o", ms=4, label="normal solution")
    ax.plot(y, [value(r, "hertz_max_pressure_Pa", 1e-6) for r in rows], marker="x", ls="--",
            label="Hertz, local curvatures")
    ax.set_ylabel("maximum pressure (MPa)")
    ax = axes[2]
    ax.plot(y, [value(r, "extent_x1_m", 1e3) for r in rows], marker="o", ms=4, label="extent along X1")
    ax.plot(y, [value(r, "extent_x2_m", 1e3) for r in rows], marker="s", ms=4, label="extent along X2")
    ax.set_ylabel("patch extent (mm)")
    for ax in axes:
        ax.set_xlabel("wheelset lateral displacement y (mm)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Patch size and maximum pressure against Hertz for the local curvatures (F3 = Fz / cos gamma)")
    fig.tight_layout()
    fig.savefig(d / "patch_size.png", dpi=120)


def patch_shapes(d, rows):
    rows = [r for r in solved(rows) if r["patch_file"]]
    if not rows:
        return
    patches = [(r, read_elements(d / r["patch_file"])) for r in rows]
    vmax = max(p for _, els in patches for _, _, p in els) * 1e-6
    half1 = max(max(abs(e[0]) for e in els) + value(r, "dx1_m") for r, els in patches) * 1e3
    half2 = max(max(abs(e[1]) for e in els) + value(r, "dx2_m") for r, els in patches) * 1e3
    columns = min(5, len(patches))
    lines = math.ceil(len(patches) / columns)
    fig, axes = plt.subplots(lines, columns, figsize=(2.5 * columns + 1.2, 2.3 * half2 / half1 * lines + 1.0),
                             squeeze=False, layout="constrained")
    image = None
    for k, (r, els) in enumerate(patches):
        ax = axes[k // columns][k % columns]
        image = draw_patch(ax, els, value(r, "dx1_m"), value(r, "dx2_m"), vmax=vmax, colorbar=False)
        ax.set_xlim(-half1, half1)
        ax.set_ylim(-half2, half2)
        note = "" if r["status"] == "single" else f" ({r['patches']} patches!)"
        ax.set_title(f"y = {value(r, 'y_m', 1e3):+.1f} mm{note}\ngamma {value(r, 'contact_angle_rad'):.3f}, "
                     f"{value(r, 'max_pressure_Pa', 1e-6):.0f} MPa", fontsize=8)
        ax.tick_params(labelsize=7)
    for k in range(len(patches), lines * columns):
        axes[k // columns][k % columns].axis("off")
    fig.supxlabel("x1 (mm), rolling direction")
    fig.supylabel("x2 (mm), to the gauge side")
    fig.suptitle("Contact patches and pressure (origin: centre of pressure)")
    fig.colorbar(image, ax=axes, label="pressure p3 (MPa)", shrink=0.6)
    fig.savefig(d / "patch_shapes.png", dpi=110)


def main(d):
    rows = read_rows(d / "patches.csv")
    contact_position(d, rows)
    patch_size(d, rows)
    patch_shapes(d, rows)


if __name__ == "__main__":
    main(Path(sys.argv[1]))
