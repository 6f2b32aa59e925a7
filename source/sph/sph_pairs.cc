// The SPH particles' pairs (see the header).

#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_kernel.h>

#include <algorithm>

namespace sluice
{
  void SphPairs::build(const SphParticles &P, const PeriodicBox &box, const double skin)
  {
    const unsigned int n_all = P.size();
    double             h_max = 0.;
    for (unsigned int a = 0; a < n_all; ++a)
      h_max = std::max(h_max, P.smoothing[a]);
    // Both kernels reach 2h (sph_kernel.h).
    grid.build(P.position, n_all, box, WendlandC2Kernel::support * h_max + skin);

    offset.assign(P.n_local + 1, 0);
    partner.clear();
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        grid.stencil(a, stencil);
        const Vec3 xa = P.position[a];
        for (const unsigned int cell : stencil)
          for (unsigned int k = grid.cell_start[cell]; k < grid.cell_start[cell + 1]; ++k)
            {
              const unsigned int b = grid.cell_particles[k];
              if ((b < P.n_local && b <= a) || (P.wall[a] && P.wall[b]))
                continue; // an owned pair from its lower index only; no wall pair
              Vec3 d = xa - P.position[b];
              if (box.any_periodic)
                d = box.minimum_image(d);
              const double reach = 2. * std::max(P.smoothing[a], P.smoothing[b]) + skin;
              if (norm_square(d) < reach * reach)
                partner.push_back(b);
            }
        offset[a + 1] = partner.size();
      }
  }
} // namespace sluice
