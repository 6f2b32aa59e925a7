#!/usr/bin/env python3
"""Writes mill.stl: a closed mill shell with lifter bars, for the wet mill
(prm/sph-dem/wet_mill.prm). A cylinder of radius R about the y axis from
y = 0 to y = L whose cross-section carries n_lifters rectangular bars, each
w wide and protruding h from the shell towards the axis (the bar's inner face
at distance R - h from the axis), evenly spaced from the angle 0 (the +x
axis, angles counted from x towards z). The section is star-shaped about the
axis, so each end cap is a fan of triangles about its centre; the shell's arcs
between the bars are cut into segments of at most 2 pi / n_arc. Normals point
into the mill (the side the particles are on), as in make_drum_mesh.py.
ASCII STL, metres.
Usage: make_mill_mesh.py [R L n_lifters h w n_arc [output file]]
"""
import math
import sys

R = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
L = float(sys.argv[2]) if len(sys.argv) > 2 else 0.04
n_lifters = int(sys.argv[3]) if len(sys.argv) > 3 else 8
h = float(sys.argv[4]) if len(sys.argv) > 4 else 0.005
w = float(sys.argv[5]) if len(sys.argv) > 5 else 0.005
n_arc = int(sys.argv[6]) if len(sys.argv) > 6 else 96
name = sys.argv[7] if len(sys.argv) > 7 else "mill.stl"


def section():
    """The cross-section's corners (x, z), counter-clockwise in (x, z)."""
    points = []
    half = math.asin(0.5 * w / R)  # the bar's half-width as an angle on the shell
    outer = math.sqrt(R * R - 0.25 * w * w)
    for k in range(n_lifters):
        a = 2 * math.pi * k / n_lifters
        er, et = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
        corner = lambda s, t: (s * er[0] + t * et[0], s * er[1] + t * et[1])
        # The bar: up its first side, across its face, down its second side.
        points += [corner(outer, -0.5 * w), corner(R - h, -0.5 * w),
                   corner(R - h, 0.5 * w), corner(outer, 0.5 * w)]
        # The arc to the next bar.
        a0, a1 = a + half, a + 2 * math.pi / n_lifters - half
        n = max(1, math.ceil((a1 - a0) / (2 * math.pi / n_arc)))
        points += [(R * math.cos(a0 + (a1 - a0) * i / n), R * math.sin(a0 + (a1 - a0) * i / n))
                   for i in range(1, n)]
    return points


def facet(out, a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n))
    out.write("facet normal %.9g %.9g %.9g\n outer loop\n" % tuple(x / length for x in n))
    for p in (a, b, c):
        out.write("  vertex %.17g %.17g %.17g\n" % p)
    out.write(" endloop\nendfacet\n")


poly = section()
m = len(poly)
at = lambda k, y: (poly[k % m][0], y, poly[k % m][1])
with open(name, "w") as out:
    out.write("solid mill\n")
    for k in range(m):
        # The shell (or a bar's side or face) between corners k and k + 1.
        facet(out, at(k, 0.0), at(k + 1, 0.0), at(k, L))
        facet(out, at(k + 1, 0.0), at(k + 1, L), at(k, L))
        # The end caps, fans about the axis.
        facet(out, (0.0, 0.0, 0.0), at(k + 1, 0.0), at(k, 0.0))
        facet(out, (0.0, L, 0.0), at(k, L), at(k + 1, L))
    out.write("endsolid mill\n")
print("%s: %d corners, %d triangles" % (name, m, 4 * m))
