#pragma once
// SPH particles for the unit tests: nx x ny x nz on a simple cubic lattice
// of spacing dx from dx/2, each moved by up to 'jitter' dx along each axis,
// of mass rho_0 dx^3, density rho_0 (1 + density_spread u) and smoothing
// length 1.5 dx (1 + h_spread u), u uniform in [-1, 1] from 'seed'.

#include <sluice/sph/sph_particles.h>

#include <random>

namespace sluice::unit
{
  inline SphParticles sph_lattice(const unsigned int nx, const unsigned int ny,
                                  const unsigned int nz, const double dx, const double rho_0,
                                  const double jitter = 0., const double density_spread = 0.,
                                  const double h_spread = 0., const unsigned int seed = 5)
  {
    std::mt19937                           random(seed);
    std::uniform_real_distribution<double> u(-1., 1.);
    SphParticles                           P;
    for (unsigned int k = 0; k < nz; ++k)
      for (unsigned int j = 0; j < ny; ++j)
        for (unsigned int i = 0; i < nx; ++i)
          {
            const Vec3 x = dx * Vec3(i + 0.5 + jitter * u(random), j + 0.5 + jitter * u(random),
                                     k + 0.5 + jitter * u(random));
            const double density = rho_0 * (1. + density_spread * u(random));
            P.push_back(P.size(), x, rho_0 * dx * dx * dx, density,
                        1.5 * dx * (1. + h_spread * u(random)));
          }
    P.n_local = P.size();
    return P;
  }
} // namespace sluice::unit
