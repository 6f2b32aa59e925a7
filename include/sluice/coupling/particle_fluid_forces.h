#pragma once
// The fluid's forces on one particle for a coupling step, from the fluid
// sampled at its centre, split as Zhou et al. (2010, Table 1) prescribe for the
// chosen formulation:
//   set I   particle: f_d + f_grad p + f_div tau + f'';       fluid gets all of it
//   set II  particle: the same;                                fluid gets f_d + f''
//   set III particle: f_d / eps - rho_f V_p g + f'';           fluid gets all of it
// with f_d = k (u - v) from the drag closure, f_grad p = -V_p grad p,
// f_div tau = V_p div tau, and f'' the virtual-mass and lift forces:
//   virtual mass  C_vm rho_f V_p (Du/Dt - dv/dt), the dv/dt part implicit as
//                 added inertia m_a = C_vm rho_f V_p (stable for rho_p ~ rho_f);
//   Saffman lift  1.615 d^2 (rho_f mu)^(1/2) |w|^(-1/2) (u - v) x w, w = curl u
//                 (Saffman 1965, in the vector form of Crowe et al. 1998);
//   Magnus lift   (pi/8) d^3 rho_f (w/2 - omega_p) x (u - v) (Rubinow & Keller 1961).
// A clump body enters as its union volume V_p and volume-equivalent diameter
// d, with its sphericities along the slip for the drag (fluid_shapes.h).
// Each appears only when the scene asks for it. The drag is integrated
// implicitly by the DEM (implicit_drag.h), so only its coefficient k and the
// fluid velocity are frozen over the step.

#include <sluice/core/sphere.h>
#include <sluice/core/vector3.h>
#include <sluice/core/coupling_parameters.h>
#include <sluice/coupling/coupling_fields.h>
#include <sluice/coupling/drag_closures.h>
#include <sluice/coupling/fluid_backend.h>
#include <sluice/coupling/fluid_shapes.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  struct FluidProperties
  {
    double density = 1000., viscosity = 1e-3;
    Vec3   gravity;
  };

  /// Fills the coupling data of one particle (its shape for the slip it
  /// has, velocity v, spin w_p) from the fluid sample s: the 'fields' in the
  /// particle's block 'data'. dt_fluid: the coupling step (for Du/Dt along
  /// the particle path); first: no previous sample yet.
  inline void particle_fluid_forces(const CouplingParameters &c, const FluidProperties &fluid,
                                    const ParticleFluidSample &s, const FluidShape &shape,
                                    const Vec3 &v, const Vec3 &w_p, const double dt_fluid,
                                    const bool first, const CouplingFields &fields, double *data)
  {
    const Vec3 u_prev(data[fields.previous_velocity], data[fields.previous_velocity + 1],
                      data[fields.previous_velocity + 2]);
    std::fill(data, data + fields.sampled_end, 0.);
    if (!s.found)
      return; // outside the fluid mesh: a pure DEM particle
    const double d   = shape.diameter;
    const double V   = shape.volume;
    const double rho = fluid.density, mu = fluid.viscosity;
    const double eps = c.two_way ? std::clamp(s.porosity, 1. - c.max_solid_fraction, 1.) : 1.;
    const Vec3   u   = s.velocity;
    const Vec3   slip = u - v;

    DragState state;
    state.eps       = eps;
    state.density   = rho;
    state.viscosity = mu;
    state.diameter  = d;
    state.slip      = norm(slip);
    state.sphericity            = shape.sphericities.sphericity;
    state.crosswise_sphericity  = shape.sphericities.crosswise;
    state.lengthwise_sphericity = shape.sphericities.lengthwise;
    double k        = particle_drag_coefficient(c.drag, state);

    Vec3 other, exchanged;
    if (c.formulation == CouplingFormulation::set_iii)
      {
        k /= eps;
        other     = (-rho * V) * fluid.gravity;
        exchanged = other;
      }
    else
      {
        if (c.pressure_gradient_force)
          other += (-V) * s.pressure_gradient;
        if (c.viscous_force)
          other += V * s.viscous_divergence;
        if (c.formulation == CouplingFormulation::set_i)
          exchanged = other;
      }
    // What the fluid fraction balances: the displaced fluid's own weight and
    // pressure forces (self_induced_velocity.h).
    if (fields.self_balanced != 0)
      for (unsigned int i = 0; i < 3; ++i)
        data[fields.self_balanced + i] = exchanged[i];

    Vec3 curl;
    if (c.saffman_lift || c.magnus_lift)
      {
        const auto &g = s.velocity_gradient; // g[i][j] = du_i/dx_j
        curl = Vec3(g[2][1] - g[1][2], g[0][2] - g[2][0], g[1][0] - g[0][1]);
      }
    double m_a = 0.;
    if (c.virtual_mass_coefficient > 0.)
      {
        m_a = c.virtual_mass_coefficient * rho * V;
        // Du/Dt = du/dt along the particle path + ((u - v) . grad) u.
        Vec3 dudt = first ? Vec3() : (1. / dt_fluid) * (u - u_prev);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            dudt[i] += s.velocity_gradient[i][j] * slip[j];
        other += m_a * dudt;
        exchanged += m_a * dudt;
      }
    if (c.saffman_lift)
      {
        const double w = norm(curl);
        if (w > 0.)
          {
            const Vec3 f = (1.615 * d * d * std::sqrt(rho * mu / w)) * cross(slip, curl);
            other += f;
            exchanged += f;
          }
      }
    if (c.magnus_lift)
      {
        const Vec3 f = (M_PI / 8. * d * d * d * rho) * cross(0.5 * curl - w_p, slip);
        other += f;
        exchanged += f;
      }

    // A particle partly out of the fluid (s.immersion < 1) feels that share
    // of every force, and the fluid gets the same share back.
    const double phi              = s.immersion;
    data[fields.drag_coefficient] = phi * k;
    data[fields.added_mass]       = phi * m_a;
    for (unsigned int i = 0; i < 3; ++i)
      {
        data[fields.fluid_velocity + i]    = u[i];
        data[fields.other_force + i]       = phi * other[i];
        data[fields.exchanged_force + i]   = phi * exchanged[i];
        data[fields.previous_velocity + i] = u[i];
      }
    if (fields.self_balanced != 0)
      for (unsigned int i = 0; i < 3; ++i)
        data[fields.self_balanced + i] *= phi;
  }
} // namespace sluice
