#pragma once
// delta-SPH: a diffusive term in the continuity equation that damps the
// density noise of weak compressibility (Molteni & Colagrossi 2009, Comput.
// Phys. Commun. 180, 861, Eq. 11; Antuono et al. 2010), with the hydrostatic
// part of the density differences taken out so that a column at rest stays
// stratified (Fourtakas et al. 2019, Comput. Fluids 190, 346, Eq. 13, in its
// linearised form rho_0 g.r_ab / c_s^2):
//
//   drho_a/dt += delta hbar c_s sum_b 2 (rho_a - rho_b - rho_0 g.(x_a - x_b) / c_s^2)
//                                     W'(r_ab, hbar) / r_ab  m_b / rho_b,
//
// hbar = (h_a + h_b) / 2; between fluid particles only (a wall particle's
// density follows from the fluid, sph_boundary.h). With the fluid fraction
// the differences are of the intrinsic densities rho_hat / eps, times eps_a.
// The term is antisymmetric, so sum_a (m_a / rho_a) drho_a/dt is unchanged
// to round-off, and a linear hydrostatic density gives none.

#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_particles.h>

namespace sluice
{
  struct DensityDiffusion
  {
    double delta = 0.;     // [-]; 0: off (Molteni & Colagrossi use 0.1)
    double sound_speed = 0.;       // c_s [m/s]
    double reference_density = 0.; // rho_0 [kg/m^3]
    Vec3   gravity;        // its stratifying part: along non-periodic directions [m/s^2]
  };

  /// Adds the diffusive term to the owned fluid particles' drho/dt.
  template <typename Kernel>
  void add_density_diffusion(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                             const DensityDiffusion &diffusion);
} // namespace sluice
