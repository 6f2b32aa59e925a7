#pragma once
// The momentum side of an SPH step (doc/sph.md), for the owned particles:
//   - pressure, Tait's equation with the reference density scaled by the
//     fluid fraction (Robinson, Ramaioli & Luding 2014, Eqs. 15-18):
//       P = B ((rho_hat / (eps rho_0))^gamma - 1),  B = rho_0 c_s^2 / gamma;
//   - the pressure force in Price's variable-h form (Price 2012, Eq. 35):
//       dv_a/dt = -sum_b m_b [P_a / (Omega_a rho_a^2) grad_a W(r_ab, h_a)
//                             + P_b / (Omega_b rho_b^2) grad_a W(r_ab, h_b)],
//     antisymmetric in a and b, so momentum is kept to round-off;
//   - the physical viscosity for the dynamic viscosity mu, Morris, Fox &
//     Zhu's (1997, Eq. 8) laminar form or Monaghan's (1997) signal-velocity
//     form tied to mu (Robinson et al. 2014, Eqs. 13-14), sph_viscosity.h:
//       dv_a/dt += sum_b m_b [the pair's viscous acceleration],
//     with grad_a W taken at hbar = (h_a + h_b) / 2, antisymmetric in a and b;
//   - optionally Monaghan's (1992) artificial viscosity, only between
//     approaching particles (v_ab . r_ab < 0), which damps the acoustic
//     noise of weak compressibility without touching a steady shear:
//       dv_a/dt += -sum_b m_b Pi_ab grad_a W(r_ab, hbar),
//       Pi_ab = -alpha c_s hbar (v_ab . r_ab) / (rhobar (r_ab^2 + 0.01 hbar^2));
//   - optionally Monaghan's (2000, J. Comput. Phys. 159, 290, Eqs. 24-26)
//     artificial pressure against the tensile instability: between
//     particles in tension it adds R_ab f_ab^4 to the bracket of the
//     pressure force, taken with hbar,
//       R_ab = R_a + R_b,  R_a = epsilon |P_a| / rho_a^2 where P_a < 0, else 0,
//       f_ab = W(r_ab, hbar) / W(hbar / sigma, hbar)
//     (hbar / sigma the local particle spacing); symmetric, so momentum is
//     still kept;
//   - gravity.
// Both sums run over the pairs (sph_pairs.h); an owned pair adds to both.
// In a coupled scene of formulation set II (Zhou et al. 2010's model A, the
// averaged equations of Gao & Sun's CFD-DEM, whose particle force is
// -V grad p + drag, their Eq. 26), the fluid's equation has -eps grad p +
// eps div tau in place of -grad p + div tau, as the finite-element fluid's
// model A: the pressure and physical viscous accelerations of each pair are
// then scaled by the fluid fraction of the particle that receives them, eps_a
// on a and eps_b on b. The pair is no longer antisymmetric: the grains take
// the rest through their -V grad p and V div tau, which set II does not give
// back to the fluid. At rest among fixed grains, grad p = rho g: no reaction
// is needed to hold the fluid there.

#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_particles.h>
#include <sluice/sph/sph_viscosity.h>

#include <vector>

namespace sluice
{
  /// Tait's equation of state.
  struct TaitEquation
  {
    double reference_density = 1000.; // rho_0 [kg/m^3]
    double sound_speed       = 10.;   // c_s [m/s]
    double exponent          = 7.;    // gamma [-]

    /// P for the superficial density rho_hat at the fluid fraction eps [Pa].
    double pressure(double density, double porosity) const;
    /// The superficial density of pressure P at the fluid fraction eps.
    double density(double pressure, double porosity) const;
  };

  struct SphForceParameters
  {
    TaitEquation state;
    double           viscosity      = 1e-3; // mu [Pa s]
    SphViscosityForm viscosity_form = SphViscosityForm::morris;
    // Monaghan's (1992) artificial viscosity between approaching particles only:
    // Pi_ab = -alpha c_s hbar (v_ab . r_ab) / (rhobar (r^2 + 0.01 hbar^2)) [-]
    double       artificial_viscosity = 0.;
    // Monaghan's (2000) artificial pressure: epsilon [-]; 0: off. It needs
    // sigma of h = sigma dx for the particle spacing.
    double       artificial_pressure = 0.;
    double       smoothing_factor    = 1.5;
    Vec3         gravity;          // [m/s^2]
    // Set II (model A): the pressure and viscous terms times the receiving
    // particle's fluid fraction; false: Robinson et al.'s -grad p + div tau.
    bool         stress_times_fluid_fraction = false;
  };

  /// P_a from the state equation, for every particle (owned and ghost).
  void pressures(SphParticles &P, const TaitEquation &state);

  /// The owned particles' accelerations (Omega and P must be current), with
  /// each pair's r and dW/dr at h_a and h_b from 'kernels' (sph_pairs.h). The
  /// viscous force sees 'viscous_velocity' (the particles' own velocities,
  /// or at walls their no-slip extrapolation, sph_boundary.h); the
  /// artificial viscosity sees the particles' own velocities, a wall's its
  /// wall's.
  template <typename Kernel>
  void accelerations(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                     const SphForceParameters &parameters,
                     const std::vector<Vec3> &viscous_velocity, const SphPairKernels &kernels);
  /// The same, with the pairs' kernels computed here.
  template <typename Kernel>
  void accelerations(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                     const SphForceParameters &parameters,
                     const std::vector<Vec3> &viscous_velocity);
} // namespace sluice
