#!/usr/bin/env python3
"""Writes granular_gas.csv: 512 spheres (radius 0.5 mm) on an 8 x 8 x 8 lattice
in a 16 mm box, with Gaussian velocities (0.5 m/s per component, the mean
removed so that the gas does not drift). The input of granular_gas_periodic.prm;
run from this directory to write it again."""
import random

random.seed(2026)
n, box, radius, sigma = 8, 0.016, 0.0005, 0.5
spacing = box / n
rows = []
for k in range(n):
    for j in range(n):
        for i in range(n):
            x = [(c + 0.5) * spacing + random.uniform(-0.2, 0.2) * (spacing - 2 * radius)
                 for c in (i, j, k)]
            rows.append((x, [random.gauss(0.0, sigma) for _ in range(3)]))
mean = [sum(v[d] for _, v in rows) / len(rows) for d in range(3)]
with open("granular_gas.csv", "w") as out:
    out.write("# x, y, z, radius, type, vx, vy, vz (make_granular_gas.py)\n")
    for x, v in rows:
        u = [v[d] - mean[d] for d in range(3)]
        out.write("%.6f, %.6f, %.6f, %g, 0, %.6f, %.6f, %.6f\n" % (*x, radius, *u))
