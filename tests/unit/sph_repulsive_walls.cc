// Walls of Lennard-Jones boundary particles (sph/sph_repulsive_walls.h):
// - the lattice walk finds every boundary particle in reach: its force
//   equals the brute-force sum over all boundary particles and their
//   periodic images, on a floor under a periodic box and on two walls that
//   meet at an edge (1e-12);
// - the force is the potential's negative gradient (central differences,
//   1e-6), nothing beyond r_0, and it pushes away from a face in reach (away
//   from corners);
// - a particle thrown at the floor, under the walls' force alone, leaves it
//   with the energy it met it with and never reaches the domain's face: at
//   half and at five times sqrt(D).

#include <sluice/sph/sph_repulsive_walls.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double dx = 1e-3, D = 2.;
  const LennardJonesLaw law{D, dx, 0.5 * dx};

  /// The force at x summed over every boundary particle and every periodic
  /// image within one box length.
  Vec3 brute_force(const RepulsiveWalls &walls, const Vec3 &x, const Vec3 &length,
                   const std::array<bool, 3> &periodic)
  {
    Vec3 a;
    for (const Vec3 &b : walls.boundary_particles())
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
          for (int k = -1; k <= 1; ++k)
            {
              const int shift[3] = {i, j, k};
              bool      wanted   = true;
              Vec3      image    = b;
              for (unsigned int d = 0; d < 3; ++d)
                {
                  wanted = wanted && (periodic[d] || shift[d] == 0);
                  image[d] += shift[d] * length[d];
                }
              if (wanted)
                a += law.acceleration(x - image);
            }
    return a;
  }

  /// Where a face's boundary particles lie along its normal.
  double plane_of(const unsigned int d, const int side, const Vec3 &lower, const Vec3 &upper)
  {
    return side > 0 ? upper[d] + 0.5 * dx : lower[d] - 0.5 * dx;
  }

  /// Random points within 1.2 r_0 of the planes (the domain's faces moved
  /// dx/2 out), and some points further in, for one set of walls.
  void check_walls(const std::vector<std::pair<unsigned int, int>> &faces, const Vec3 &lower,
                   const Vec3 &upper, const std::array<bool, 3> &periodic, const char *name)
  {
    const RepulsiveWalls             walls(faces, lower, upper, periodic, 0.5 * dx, law);
    std::mt19937                     random(7);
    std::uniform_real_distribution<> unit(0., 1.);
    double                           worst_sum = 0., worst_gradient = 0.;
    unsigned int                     n_pushed = 0, n_wrong_way = 0, n_beyond = 0;
    for (unsigned int sample = 0; sample < 400; ++sample)
      {
        const auto &[d, side] = faces[sample % faces.size()];
        Vec3 x(lower.x + unit(random) * (upper.x - lower.x),
               lower.y + unit(random) * (upper.y - lower.y),
               lower.z + unit(random) * (upper.z - lower.z));
        // Its distance from the face's plane: 0.3 r_0 to 1.2 r_0.
        const double plane = plane_of(d, side, lower, upper);
        x[d]               = plane - side * dx * (0.3 + 0.9 * unit(random));
        // Periodic directions: now and then a point just beyond the box's end.
        for (unsigned int e = 0; e < 3; ++e)
          if (periodic[e] && sample % 7 == 0)
            x[e] = lower[e] + (upper[e] - lower[e]) * (unit(random) < 0.5 ? -0.02 : 1.02);
        const Vec3 a     = walls.acceleration(x);
        const Vec3 exact = brute_force(walls, x, upper - lower, periodic);
        worst_sum = std::max(worst_sum, norm(a - exact) / std::max(norm(exact), D / dx));

        // -grad phi by central differences.
        const double step = 1e-7 * dx;
        Vec3         gradient;
        for (unsigned int e = 0; e < 3; ++e)
          {
            Vec3 plus = x, minus = x;
            plus[e] += step, minus[e] -= step;
            gradient[e] = (walls.potential(plus) - walls.potential(minus)) / (2. * step);
          }
        worst_gradient = std::max(worst_gradient, norm(a + gradient) / std::max(norm(a), D / dx));

        // Inside the domain and in reach of one face only, away from it: each
        // boundary particle's push has a positive component along its inward
        // normal. (Within 0.9 r_0 of the plane a lattice point of spacing
        // r_0 / 2 is always in reach. In a corner a neighbouring wall's
        // particles may push toward the face.)
        bool inside = true, alone = true;
        for (unsigned int e = 0; e < 3; ++e)
          inside = inside && x[e] >= lower[e] && x[e] <= upper[e];
        for (const auto &[e, s] : faces)
          alone = alone && (e == d || std::abs(x[e] - plane_of(e, s, lower, upper)) >= dx);
        if (inside && alone && std::abs(x[d] - plane) < 0.9 * dx)
          {
            ++n_pushed;
            if (!(-side * a[d] > 0.))
              ++n_wrong_way;
          }
        bool in_reach = false;
        for (const auto &[e, s] : faces)
          in_reach = in_reach || std::abs(x[e] - plane_of(e, s, lower, upper)) < dx;
        if (!in_reach && norm(a) != 0.)
          ++n_beyond;
      }
    std::printf("%s: lattice walk vs brute force %.2e, force vs -grad phi %.2e, "
                "%u points pushed (%u the wrong way), %u forces beyond r_0\n",
                name, worst_sum, worst_gradient, n_pushed, n_wrong_way, n_beyond);
    check(worst_sum < 1e-12, "lattice walk against the brute-force sum", worst_sum, 0.);
    check(worst_gradient < 1e-6, "force against -grad phi", worst_gradient, 0.);
    check(n_pushed > 50 && n_wrong_way == 0, "pushed away from the face", n_wrong_way, 0.);
    check(n_beyond == 0, "no force beyond r_0", n_beyond, 0.);
  }

  /// A particle thrown at a floor under a periodic box, leap-frog under the
  /// walls' force alone, until it is back at its starting height.
  void check_bounce(const double speed_over_sqrt_D)
  {
    const Vec3           lower(0., 0., 0.), upper(4. * dx, 4. * dx, 8. * dx);
    const RepulsiveWalls walls({{2u, -1}}, lower, upper, {{true, true, false}}, 0.5 * dx, law);
    const double         v_0 = speed_over_sqrt_D * std::sqrt(D);
    Vec3         x(1.3 * dx, 2.1 * dx, 1.5 * dx);
    Vec3         v = v_0 * (1. / std::sqrt(1.1)) * Vec3(0.3, 0.1, -1.);
    const double dt = 2e-4 * dx / v_0, energy = 0.5 * norm_square(v) + walls.potential(x);
    double       drift = 0., lowest = x.z;
    Vec3         a     = walls.acceleration(x);
    for (unsigned int step = 0; step < 100000 && !(v.z > 0. && x.z >= 1.5 * dx); ++step)
      {
        v += 0.5 * dt * a;
        x += dt * v;
        a = walls.acceleration(x);
        v += 0.5 * dt * a;
        drift  = std::max(drift, std::abs(0.5 * norm_square(v) + walls.potential(x) - energy));
        lowest = std::min(lowest, x.z);
      }
    const double back = norm(v) / v_0 - 1.;
    std::printf("bounce at %.1f sqrt(D): back at %.9f of the speed, energy drift %.2e of it, "
                "lowest %.3f dx above the domain's face\n",
                speed_over_sqrt_D, 1. + back, drift / energy, lowest / dx);
    check(v.z > 0. && x.z >= 1.5 * dx, "the particle comes back up", x.z / dx, 1.5);
    check(std::abs(back) < 1e-6, "it leaves with the speed it came with", back, 0.);
    check(drift / energy < 1e-3, "energy kept along the way", drift / energy, 0.);
    check(lowest > 0., "never through the domain's face", lowest / dx, 0.);
  }
} // namespace

int main()
{
  check_walls({{2u, -1}}, Vec3(0., 0., 0.), Vec3(4. * dx, 3. * dx, 6. * dx), {{true, true, false}},
              "floor, periodic x and y");
  check_walls({{0u, -1}, {2u, -1}, {0u, 1}}, Vec3(0., 0., 0.), Vec3(5.3 * dx, 4. * dx, 6. * dx),
              {{false, true, false}}, "tank of x-, x+ and z-, periodic y");
  check_walls({{1u, 1}, {2u, 1}}, Vec3(0., 0., 0.), Vec3(4. * dx, 4.7 * dx, 5.1 * dx),
              {{false, false, false}}, "y+ and z+ meeting at an edge, closed box");
  check_bounce(0.5);
  check_bounce(5.);
  return sluice::unit::failures == 0 ? 0 : 1;
}
