#!/usr/bin/env python3
"""Writes a closed box [0, Lx] x [0, Ly] x [0, Lz] as a gmsh 2.2 surface mesh:
each face cut into n x n cells of two triangles (n = 1: the 12-triangle box).
Usage: make_box_mesh.py Lx Ly Lz n output.msh
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gmsh_surface import write_msh  # noqa: E402

L = [float(a) for a in sys.argv[1:4]]
n = int(sys.argv[4])
name = sys.argv[5]
nodes, index, triangles = [], {}, []


def node(p):
    key = tuple(round(c / L[k] * n) for k, c in enumerate(p))
    if key not in index:
        index[key] = len(nodes) + 1
        nodes.append(p)
    return index[key]


for axis in range(3):
    u, v = [k for k in range(3) if k != axis]
    for side in (0.0, L[axis]):
        for i in range(n):
            for j in range(n):
                corners = []
                for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    p = [0.0, 0.0, 0.0]
                    p[axis] = side
                    p[u] = L[u] * (i + di) / n
                    p[v] = L[v] * (j + dj) / n
                    corners.append(node(p))
                a, b, c, d = corners
                triangles += [(a, b, c), (a, c, d)]
write_msh(name, nodes, triangles)
