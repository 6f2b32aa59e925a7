#pragma once
// The fields a DEM particle feels, evaluated at the SPH fluid particles for
// Shepard's interpolation to the DEM particles (Robinson, Ramaioli & Luding
// 2014, §3.4; sph_solid_exchange.h), each as the fluid's own equations
// discretise it, so that a particle in a fluid at rest feels exactly the
// pressure gradient that holds the fluid at rest:
//   - grad P_a = rho_hat_a sum_b m_b [P_a / (Omega_a rho_a^2) grad_a W(r_ab, h_a)
//                                    + P_b / (Omega_b rho_b^2) grad_a W(r_ab, h_b)],
//     the pressure force of sph_forces.h times -rho_hat_a;
//   - div tau_a = rho_hat_a times the viscous acceleration, in the fluid's
//     own form (Morris' or the signal-velocity one, sph_viscosity.h);
//   - grad u_a = sum_b V_b (u_b - u_a) (x) grad_a W(r_ab, h_a), V_b = m_b / rho_hat_b;
//   - grad eps_a = sum_b V_b (eps_b - eps_a) grad_a W(r_ab, h_a), over fluid
//     particles only (a wall has no fluid fraction of its own).
// Wall particles get no fields (no DEM particle samples them).

#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_forces.h>
#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_particles.h>

#include <array>
#include <vector>

namespace sluice
{
  struct SphFluidFields
  {
    std::vector<Vec3>                pressure_gradient;  // [Pa/m]
    std::vector<Vec3>                viscous_divergence; // div tau [N/m^3]
    std::vector<Vec3>                porosity_gradient;  // [1/m]
    std::array<std::vector<Vec3>, 3> velocity_gradient;  // [i]: grad u_i [1/s]
  };

  /// The fields at every owned particle (Omega and P must be current), with
  /// the velocities 'velocity' (at walls their no-slip extrapolation).
  template <typename Kernel>
  SphFluidFields fluid_fields(const SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                              const SphForceParameters &parameters,
                              const std::vector<Vec3> &velocity);

  /// grad P alone, bit for bit as fluid_fields gives it: the start's
  /// relaxation needs it every SPH step and nothing else.
  template <typename Kernel>
  std::vector<Vec3> pressure_gradients(const SphParticles &P, const SphPairs &pairs,
                                       const PeriodicBox &box);
} // namespace sluice
