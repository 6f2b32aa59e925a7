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
    for_each_pair(P, pairs, box, [&](const unsigned int a, const unsigned int b, const Vec3 &,
                                     const double r) {
      if (P.wall[a] || P.wall[b])
        return;
      const double h_mean = 0.5 * (P.smoothing[a] + P.smoothing[b]);
      const double weight =
        2. * epsilon * kernel_value<Kernel>(r, h_mean) / (P.density[a] + P.density[b]);
      const Vec3 v_ba = velocity[b] - velocity[a];
      correction[a] += (P.mass[b] * weight) * v_ba;
      if (b < P.n_local)
        correction[b] -= (P.mass[a] * weight) * v_ba;
    });
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
