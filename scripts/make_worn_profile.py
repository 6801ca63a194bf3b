#!/usr/bin/python3
"""Writes a worn wheel or rail profile: a shipped new profile with material taken off by a stated
wear shape, in the new profile's format and frame (docs/GEOMETRY.md §1; lengths in mm).

Usage: /usr/bin/python3 scripts/make_worn_profile.py WEAR OUTPUT
       WEAR: gauge-corner (60E1 rail head, writes a .prr) or hollow (S1002 wheel, writes a .prw)

Both wear shapes take off a depth that follows a cos² bump over a coordinate u along the profile,

    d(u) = D cos²(π (u − u_c) / W)   for |u − u_c| ≤ W/2,    d(u) = 0 elsewhere,

largest (D) at the centre u_c, zero with zero slope at the band's ends u_c ± W/2.

gauge-corner: the upright 60E1 head of scripts/make_rail_profile.py (data/profiles/UIC60_upright.prr;
origin at the top of the crown on the rail's axis, y to the field side, z down) with gauge-corner
wear. u is the arc length along the new head from the top on the rail's axis (y = 0) towards the
gauge side (-y); the material is taken off along the surface normal, into the head:

    D = 2.2 mm,  u_c = 39 mm,  W = 36 mm   (the band u = 21 ... 57 mm)

The centre lies on the R13 gauge corner at y = -35.22 mm, z = 10.46 mm (where the surface leans
65.4 degrees from the horizontal); the band begins on the crown's R80 at y = -20.93 mm (vertical
wear 0.29 mm at y = -25 mm) and ends on the 1:20 flank 28.35 mm below the top, above the flank's
written end at 30 mm. Side wear, the lateral retreat of the gauge face 14 mm below the top: 2.01
mm. The top of the crown and the field side are untouched. The worn gauge side is sampled every
0.1 mm of its own arc length (the offset curve resampled, each point on the exact offset of the
EN 13674-1 arcs); the field side (y >= 0) is the new head's points. The script checks that y rises
strictly from the first point to the last (a single-valued z(y), so no self-intersection).

hollow: the S1002 wheel of the Manchester contact benchmark (data/profiles/MBench_S1002_v3.prw,
SIMPACK, mirror.y = 1, inversion = 1) with tread hollowing. In the file's own columns the flange is
at +y and the field side at -y; the reader's mirror.y turns that into the profile frame (flange at
-y). The taping line is at y = 0 in both (the flange back at +70 mm in the file's columns, its
commented-out first point; -70 mm in the profile frame). u is the lateral coordinate of the profile
frame (u = -y of the file's columns) and the material is taken off radially (z of each point,
radius outwards, reduced by d; y kept):

    D = 2.0 mm,  u_c = +5 mm,  W = 56 mm   (the band u = -23 ... +33 mm)

the centre 5 mm field-side of the taping line (-5 mm in the file's columns), the band over the
tread: it ends 3 mm tread-side of y = -26 mm, where S1002's tread curve meets its flange root, so
the flange is untouched, and on the field side at +33 mm, near the end of the tread curve (+32.16
mm). The hollow's bottom is at y = +6.27 mm, its radius 2.15 mm below the new wheel's at the
taping line; field-side of it the worn tread rises to a false flange whose crest, at y = +28.96
mm, stands 1.45 mm proud of the bottom (radially). The taping line loses 1.85 mm. Points outside
the band are copied as written, header and trailer as in the new file but for the file name, the
comment and the lines naming this script.

Standard library only.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_rail_profile  # noqa: E402  (the new 60E1 head, same directory)

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
S1002_FILE = os.path.join(ROOT, "data", "profiles", "MBench_S1002_v3.prw")

# (largest depth D, centre u_c, band width W) in mm, as the docstring states them.
GAUGE_CORNER = (2.2, 39.0, 36.0)
HOLLOW = (2.0, 5.0, 56.0)
DENSE_STEP_MM = 0.001  # the offset curve's arc length is summed over chords this long


def depth(u, wear):
    largest, centre, width = wear
    x = u - centre
    return largest * math.cos(math.pi * x / width) ** 2 if abs(x) <= width / 2.0 else 0.0


def head_at(u, pieces, flank):
    """Point (y, z) and unit tangent of the new head's field-side half at arc length u from the top."""
    for yc, zc, radius, ta, tb in pieces:
        length = radius * (tb - ta)
        if u <= length:
            t = ta + u / radius
            return (yc + radius * math.sin(t), zc - radius * math.cos(t)), (math.cos(t), math.sin(t))
        u -= length
    y0, z0, direction, _ = flank
    return (y0 + u * direction[0], z0 + u * direction[1]), direction


