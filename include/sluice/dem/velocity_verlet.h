#pragma once
// Velocity-Verlet integration of translation and rotation (Allen & Tildesley),
// split into the two pieces the time loop needs: a half kick with the current
// forces and torques, and a drift. Solid spheres, I = 2/5 m R^2.

#include <sluice/core/vector3.h>
#include <sluice/dem/particle_storage.h>

#include <algorithm>

namespace sluice
{
  /// v += h (F/m + g), w += h T/I for the owned particles (h: half a step).
  inline void half_kick(ParticleStorage &P, const double h, const Vec3 &gravity)
  {
    Vec3 *const         v  = P.velocity.data();
    Vec3 *const         w  = P.angular_velocity.data();
    const Vec3 *const   f  = P.force.data();
    const Vec3 *const   t  = P.torque.data();
    const double *const im = P.inverse_mass.data();
    const double *const ii = P.inverse_inertia.data();
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        v[i] += h * (im[i] * f[i] + gravity);
        w[i] += (h * ii[i]) * t[i];
      }
  }

  /// x += dt v for the owned particles; notes the largest squared speed (for
  /// the DEM's per-step health check, while v is at hand).
  inline void drift(ParticleStorage &P, const double dt)
  {
    Vec3 *const       x = P.position.data();
    const Vec3 *const v = P.velocity.data();
    double            fastest_2 = 0.;
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        x[i] += dt * v[i];
        fastest_2 = std::max(fastest_2, norm_square(v[i]));
      }
    P.max_drift_speed_2 = fastest_2;
  }
} // namespace sluice
