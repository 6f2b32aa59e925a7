#pragma once
// Solid walls as layers of fixed wall particles, with the generalised wall
// boundary condition of Adami, Hu & Adams (2012, J. Comput. Phys. 231, 7057).
// Each step a wall particle w takes from the fluid particles f around it
//   - the pressure (their Eq. 27), which holds the hydrostatic balance at the
//     wall:
//       P_w = max(0, [sum_f P_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf] / sum_f W_wf),
//     r_wf = x_w - x_f, a_w the wall's acceleration (0 for a wall at rest);
//     never below 0: a wall pushes but does not pull, else a free surface
//     in tension sliding down a wall sticks to it (and at coarse resolution
//     passes through it);
//   - the density of that pressure by the state equation (their Eq. 28);
//   - for the viscous force only, the velocity that makes the no-slip
//     condition hold at the wall (their Eqs. 22-23):
//       v_w = 2 v_wall - sum_f v_f W_wf / sum_f W_wf;
//     the continuity equation sees the wall's own velocity.
// A wall particle with no fluid around it keeps P = 0 and its own velocity.
// W is taken with the wall particle's h.

#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_forces.h>
#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_particles.h>

#include <vector>

namespace sluice
{
  class WallStates
  {
  public:
    /// Sets the wall particles' pressure and density, and in 'no_slip' their
    /// extrapolated velocities for the viscous force (fluid particles keep
    /// their own). Needs the fluid's pressures.
    template <typename Kernel>
    void update(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                const TaitEquation &state, const Vec3 &gravity);

    /// Per particle: the velocity the viscous force sees.
    std::vector<Vec3> no_slip;
  };
} // namespace sluice