def gauge_corner_worn():
    """The worn 60E1 head from the gauge side (-y) to the field side (+y)."""
    pieces, flank = make_rail_profile.head_pieces("60E1")
    total = sum(radius * (tb - ta) for _, _, radius, ta, tb in pieces) + flank[3]

    # The wear is worked out on the field-side half (the head is symmetric) and mirrored: the
    # inward normal of a tangent (ty, tz) there is (-tz, ty) (z down, the head below and inside).
    def worn(u):
        (y, z), (ty, tz) = head_at(u, pieces, flank)
        d = depth(u, GAUGE_CORNER)
        return y - d * tz, z + d * ty

    count = int(round(total / DENSE_STEP_MM))
    dense_u = [total * k / count for k in range(count + 1)]
    dense = [worn(u) for u in dense_u]
    length = [0.0]
    for a, b in zip(dense, dense[1:]):
        length.append(length[-1] + math.hypot(b[0] - a[0], b[1] - a[1]))
    half = []
    k = 0
    step = 0
    while step * make_rail_profile.STEP_MM <= length[-1] + 1e-9:
        target = min(step * make_rail_profile.STEP_MM, length[-1])
        while k + 1 < count and length[k + 1] < target:
            k += 1
        f = (target - length[k]) / (length[k + 1] - length[k])
        half.append(worn(dense_u[k] + f * (dense_u[k + 1] - dense_u[k])))
        step += 1
    points = [(-y, z) for y, z in reversed(half[1:])] + make_rail_profile.half_profile("60E1")
    for i, (a, b) in enumerate(zip(points, points[1:])):
        if not b[0] > a[0]:
            raise SystemExit(f"make_worn_profile.py: the worn head turns back at point {i + 1} "
                             f"(y = {a[0]:.6f} mm, z = {a[1]:.6f} mm): not a single-valued z(y)")
    return points


def write_gauge_corner(path):
    largest, centre, width = GAUGE_CORNER
    points = gauge_corner_worn()  # before the file is opened: a refused head leaves no file
    with open(path, "w", encoding="ascii") as out:
        out.write("! 60E1 rail head (EN 13674-1), upright (no inclination), with gauge-corner wear, written by\n")
        out.write("! scripts/make_worn_profile.py gauge-corner from the head of scripts/make_rail_profile.py 60E1:\n")
        out.write(f"! depth {largest} cos^2(pi (u - {centre}) / {width}) mm along the normal for |u - {centre}| <= "
                  f"{width / 2.0} mm,\n")
        out.write("! u the arc length from the top on the axis towards the gauge side (-y); 0.1 mm arc steps.\n")
        out.write("! Origin on the rail's axis at the top of the crown, y to the field side, z down (mm).\n")
        make_rail_profile.write_prr_body(out, "60E1 upright, gauge-corner wear 2.2 mm (side wear 2.0 mm at 14 mm)",
                                         points)


def write_hollow(path):
    largest, centre, width = HOLLOW
    with open(S1002_FILE, encoding="ascii") as f:
        lines = f.read().split("\n")
    out_lines = []
    in_points = False
    for line in lines:
        text = line.strip()
        if text.startswith("! File Name"):
            line = "! File Name      : " + os.path.basename(path)
        elif text.startswith("! Creation Date"):
            line = ("! Written by     : scripts/make_worn_profile.py hollow, from MBench_S1002_v3.prw: radial wear\n"
                    f"!                  {largest} cos^2(pi (u - {centre}) / {width}) mm for |u - {centre}| <= "
                    f"{width / 2.0} mm,\n"
                    "!                  u = -y of the columns below (the profile frame's y, taping line at 0)")
        elif text.startswith("comment "):
            head, _, tail = line.partition("'")
            _, _, rest = tail.partition("'")
            line = head + "'S1002 wheel profile v3 for Manchester Contact Benchmark, tread hollowed 2 mm'" + rest
        elif text == "point.begin":
            in_points = True
        elif text == "point.end":
            in_points = False
        elif in_points and text and not text.startswith("!"):
            y_text, z_text = text.split("\t")
            d = depth(-float(y_text), HOLLOW)
            if d > 0.0:
                line = f"{y_text}\t{float(z_text) - d:.7E}"
        out_lines.append(line)
    with open(path, "w", encoding="ascii") as out:
        out.write("\n".join(out_lines))


WEARS = {"gauge-corner": write_gauge_corner, "hollow": write_hollow}


def main(argv):
    if len(argv) != 3 or argv[1] not in WEARS:
        sys.stderr.write(__doc__.split("\n\n")[1] + "\n")
        return 2
    WEARS[argv[1]](argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
