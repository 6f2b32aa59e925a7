#pragma once
// The kick of a coupled scene, for DemSystem::advance: contacts, gravity and
// the frozen non-drag fluid forces held over the half step, the drag
// integrated exactly for the frozen drag coefficient and fluid velocity
// (implicit_drag.h). Each particle adds the impulse the fluid gave it to its
// record, which the fluid receives with the opposite sign (Zhou et al. 2010,
// coupling scheme 3).

#include <sluice/coupling/coupling_fields.h>
#include <sluice/coupling/implicit_drag.h>
#include <sluice/coupling/particle_fluid_forces.h>
#include <sluice/dem/particle_storage.h>

namespace sluice
{
  struct FluidForcesKick
  {
    Vec3                  gravity;
    const CouplingFields &fields;

    void kick(ParticleStorage &P, const double h) const
    {
      const CouplingFields &cd = fields;
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          double *const e   = P.extra_of(i);
          const double  m_a = e[cd.added_mass];
          const Vec3    u(e[cd.fluid_velocity], e[cd.fluid_velocity + 1],
                       e[cd.fluid_velocity + 2]);
          const Vec3    other(e[cd.other_force], e[cd.other_force + 1], e[cd.other_force + 2]);
          const Vec3    exchanged(e[cd.exchanged_force], e[cd.exchanged_force + 1],
                               e[cd.exchanged_force + 2]);
          const Vec3     F    = P.force[i] + P.mass[i] * gravity + other;
          const DragStep step = integrate_drag(P.mass[i] + m_a, e[cd.drag_coefficient], u,
                                               P.velocity[i], F, h);
          // The fluid gave: the drag impulse, the exchanged forces, and for the
          // virtual mass its implicit part -m_a dv.
          const Vec3 impulse = step.impulse + h * exchanged - m_a * (step.velocity - P.velocity[i]);
          for (unsigned int d = 0; d < 3; ++d)
            e[cd.fluid_impulse + d] += impulse[d];
          P.velocity[i] = step.velocity;
          P.angular_velocity[i] += (h * P.inverse_inertia[i]) * P.torque[i];
        }
    }

    /// A bed held in place ('cfd-dem/fixed particles') takes no DEM step: it
    /// only receives the fluid's impulse over a duration.
    void hold(ParticleStorage &P, const double duration) const
    {
      const CouplingFields &cd = fields;
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          double *e = P.extra_of(i);
          for (unsigned int d = 0; d < 3; ++d)
            e[cd.fluid_impulse + d] +=
              duration * (e[cd.drag_coefficient] * (e[cd.fluid_velocity + d] - P.velocity[i][d]) +
                          e[cd.exchanged_force + d]);
        }
    }
  };
} // namespace sluice
