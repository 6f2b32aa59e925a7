#!/usr/bin/env python3
"""Writes floor.msh, the triangulated plane z = 0 of mesh_plane_equivalence.prm.

A rectangle [-0.05, 0.05] x [-0.3, 0.3] m cut by grid lines of very uneven
spacing (0.5 mm to 40 mm, so triangle areas differ by four orders of
magnitude), each cell split into two triangles along alternating diagonals.
The line x = 0 is a grid line: a sphere sliding along it stays over edges and
passes a vertex at every y line. gmsh ASCII format 2.2, 3-node triangles.
Usage: make_floor_mesh.py [output file]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gmsh_surface import write_msh  # noqa: E402

xs = [-0.05, -0.03, -0.012, 0.0, 0.0005, 0.004, 0.03, 0.05]
ys = [-0.3]
step = 0.0005
while ys[-1] < 0.3 - 1e-12:
    # Grow the spacing to 40 mm and back down, twice over the length.
    ys.append(min(0.3, ys[-1] + step))
    step = step * 2.5 if len(ys) % 10 < 5 else max(0.0005, step / 2.5)
    step = min(step, 0.04)

nodes = [(x, y) for y in ys for x in xs]
triangles = []
nx = len(xs)
for j in range(len(ys) - 1):
    for i in range(nx - 1):
        a, b = j * nx + i, j * nx + i + 1
        c, d = a + nx, b + nx
        if (i + j) % 2 == 0:
            triangles += [(a, b, d), (a, d, c)]
        else:
            triangles += [(a, b, c), (b, d, c)]

write_msh(sys.argv[1] if len(sys.argv) > 1 else "floor.msh",
          [(x, y, 0.0) for x, y in nodes], [(a + 1, b + 1, c + 1) for a, b, c in triangles])
