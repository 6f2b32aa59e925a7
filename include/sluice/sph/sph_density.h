#pragma once
// The density side of an SPH step (Price 2012, J. Comput. Phys. 231, 759,
// §2.7 and §3; Robinson, Ramaioli & Luding 2014, Eqs. 10-11 and 19), each
// particle's kernel taken with its own smoothing length:
//   - summation density (the start, and a check): rho_a = sum_b m_b W(r_ab, h_a),
//     the particle itself included;
//   - smoothing length: h_a = sigma (m_a / rho_a)^(1/3);
//   - Price's correction: Omega_a = 1 - (dh_a/drho_a) sum_b m_b dW(r_ab, h_a)/dh_a,
//     with dh/drho = -h / (3 rho), the particle itself included;
//   - continuity: drho_a/dt = (1 / Omega_a) sum_b m_b (v_a - v_b) . grad_a W(r_ab, h_a).
// rho is the superficial density rho_hat = eps rho of the averaged equations.
// With a fixed smoothing length (grad_h = false: each particle keeps the h it
// started with, as in Monaghan 1992 and Morris et al. 1997) there is no
// dh/drho term: Omega_a = 1 and the continuity sum is taken as it is.
// The sums run over the pairs (sph_pairs.h); an owned pair adds to both of
// its particles, a pair with a ghost to the owned one only.

#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_particles.h>

namespace sluice
{
  /// rho_a = sum_b m_b W(r_ab, h_a) for the owned fluid particles (a wall
  /// particle's density follows from its pressure, sph_boundary.h).
  template <typename Kernel>
  void summation_density(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box);

  /// h_a = sigma (m_a / rho_a)^(1/3) for every particle (owned and ghost).
  void smoothing_lengths(SphParticles &P, double sigma);

  /// Omega_a for the owned particles (1 without grad_h).
  template <typename Kernel>
  void correction_factors(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                          bool grad_h = true);

  /// drho_a/dt for the owned particles (Omega_a must be current).
  template <typename Kernel>
  void density_rates(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box);

  /// Omega_a and then drho_a/dt for the owned particles in one pass over the
  /// pairs: the same sums, in the same order, as the two functions above
  /// (the step's form; a pass costs as much as its sums).
  /// Also keeps each pair's r and dW/dr at h_a and h_b in 'kernels' for the
  /// accelerations (sph_forces.h).
  template <typename Kernel>
  void correction_factors_and_density_rates(SphParticles &P, const SphPairs &pairs,
                                            const PeriodicBox &box, SphPairKernels &kernels,
                                            bool grad_h = true);
  template <typename Kernel>
  void correction_factors_and_density_rates(SphParticles &P, const SphPairs &pairs,
                                            const PeriodicBox &box);

  /// Each pair's r and dW/dr at h_a and h_b alone (where the step does not
  /// take the continuity sums: summation density).
  template <typename Kernel>
  void pair_kernels(const SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                    SphPairKernels &kernels);
} // namespace sluice
