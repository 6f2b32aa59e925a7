#pragma once
// The drag on a particle over one time step, integrated exactly for the step's
// frozen drag coefficient k, fluid velocity u and other force F (gravity,
// buoyancy, contacts):
//   m dv/dt = k (u - v) + F   =>   v(t + dt) = v_inf + (v - v_inf) e^(-dt/tau_p),
//   v_inf = u + F / k, tau_p = m / k.
// This is unconditionally stable and reaches the terminal velocity exactly, so a
// relaxation time tau_p far below the step (fine powders, water-glycerol) does not
// force a smaller step; an explicit update is unstable for dt > 2 tau_p. The
// impulse the drag delivered, J = m (v(t+dt) - v) - F dt, is what the fluid must
// receive with the opposite sign (coupling scheme 3 of Zhou et al. 2010):
// momentum is then conserved exactly, whatever dt / tau_p.

#include <sluice/core/vector3.h>

#include <cmath>

namespace sluice
{
  struct DragStep
  {
    Vec3 velocity; // v(t + dt)
    Vec3 impulse;  // integral of k (u - v) dt over the step: the fluid gets -impulse
  };

  /// mass m > 0, drag coefficient k >= 0, all other forces F held over dt.
  inline DragStep integrate_drag(const double mass, const double k, const Vec3 &fluid_velocity,
                                 const Vec3 &velocity, const Vec3 &other_force, const double dt)
  {
    DragStep step;
    const double x = dt * k / mass;
    if (x < 1e-8)
      {
        // No drag to speak of: v + dt (k (u - v) + F) / m, to second order in x.
        const Vec3 accel = (1. / mass) * (k * (fluid_velocity - velocity) + other_force);
        step.velocity    = velocity + dt * (1. - 0.5 * x) * accel;
      }
    else
      {
        const Vec3   terminal = fluid_velocity + (1. / k) * other_force;
        const double decay    = std::exp(-x);
        step.velocity         = terminal + decay * (velocity - terminal);
      }
    step.impulse = mass * (step.velocity - velocity) - dt * other_force;
    return step;
  }
} // namespace sluice
