#!/usr/bin/env python3
"""Writes a closed box [0, Lx] x [0, Ly] x [0, Lz] as a gmsh 2.2 surface mesh:
each face cut into n x n cells of two triangles (n = 1: the 12-triangle box).
Usage: make_box_mesh.py Lx Ly Lz n output.msh
"""
import sys

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
with open(name, "w") as out:
    out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
    for k, p in enumerate(nodes):
        out.write("%d %.17g %.17g %.17g\n" % (k + 1, p[0], p[1], p[2]))
    out.write("$EndNodes\n$Elements\n%d\n" % len(triangles))
    for k, t in enumerate(triangles):
        out.write("%d 2 2 1 1 %d %d %d\n" % (k + 1, t[0], t[1], t[2]))
    out.write("$EndElements\n")
