#!/usr/bin/env python3
"""Writes the square-duct pipe bend of slurry_bend.prm (the pump's wear case
of Gao & Sun §5.1 in miniature), twice from the same points:

  bend_fluid.msh  the fluid's hexahedra (gmsh 2.2, 8-node hexahedra; boundary
                  quadrilaterals tagged 1 inlet, 2 outlet, 3 wall), for
                  'fluid mesh/type = gmsh';
  bend_wall.msh   the duct's wall as triangles (two per wall quadrilateral,
                  open at the inlet and the outlet), for a mesh wall.

The duct has a square cross-section of side W; its centreline runs along +x
from the origin for L1, turns through 90 degrees about (L1, Rc) with
centreline radius Rc, and runs along +y for L2. Its cross-section spans
a in [-W/2, W/2] towards the centre of the bend and z in [-W/2, W/2].
Usage: make_bend_mesh.py [W Rc L1 L2 cells_across cells_leg1 cells_bend cells_leg2]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gmsh_surface import write_msh  # noqa: E402

args = [float(a) for a in sys.argv[1:5]] or [0.02, 0.03, 0.04, 0.06]
W, Rc, L1, L2 = args
cells = [int(a) for a in sys.argv[5:9]] or [4, 8, 8, 12]
n_across, n1, nb, n2 = cells


def centreline(i):
    """Point and inward normal at centreline station i (0..n1+nb+n2)."""
    if i <= n1:
        return (L1 * i / n1, 0.0), (0.0, 1.0)
    if i <= n1 + nb:
        phi = 0.5 * math.pi * (i - n1) / nb
        return (L1 + Rc * math.sin(phi), Rc - Rc * math.cos(phi)), (-math.sin(phi), math.cos(phi))
    return (L1 + Rc, Rc + L2 * (i - n1 - nb) / n2), (-1.0, 0.0)


n_s = n1 + nb + n2
nodes = []
for i in range(n_s + 1):
    (px, py), (nx, ny) = centreline(i)
    for k in range(n_across + 1):
        for j in range(n_across + 1):
            a = -0.5 * W + W * j / n_across
            z = -0.5 * W + W * k / n_across
            nodes.append((px + a * nx, py + a * ny, z))
node = lambda i, j, k: 1 + j + (n_across + 1) * (k + (n_across + 1) * i)

# Hexahedra with (s, a, z) right-handed, in gmsh's (= VTK's) node order.
hexes = []
for i in range(n_s):
    for k in range(n_across):
        for j in range(n_across):
            hexes.append([node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                          node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1),
                          node(i, j + 1, k + 1)])
# Boundary quadrilaterals: the ends, then the four walls.
quads = []
for i, tag in ((0, 1), (n_s, 2)):
    for k in range(n_across):
        for j in range(n_across):
            quads.append((tag, [node(i, j, k), node(i, j + 1, k), node(i, j + 1, k + 1),
                                node(i, j, k + 1)]))
walls = []
for i in range(n_s):
    for m in range(n_across):
        walls.append([node(i, 0, m), node(i + 1, 0, m), node(i + 1, 0, m + 1), node(i, 0, m + 1)])
        walls.append([node(i, n_across, m), node(i, n_across, m + 1), node(i + 1, n_across, m + 1),
                      node(i + 1, n_across, m)])
        walls.append([node(i, m, 0), node(i, m + 1, 0), node(i + 1, m + 1, 0), node(i + 1, m, 0)])
        walls.append([node(i, m, n_across), node(i + 1, m, n_across), node(i + 1, m + 1, n_across),
                      node(i, m + 1, n_across)])
quads += [(3, q) for q in walls]

here = os.path.dirname(os.path.abspath(__file__))
with open(os.path.join(here, "bend_fluid.msh"), "w") as out:
    out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
    for k, p in enumerate(nodes):
        out.write("%d %.17g %.17g %.17g\n" % (k + 1, p[0], p[1], p[2]))
    out.write("$EndNodes\n$Elements\n%d\n" % (len(quads) + len(hexes)))
    for k, (tag, q) in enumerate(quads):
        out.write("%d 3 2 %d %d %s\n" % (k + 1, tag, tag, " ".join(map(str, q))))
    for k, h in enumerate(hexes):
        out.write("%d 5 2 10 10 %s\n" % (len(quads) + k + 1, " ".join(map(str, h))))
    out.write("$EndElements\n")
# The wall's triangles, numbered on the nodes they use.
used = sorted({v for q in walls for v in q})
renumber = {v: k + 1 for k, v in enumerate(used)}
triangles = []
for q in walls:
    a, b, c, d = (renumber[v] for v in q)
    triangles += [(a, b, c), (a, c, d)]
write_msh(os.path.join(here, "bend_wall.msh"), [nodes[v - 1] for v in used], triangles)
print("bend_fluid.msh: %d hexahedra; bend_wall.msh: %d triangles" % (len(hexes), len(triangles)))
