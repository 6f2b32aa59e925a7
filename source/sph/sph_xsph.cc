// XSPH's drift correction (see the header).

#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_xsph.h>

namespace sluice
{
  template <typename Kernel>
  void xsph_corrections(const SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                        const double epsilon, const std::vector<Vec3> &velocity,
                        std::vector<Vec3> &correction)
  {
    correction.assign(P.n_local, Vec3());
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        if (P.wall[a])
          continue;
        for (unsigned int k = pairs.offset[a]; k < pairs.offset[a + 1]; ++k)
          {
            const unsigned int b = pairs.partner[k];
            if (P.wall[b])
              continue;
            Vec3 d = P.position[a] - P.position[b];
            if (box.any_periodic)
              d = box.minimum_image(d);
            const double h_mean = 0.5 * (P.smoothing[a] + P.smoothing[b]);
            const double weight = 2. * epsilon * kernel_value<Kernel>(norm(d), h_mean) /
                                  (P.density[a] + P.density[b]);
            const Vec3 v_ba = velocity[b] - velocity[a];
            correction[a] += (P.mass[b] * weight) * v_ba;
            if (b < P.n_local)
              correction[b] -= (P.mass[a] * weight) * v_ba;
          }
      }
  }

  template void xsph_corrections<CubicSplineKernel>(const SphParticles &, const SphPairs &,
                                                    const PeriodicBox &, double,
                                                    const std::vector<Vec3> &,
                                                    std::vector<Vec3> &);
  template void xsph_corrections<WendlandC2Kernel>(const SphParticles &, const SphPairs &,
                                                   const PeriodicBox &, double,
                                                   const std::vector<Vec3> &,
                                                   std::vector<Vec3> &);
} // namespace sluice
