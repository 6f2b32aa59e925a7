#!/usr/bin/env python3
"""Writes drum.msh: the closed drum of ../shared/peers/liggghts/drum.in (the
geometry of its drum.stl): a cylinder of radius R = 0.05 m about the y axis
from y = 0 to y = L = 0.03 m, n = 96 segments around, its shell cut into two
triangles per segment and each end cap into a fan of n triangles about the
axis (384 triangles). gmsh ASCII format 2.2, 3-node triangles.
Usage: make_drum_mesh.py [R L n [output file]]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gmsh_surface import write_msh  # noqa: E402

R = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
L = float(sys.argv[2]) if len(sys.argv) > 2 else 0.03
n = int(sys.argv[3]) if len(sys.argv) > 3 else 96
name = sys.argv[4] if len(sys.argv) > 4 else "drum.msh"

# Nodes: the rim at y = 0 (1..n), the rim at y = L (n+1..2n), the two centres.
nodes = []
for y in (0.0, L):
    for k in range(n):
        a = 2 * math.pi * k / n
        nodes.append((R * math.cos(a), y, R * math.sin(a)))
nodes += [(0.0, 0.0, 0.0), (0.0, L, 0.0)]
rim0 = lambda k: k % n + 1
rim1 = lambda k: n + k % n + 1
c0, c1 = 2 * n + 1, 2 * n + 2
triangles = []
for k in range(n):
    triangles += [(rim0(k), rim0(k + 1), rim1(k)), (rim0(k + 1), rim1(k + 1), rim1(k)),
                  (c0, rim0(k + 1), rim0(k)), (c1, rim1(k), rim1(k + 1))]

write_msh(name, nodes, triangles)
