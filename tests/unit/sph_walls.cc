// Walls of wall particles (sph/sph_boundary.h) and what the forces take
// from them (sph/sph_forces.h), on a block of fluid over a floor:
// - a uniform fluid pressure P_0 > 0 without gravity gives every wall
//   particle in reach P_0 (Adami et al.'s Eq. 27, a weighted mean), to
//   round-off, and the density of P_0;
// - a fluid in tension (P < 0) gives the walls P = 0 and rho_0: a wall
//   pushes but does not pull (free surfaces sliding down a wall otherwise
//   stick to it and, at coarse resolution, pass through it);
// - a fluid gliding at U along a wall at rest, without pressure or physical
//   viscosity: the walls' no-slip velocity is -U, but the artificial
//   viscosity sees their own, 0: a fluid particle's acceleration equals the
//   artificial viscosity's sum written out here with v_ab = U, to round-off.

#include <sluice/sph/sph_boundary.h>
#include <sluice/sph/sph_density.h>
#include <sluice/sph/sph_forces.h>
#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_pairs.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double rho_0 = 1000., dx = 1e-3;
  const unsigned int n = 8; // fluid n x n x n over 3 layers of wall, periodic in x and y

  struct Tank
  {
    SphParticles P;
    PeriodicBox  box;
    SphPairs     pairs;
  };

  template <typename Kernel>
  Tank tank(const double fluid_pressure, const TaitEquation &state)
  {
    Tank t;
    for (int k = -3; k < int(n); ++k)
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int i = 0; i < n; ++i)
          t.P.push_back(t.P.size(), dx * Vec3(i + 0.5, j + 0.5, k + 0.5), rho_0 * dx * dx * dx,
                        state.density(fluid_pressure, 1.), 1.5 * dx, k < 0);
    t.P.n_local = t.P.size();
    for (unsigned int a = 0; a < t.P.size(); ++a)
      t.P.pressure[a] = t.P.wall[a] ? 0. : fluid_pressure;
    t.box = PeriodicBox(Vec3(0., 0., -4. * dx), Vec3(n * dx, n * dx, (n + 1) * dx),
                        {{true, true, false}});
    t.pairs.build(t.P, t.box, 0.);
    return t;
  }

  template <typename Kernel>
  void check_wall_pressure()
  {
    const std::string name = Kernel::name;
    TaitEquation      state;
    state.reference_density = rho_0;
    state.sound_speed       = 20.;
    for (const double P_0 : {2e3, -2e3})
      {
        Tank       t = tank<Kernel>(P_0, state);
        WallStates walls;
        walls.update<Kernel>(t.P, t.pairs, t.box, state, Vec3());
        const double expected = std::max(P_0, 0.);
        double       deviation = 0.;
        unsigned int in_reach = 0;
        for (unsigned int a = 0; a < t.P.size(); ++a)
          if (t.P.wall[a] && t.P.position[a].z > -2. * dx) // the two layers the fluid reaches
            {
              deviation = std::max({deviation, std::abs(t.P.pressure[a] - expected),
                                    std::abs(t.P.density[a] - state.density(expected, 1.))});
              ++in_reach;
            }
        std::printf("%s: fluid at %g Pa, %u wall particles, largest deviation %.3g\n",
                    Kernel::name, P_0, in_reach, deviation);
        check(deviation < 1e-9 * std::abs(P_0) && in_reach == 2 * n * n,
              (name + (P_0 > 0. ? ": walls take the fluid's pressure" :
                                  ": walls do not pull a fluid in tension")).c_str(),
              deviation, 0.);
      }
  }

  template <typename Kernel>
  void check_artificial_viscosity_at_walls()
  {
    const std::string  name = Kernel::name;
    SphForceParameters p;
    p.state.reference_density = rho_0;
    p.state.sound_speed       = 20.;
    p.viscosity               = 0.;
    p.artificial_viscosity    = 0.1;
    Tank         t = tank<Kernel>(0., p.state);
    const double U = 0.3; // [m/s] along x
    for (unsigned int a = 0; a < t.P.size(); ++a)
      if (!t.P.wall[a])
        t.P.velocity[a] = Vec3(U, 0., 0.);
    correction_factors<Kernel>(t.P, t.pairs, t.box);
    WallStates walls;
    walls.update<Kernel>(t.P, t.pairs, t.box, p.state, Vec3());
    for (unsigned int a = 0; a < t.P.size(); ++a)
      t.P.pressure[a] = 0.;
    accelerations<Kernel>(t.P, t.pairs, t.box, p, walls.no_slip);

    // The bottom fluid particle at (dx/2, dx/2, dx/2): Monaghan's sum over
    // the wall particles it approaches, with the walls at rest.
    const unsigned int f = 3 * n * n;
    Vec3               expected;
    double             no_slip_seen = 0.;
    for (unsigned int b = 0; b < t.P.size(); ++b)
      if (t.P.wall[b])
        {
          const Vec3   d = t.box.minimum_image(t.P.position[f] - t.P.position[b]);
          const double r = norm(d), h = 1.5 * dx;
          if (r >= 2. * h || dot(t.P.velocity[f], d) >= 0.)
            continue;
          const double Pi = -p.artificial_viscosity * p.state.sound_speed * h *
                            dot(t.P.velocity[f], d) /
                            (0.5 * (t.P.density[f] + t.P.density[b]) * (r * r + 0.01 * h * h));
          expected += (-t.P.mass[b] * Pi * kernel_radial_derivative<Kernel>(r, h) / r) * d;
          no_slip_seen = std::min(no_slip_seen, walls.no_slip[b].x);
        }
    std::printf("%s: gliding fluid particle's acceleration %.9g, walls at rest give %.9g "
                "(their no-slip velocity down to %.3g m/s)\n",
                Kernel::name, t.P.acceleration[f].x, expected.x, no_slip_seen);
    check(norm(t.P.acceleration[f] - expected) < 1e-9 * norm(expected) && expected.x < 0. &&
            no_slip_seen < -0.5 * U,
          (name + ": artificial viscosity sees the walls' own velocity").c_str(),
          t.P.acceleration[f].x, expected.x);
  }
} // namespace

int main()
{
  check_wall_pressure<CubicSplineKernel>();
  check_wall_pressure<WendlandC2Kernel>();
  check_artificial_viscosity_at_walls<CubicSplineKernel>();
  check_artificial_viscosity_at_walls<WendlandC2Kernel>();
  if (sluice::unit::failures == 0)
    std::printf("sph walls: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
