// delta-SPH's diffusive term (see the header).

#include <sluice/sph/sph_density_diffusion.h>
#include <sluice/sph/sph_kernel.h>

namespace sluice
{
  template <typename Kernel>
  void add_density_diffusion(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                             const DensityDiffusion &diffusion)
  {
    const double c = diffusion.sound_speed;
    const Vec3   hydrostatic = (diffusion.reference_density / (c * c)) * diffusion.gravity;
    for_each_pair(P, pairs, box, [&](const unsigned int a, const unsigned int b, const Vec3 &d,
                                     const double r) {
      if (P.wall[a] || P.wall[b] || !(r > 0.))
        return;
      const double h_mean = 0.5 * (P.smoothing[a] + P.smoothing[b]);
      const double excess = P.density[a] / P.porosity[a] - P.density[b] / P.porosity[b] -
                            dot(hydrostatic, d);
      // The pair's flux, per unit volume of the receiving particle.
      const double flux = diffusion.delta * h_mean * c * 2. * excess *
                          kernel_radial_derivative<Kernel>(r, h_mean) / r;
      P.density_rate[a] += P.porosity[a] * flux * P.mass[b] / P.density[b];
      if (b < P.n_local)
        P.density_rate[b] -= P.porosity[b] * flux * P.mass[a] / P.density[a];
    });
  }

  template void add_density_diffusion<CubicSplineKernel>(SphParticles &, const SphPairs &,
                                                         const PeriodicBox &,
                                                         const DensityDiffusion &);
  template void add_density_diffusion<WendlandC2Kernel>(SphParticles &, const SphPairs &,
                                                        const PeriodicBox &,
                                                        const DensityDiffusion &);
} // namespace sluice
