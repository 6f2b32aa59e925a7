#!/usr/bin/env python3
"""Writes a flat-bottomed cylindrical silo as a gmsh 2.2 surface mesh: a
cylinder of radius R from z = 0 to z = H about the z axis, and a bottom at
z = 0 with a central circular orifice of diameter D (open at the top and at
the orifice), n segments around; the bottom is cut into rings of about equal
width between D/2 and R.
Usage: make_hopper_mesh.py R H D n output.msh
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gmsh_surface import write_msh  # noqa: E402

R, H, D = (float(a) for a in sys.argv[1:4])
n = int(sys.argv[4])
name = sys.argv[5]
rings = max(1, int(round((R - D / 2) / (2 * math.pi * R / n))))
nodes, triangles = [], []


def ring(radius, z):
    first = len(nodes) + 1
    for k in range(n):
        a = 2 * math.pi * k / n
        nodes.append((radius * math.cos(a), radius * math.sin(a), z))
    return first


def band(a, b):
    """Triangles between two rings of n nodes (first node numbers a and b)."""
    for k in range(n):
        k1 = (k + 1) % n
        triangles.append((a + k, a + k1, b + k))
        triangles.append((a + k1, b + k1, b + k))


radii = [D / 2 + (R - D / 2) * j / rings for j in range(rings + 1)]
firsts = [ring(r, 0.0) for r in radii]
for a, b in zip(firsts, firsts[1:]):
    band(a, b)
top = ring(R, H)
band(firsts[-1], top)
write_msh(name, nodes, triangles)
