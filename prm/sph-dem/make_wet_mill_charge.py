#!/usr/bin/env python3
"""Writes wet_mill_charge.csv: the charge of the wet mill (wet_mill.prm,
dry_mill.prm) as clump bodies, one row each: x, y, z, template, scale, type,
qw, qx, qy, qz, vx, vy, vz (insertion 'method = file' in a clump scene).

The mill (prm/geometry/make_mill_mesh.py): radius R = 0.05 m, length
L = 0.04 m, eight 5 mm lifter bars. Gao & Sun's (§5.3) fillings: the charge's
bulk volume 31.7% of the mill, the balls' 15.4%, at a bulk solid fraction of
0.6 (an assumption: a settled random packing of spheres and clumps):
  - balls (type 0, 7850 kg/m^3): diameters 8 and 6 mm, half the balls' mass each;
  - ore (type 1, 2700 kg/m^3), the rest of the solid volume, a third each:
    tetrahedral clumps (template 1: four spheres of radius 1.8 mm
    overlapping by a quarter of their diameter, volume-equivalent diameter
    5.5 mm), spheres of 5 mm and of 4 mm.
Template 0 is a sphere of radius 1 mm, scaled to each sphere's radius.
The bodies are placed by random sequential addition, largest first, each
wholly inside the circle the lifters' faces leave free (radius 44.5 mm, 0.5 mm
from the bars) and 0.5 mm from the end caps, not touching another; the
tetrahedra in random orientations. At rest: they fall into place when the
scene starts. Reproducible (seed 11).
Usage: make_wet_mill_charge.py [output file]
"""
import math
import random
import sys

R, L, LIFTER = 0.05, 0.04, 0.005
MARGIN = 0.0005
BULK_SOLID = 0.6
MILL_VOLUME = math.pi * R * R * L - 8 * LIFTER * LIFTER * L
name = sys.argv[1] if len(sys.argv) > 1 else "wet_mill_charge.csv"

# Template 1 at scale 1.5: members of radius 1.8 mm whose centres are an edge
# e = 2 r (1 - 0.25) apart; the body's volume is the union's (four spheres
# less the six lens-shaped overlaps); its bounding radius the circumradius
# e sqrt(6)/4 plus r.
r_t = 0.0018
e_t = 2 * r_t * 0.75
lens = math.pi * (4 * r_t + e_t) * (2 * r_t - e_t) ** 2 / 12  # two spheres' overlap
v_tetra = 4 * 4 / 3 * math.pi * r_t ** 3 - 6 * lens
bound_tetra = e_t * math.sqrt(6) / 4 + r_t


def ball(d):
    return math.pi / 6 * d ** 3


solid = 0.317 * MILL_VOLUME * BULK_SOLID
balls = 0.154 * MILL_VOLUME * BULK_SOLID
ore = solid - balls
# (template, scale, type, volume, bounding radius, count)
classes = [
    (0, 4.0, 0, ball(0.008), 0.004, round(0.5 * balls / ball(0.008))),
    (0, 3.0, 0, ball(0.006), 0.003, round(0.5 * balls / ball(0.006))),
    (1, 1.5, 1, v_tetra, bound_tetra, round(ore / 3 / v_tetra)),
    (0, 2.5, 1, ball(0.005), 0.0025, round(ore / 3 / ball(0.005))),
    (0, 2.0, 1, ball(0.004), 0.002, round(ore / 3 / ball(0.004))),
]

rng = random.Random(11)
placed = []  # (x, y, z, bounding radius)
rows = []
free = R - LIFTER - MARGIN
for template, scale, kind, volume, bound, count in classes:
    for _ in range(count):
        for attempt in range(200000):
            rho = (free - bound) * math.sqrt(rng.random())
            phi = 2 * math.pi * rng.random()
            x, z = rho * math.cos(phi), rho * math.sin(phi)
            y = bound + MARGIN + (L - 2 * (bound + MARGIN)) * rng.random()
            if all((x - p[0]) ** 2 + (y - p[1]) ** 2 + (z - p[2]) ** 2 > (bound + p[3]) ** 2
                   for p in placed):
                break
        else:
            sys.exit("make_wet_mill_charge.py: no room left for a body of bounding radius %g"
                     % bound)
        placed.append((x, y, z, bound))
        # A uniformly random orientation (Shoemake 1992); spheres need none.
        q = (1.0, 0.0, 0.0, 0.0)
        if template == 1:
            u1, u2, u3 = rng.random(), rng.random(), rng.random()
            q = (math.sqrt(u1) * math.cos(2 * math.pi * u3),
                 math.sqrt(1 - u1) * math.sin(2 * math.pi * u2),
                 math.sqrt(1 - u1) * math.cos(2 * math.pi * u2),
                 math.sqrt(u1) * math.sin(2 * math.pi * u3))
        rows.append("%.9g, %.9g, %.9g, %d, %g, %d, %.12g, %.12g, %.12g, %.12g, 0, 0, 0"
                    % ((x, y, z, template, scale, kind) + q))

with open(name, "w") as out:
    out.write("# The wet mill's charge (make_wet_mill_charge.py): x, y, z, template, scale, "
              "type, qw, qx, qy, qz, vx, vy, vz\n")
    out.write("\n".join(rows) + "\n")
counts = [c[5] for c in classes]
print("%s: %d bodies (balls 8 mm %d, 6 mm %d; ore tetrahedra %d, 5 mm %d, 4 mm %d); "
      "solid %.4g m^3 = %.1f%% of the mill's %.4g m^3 (balls %.4g m^3)"
      % ((name, len(rows)) + tuple(counts) + (solid, 100 * solid / MILL_VOLUME, MILL_VOLUME,
                                               balls)))
