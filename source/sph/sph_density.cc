// The density side of an SPH step (see the header).

#include <sluice/sph/sph_density.h>
#include <sluice/sph/sph_kernel.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  template <typename Kernel>
  void summation_density(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box)
  {
    // A wall particle keeps the density its pressure gives it (sph_boundary.h).
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        P.density[a] = P.mass[a] * kernel_value<Kernel>(0., P.smoothing[a]);
    for_each_pair(P, pairs, box, [&](const unsigned int a, const unsigned int b, const Vec3 &,
                                     const double r) {
      if (!P.wall[a])
        P.density[a] += P.mass[b] * kernel_value<Kernel>(r, P.smoothing[a]);
      if (b < P.n_local && !P.wall[b])
        P.density[b] += P.mass[a] * kernel_value<Kernel>(r, P.smoothing[b]);
    });
  }

  void smoothing_lengths(SphParticles &P, const double sigma)
  {
    for (unsigned int a = 0; a < P.size(); ++a)
      P.smoothing[a] = sigma * std::cbrt(P.mass[a] / P.density[a]);
  }

  template <typename Kernel>
  void correction_factors(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                          const bool grad_h)
  {
    if (!grad_h)
      {
        std::fill(P.omega.begin(), P.omega.begin() + P.n_local, 1.);
        return;
      }
    // The sums of m_b dW/dh first, in 'omega'.
    for (unsigned int a = 0; a < P.n_local; ++a)
      P.omega[a] = P.mass[a] * kernel_h_derivative<Kernel>(0., P.smoothing[a]);
    for_each_pair(P, pairs, box, [&](const unsigned int a, const unsigned int b, const Vec3 &,
                                     const double r) {
      P.omega[a] += P.mass[b] * kernel_h_derivative<Kernel>(r, P.smoothing[a]);
      if (b < P.n_local)
        P.omega[b] += P.mass[a] * kernel_h_derivative<Kernel>(r, P.smoothing[b]);
    });
    for (unsigned int a = 0; a < P.n_local; ++a)
      P.omega[a] = 1. + P.smoothing[a] / (3. * P.density[a]) * P.omega[a];
  }

  template <typename Kernel>
  void density_rates(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box)
  {
    for (unsigned int a = 0; a < P.n_local; ++a)
      P.density_rate[a] = 0.;
    for_each_pair(P, pairs, box, [&](const unsigned int a, const unsigned int b, const Vec3 &d,
                                     const double r) {
      if (!(r > 0.))
        return;
      // (v_a - v_b) . grad_a W(r, h) = dW/dr (v_ab . d) / r, and the same
      // from b's side with d and v_ab both reversed.
      const double vd = dot(P.velocity[a] - P.velocity[b], d) / r;
      P.density_rate[a] += P.mass[b] * kernel_radial_derivative<Kernel>(r, P.smoothing[a]) * vd;
      if (b < P.n_local)
        P.density_rate[b] += P.mass[a] * kernel_radial_derivative<Kernel>(r, P.smoothing[b]) * vd;
    });
    for (unsigned int a = 0; a < P.n_local; ++a)
      P.density_rate[a] /= P.omega[a];
  }

  template <typename Kernel>
  void correction_factors_and_density_rates(SphParticles &P, const SphPairs &pairs,
                                            const PeriodicBox &box, SphPairKernels &kernels,
                                            const bool grad_h)
  {
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        P.omega[a]        = P.mass[a] * kernel_h_derivative<Kernel>(0., P.smoothing[a]);
        P.density_rate[a] = 0.;
      }
    kernels.reset(pairs.partner.size());
    for_each_indexed_pair(P, pairs, box, [&](const unsigned int k, const unsigned int a,
                                             const unsigned int b, const Vec3 &d,
                                             const double r) {
      const double ha = P.smoothing[a], hb = P.smoothing[b];
      kernels.r[k]    = r;
      if (!(r < Kernel::support * std::max(ha, hb))) // in the list's skin: all terms vanish
        return;
      if (grad_h)
        {
          P.omega[a] += P.mass[b] * kernel_h_derivative<Kernel>(r, ha);
          if (b < P.n_local)
            P.omega[b] += P.mass[a] * kernel_h_derivative<Kernel>(r, hb);
        }
      if (!(r > 0.))
        return;
      kernels.dW_a[k] = kernel_radial_derivative<Kernel>(r, ha);
      kernels.dW_b[k] = kernel_radial_derivative<Kernel>(r, hb);
      const double vd = dot(P.velocity[a] - P.velocity[b], d) / r;
      P.density_rate[a] += P.mass[b] * kernels.dW_a[k] * vd;
      if (b < P.n_local)
        P.density_rate[b] += P.mass[a] * kernels.dW_b[k] * vd;
    });
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        P.omega[a] = grad_h ? 1. + P.smoothing[a] / (3. * P.density[a]) * P.omega[a] : 1.;
        P.density_rate[a] /= P.omega[a];
      }
  }

  template <typename Kernel>
  void correction_factors_and_density_rates(SphParticles &P, const SphPairs &pairs,
                                            const PeriodicBox &box)
  {
    SphPairKernels kernels;
    correction_factors_and_density_rates<Kernel>(P, pairs, box, kernels);
  }

  template <typename Kernel>
  void pair_kernels(const SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                    SphPairKernels &kernels)
  {
    kernels.reset(pairs.partner.size());
    for_each_indexed_pair(P, pairs, box, [&](const unsigned int k, const unsigned int a,
                                             const unsigned int b, const Vec3 &,
                                             const double r) {
      kernels.r[k] = r;
      if (r > 0. && r < Kernel::support * std::max(P.smoothing[a], P.smoothing[b]))
        {
          kernels.dW_a[k] = kernel_radial_derivative<Kernel>(r, P.smoothing[a]);
          kernels.dW_b[k] = kernel_radial_derivative<Kernel>(r, P.smoothing[b]);
        }
    });
  }

  // The two kernels of sph_kernel.h.
#define SLUICE_SPH_DENSITY(Kernel)                                                                \
  template void summation_density<Kernel>(SphParticles &, const SphPairs &, const PeriodicBox &);  \
  template void correction_factors<Kernel>(SphParticles &, const SphPairs &, const PeriodicBox &,  \
                                           bool);                                               \
  template void density_rates<Kernel>(SphParticles &, const SphPairs &, const PeriodicBox &);    \
  template void correction_factors_and_density_rates<Kernel>(SphParticles &, const SphPairs &,    \
                                                             const PeriodicBox &);              \
  template void correction_factors_and_density_rates<Kernel>(SphParticles &, const SphPairs &,    \
                                                             const PeriodicBox &,               \
                                                             SphPairKernels &, bool);           \
  template void pair_kernels<Kernel>(const SphParticles &, const SphPairs &, const PeriodicBox &, \
                                     SphPairKernels &);
  SLUICE_SPH_DENSITY(CubicSplineKernel)
  SLUICE_SPH_DENSITY(WendlandC2Kernel)
#undef SLUICE_SPH_DENSITY
} // namespace sluice
