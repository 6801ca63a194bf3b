#!/usr/bin/python3
"""Writes the head of an upright EN 13674-1 Vignole rail as a SIMPACK rail profile (.prr).

Usage: /usr/bin/python3 scripts/make_rail_profile.py RAIL OUTPUT.prr
       RAIL: 60E1 (UIC 60) or 54E1 (UIC 54)

The rail head of EN 13674-1 is drawn from arcs joined tangentially, symmetric about the rail's
vertical axis: the crown R300, then R80, then R13, then the head's flank, a straight line leaning
out 1:20 from the vertical. The drawing gives the lateral width over which each crown arc runs:

    rail   R300 arc over   R80 arc over   R13 until the 1:20 flank   head width at the flank
    60E1   20.456 mm       52.053 mm      (tangent 1:20)             72 mm
    54E1   20.024 mm       49.727 mm      (tangent 1:20)             70 mm

(the head width is not an input: it follows from the arcs and is checked by
tests/rail_profile_generator_test.cpp). The flank is written down to 30 mm below the top of the
rail (the largest gauge measuring depth the project accepts), above the R3 fillet to the head's
underside; the rest of the section (underside, web, foot) never touches a wheel and is left out.

Profile frame as the project's rail profiles (docs/GEOMETRY.md §1): origin at the top of the
crown on the rail's axis, y lateral (the gauge side is -y), z down, in millimetres; the rail stands
upright (no inclination: give the track's rail cant with the set-up key track.rail_cant_rad).
Points are sampled every 0.1 mm of arc length, from the gauge side's flank over the crown to the
field side's flank. Standard library only.
"""
import math
import sys

# RAIL: (lateral width of the R300 arc, lateral width to the end of the R80 arc) in mm.
RAILS = {"60E1": (20.456, 52.053), "54E1": (20.024, 49.727)}
CROWN_RADIUS_MM = 300.0
SHOULDER_RADIUS_MM = 80.0
CORNER_RADIUS_MM = 13.0
FLANK_SLOPE = 1.0 / 20.0  # lateral per vertical
FLANK_DEPTH_MM = 30.0
STEP_MM = 0.1


def head_pieces(rail):
    """The field-side half (y >= 0) from the top on the axis outwards, as (arcs, flank): the arcs
    R300, R80, R13 as (centre y, centre z, radius, angle from, angle to), and the flank as (start y,
    start z, unit direction (dy, dz), length down to FLANK_DEPTH_MM)."""
    r300_width, r80_width = RAILS[rail]
    pieces = []  # (kind, data): arcs as (centre y, centre z, radius, angle from, angle to)
    # Angles are measured from the downward z axis towards +y: a point of a circle of radius R
    # about (yc, zc) at angle t is (yc + R sin t, zc - R cos t) (z down: the crown is above).
    t1 = math.asin(r300_width / 2.0 / CROWN_RADIUS_MM)
    pieces.append((0.0, CROWN_RADIUS_MM, CROWN_RADIUS_MM, 0.0, t1))
    # R80 tangent to R300 at t1: its centre lies on the same normal, 300 - 80 from the R300 centre.
    yc80 = (CROWN_RADIUS_MM - SHOULDER_RADIUS_MM) * math.sin(t1)
    zc80 = CROWN_RADIUS_MM - (CROWN_RADIUS_MM - SHOULDER_RADIUS_MM) * math.cos(t1)
    t2 = math.asin((r80_width / 2.0 - yc80) / SHOULDER_RADIUS_MM)
    pieces.append((yc80, zc80, SHOULDER_RADIUS_MM, t1, t2))
    # R13 tangent to R80 at t2, running until its tangent leans 1:20 out from the vertical (the
    # tangent at angle t is (cos t, sin t): down and outwards at t = 90 degrees - atan(1/20)).
    yc13 = yc80 + (SHOULDER_RADIUS_MM - CORNER_RADIUS_MM) * math.sin(t2)
    zc13 = zc80 - (SHOULDER_RADIUS_MM - CORNER_RADIUS_MM) * math.cos(t2)
    t3 = math.pi / 2.0 - math.atan(FLANK_SLOPE)
    pieces.append((yc13, zc13, CORNER_RADIUS_MM, t2, t3))
    # The flank: a straight line from the R13 end, leaning out 1:20 while going down.
    y0 = yc13 + CORNER_RADIUS_MM * math.sin(t3)
    z0 = zc13 - CORNER_RADIUS_MM * math.cos(t3)
    direction = (math.sin(math.atan(FLANK_SLOPE)), math.cos(math.atan(FLANK_SLOPE)))
    flank_length = (FLANK_DEPTH_MM - z0) / direction[1]
    return pieces, (y0, z0, direction, flank_length)


def half_profile(rail):
    """The field-side half (y >= 0) as a list of (y, z) from the top on the axis outwards."""
    pieces, (y0, z0, direction, flank_length) = head_pieces(rail)
    points = []
    carried = 0.0  # arc length already walked past the last sample
    for yc, zc, radius, ta, tb in pieces:
        length = radius * (tb - ta)
        s = carried
        while s < length:
            t = ta + s / radius
            points.append((yc + radius * math.sin(t), zc - radius * math.cos(t)))
            s += STEP_MM
        carried = s - length
    s = carried
    while s <= flank_length + 1e-9:
        points.append((y0 + s * direction[0], z0 + s * direction[1]))
        s += STEP_MM
    return points


def profile(rail):
    """The whole head, from the gauge side (-y) to the field side (+y)."""
    half = half_profile(rail)
    gauge_side = [(-y, z) for y, z in reversed(half[1:])]
    return gauge_side + half


def write_prr(path, rail, points):
    r300_width, r80_width = RAILS[rail]
    with open(path, "w", encoding="ascii") as out:
        out.write(f"! {rail} rail head (EN 13674-1), upright (no inclination), written by\n")
        out.write(f"! scripts/make_rail_profile.py {rail}: R300 over {r300_width} mm, R80 to {r80_width} mm,\n")
        out.write("! R13 to the 1:20 flank, arcs joined tangentially, a point every 0.1 mm of arc length.\n")
        out.write("! Origin on the rail's axis at the top of the crown, y to the field side, z down (mm).\n")
        write_prr_body(out, f"{rail} upright, generated from the EN 13674-1 head radii", points)


def write_prr_body(out, comment, points):
    """The SIMPACK rail profile after the leading comment lines: header, spline, points in mm."""
    out.write("header.begin\n  version = 1\n  type    = 0   ! 0 = rail profile\nheader.end\n")
    out.write("spline.begin\n")
    out.write(f"  comment     = '{comment}'\n")
    out.write("  units.len.f = 1000.\n  units.ang.f = 1.\n  point.begin\n")
    for y, z in points:
        out.write(f"    {y:12.6f} {z:12.6f}\n")
    out.write("  point.end\nspline.end\n")


def main(argv):
    if len(argv) != 3 or argv[1] not in RAILS:
        sys.stderr.write(__doc__.split("\n\n")[1] + "\n")
        return 2
    write_prr(argv[2], argv[1], profile(argv[1]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
