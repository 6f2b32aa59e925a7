#pragma once
// XSPH (Monaghan 1989, J. Comput. Phys. 82, 1; Gao & Sun's §4): particles
// drift with their velocity plus a fraction epsilon of its local average
// difference, which keeps neighbouring particles moving together and
// orders them in a flow:
//
//   dx_a/dt = v_a + epsilon sum_b 2 m_b / (rho_a + rho_b) (v_b - v_a) W(r_ab, hbar),
//
// hbar = (h_a + h_b) / 2, between fluid particles only. The weights are
// symmetric, so sum_a m_a (dx_a/dt - v_a) = 0: the drift moves no momentum,
// and a uniform velocity gets none.

#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_particles.h>

#include <vector>

namespace sluice
{
  /// The owned fluid particles' XSPH corrections (dx/dt - v), for 'velocity'
  /// (zero at walls).
  template <typename Kernel>
  void xsph_corrections(const SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                        double epsilon, const std::vector<Vec3> &velocity,
                        std::vector<Vec3> &correction);
} // namespace sluice
