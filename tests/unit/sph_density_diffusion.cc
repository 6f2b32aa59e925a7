// delta-SPH's diffusive term (sph/sph_density_diffusion.h):
// - it moves density between particles without changing sum_a V_a rho_a:
//   on a jittered periodic lattice with densities and h varying, sum_a V_a
//   drho_a/dt is zero to round-off;
// - a column at rest, its density linear in depth as the hydrostatic one
//   (rho_0 + rho_0 g.x / c_s^2), gets no diffusion anywhere, its free faces
//   included (the hydrostatic correction); without the correction the
//   faces would diffuse;
// - a density wave rho_0 (1 + A sin(k x)) decays at delta hbar c_s times the
//   SPH Laplacian: against the continuum's -k^2, within 8% at 16 spacings a
//   wavelength and 4 times closer at 32 (second order).

#include <sluice/sph/sph_density.h>
#include <sluice/sph/sph_density_diffusion.h>
#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_pairs.h>

#include "check.h"
#include "sph_lattice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double rho_0 = 1000., dx = 1e-3, c_s = 5.;

  SphParticles lattice(const unsigned int nx, const unsigned int ny, const unsigned int nz,
                       const double jitter = 0., const double spread = 0.)
  {
    return sluice::unit::sph_lattice(nx, ny, nz, dx, rho_0, jitter, 0.01 * spread, 0.2 * spread);
  }

  DensityDiffusion diffusion(const Vec3 &gravity)
  {
    DensityDiffusion d;
    d.delta             = 0.1;
    d.sound_speed       = c_s;
    d.reference_density = rho_0;
    d.gravity           = gravity;
    return d;
  }

  template <typename Kernel>
  void check_conservation()
  {
    const std::string name = Kernel::name;
    SphParticles      P    = lattice(8, 8, 8, 0.3, 1.);
    const PeriodicBox box(Vec3(), 8. * dx * Vec3(1., 1., 1.), {{true, true, true}});
    SphPairs          pairs;
    pairs.build(P, box, 0.);
    add_density_diffusion<Kernel>(P, pairs, box, diffusion(Vec3(0., 0., -9.81)));
    double sum = 0., scale = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        sum += P.mass[a] / P.density[a] * P.density_rate[a];
        scale += std::abs(P.mass[a] / P.density[a] * P.density_rate[a]);
      }
    std::printf("%s: sum V drho/dt = %.3g of sum |V drho/dt|\n", Kernel::name, sum / scale);
    check(scale > 0. && std::abs(sum) < 1e-13 * scale, (name + ": conservation").c_str(),
          sum / scale, 0.);
  }

  template <typename Kernel>
  void check_hydrostatic()
  {
    const std::string name = Kernel::name;
    const Vec3        g(0., 0., -9.81);
    SphParticles      P = lattice(8, 8, 8);
    for (unsigned int a = 0; a < P.size(); ++a)
      P.density[a] = rho_0 + rho_0 * dot(g, P.position[a]) / (c_s * c_s);
    const PeriodicBox box(-dx * Vec3(1., 1., 1.), 9. * dx * Vec3(1., 1., 1.), {{false, false, false}});
    SphPairs          pairs;
    pairs.build(P, box, 0.);
    add_density_diffusion<Kernel>(P, pairs, box, diffusion(g));
    double worst = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      worst = std::max(worst, std::abs(P.density_rate[a]));
    // Without the correction the top and bottom faces diffuse: a scale for 'worst'.
    SphParticles Q = P;
    for (double &r : Q.density_rate)
      r = 0.;
    add_density_diffusion<Kernel>(Q, pairs, box, diffusion(Vec3()));
    double uncorrected = 0.;
    for (unsigned int a = 0; a < Q.n_local; ++a)
      uncorrected = std::max(uncorrected, std::abs(Q.density_rate[a]));
    std::printf("%s: hydrostatic block: largest rate %.3g, %.3g without the correction\n",
                Kernel::name, worst, uncorrected);
    check(worst < 1e-12 * uncorrected, (name + ": a hydrostatic column stays").c_str(), worst,
          0.);
  }

  /// The ratio of the measured decay rate to the continuum's at the crest.
  template <typename Kernel>
  double wave_ratio(const unsigned int wavelength)
  {
    SphParticles      P = lattice(wavelength, 8, 8);
    const double      k = 2. * M_PI / (wavelength * dx), A = 1e-3;
    const PeriodicBox box(Vec3(), dx * Vec3(wavelength, 8., 8.), {{true, true, true}});
    for (unsigned int a = 0; a < P.size(); ++a)
      P.density[a] = rho_0 * (1. + A * std::sin(k * P.position[a].x));
    smoothing_lengths(P, 1.5);
    SphPairs pairs;
    pairs.build(P, box, 0.);
    add_density_diffusion<Kernel>(P, pairs, box, diffusion(Vec3()));
    // The particle nearest the crest, sin(k x) = 1.
    double best = 0., ratio = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        const double s = std::sin(k * P.position[a].x);
        if (s > best)
          {
            best = s;
            const double continuum =
              0.1 * P.smoothing[a] * c_s * (-k * k) * (P.density[a] - rho_0);
            ratio = P.density_rate[a] / continuum;
          }
      }
    return ratio;
  }

  template <typename Kernel>
  void check_wave()
  {
    const std::string name = Kernel::name;
    const double      coarse = wave_ratio<Kernel>(16), fine = wave_ratio<Kernel>(32);
    std::printf("%s: wave decay against the continuum: %.5f (16 dx), %.5f (32 dx)\n",
                Kernel::name, coarse, fine);
    check(std::abs(coarse - 1.) < 0.08, (name + ": the wave's decay, 16 dx").c_str(), coarse, 1.);
    check(std::abs(fine - 1.) < 0.3 * std::abs(coarse - 1.),
          (name + ": second order in the wavelength").c_str(), fine, 1.);
  }
} // namespace

int main()
{
  check_conservation<CubicSplineKernel>();
  check_conservation<WendlandC2Kernel>();
  check_hydrostatic<CubicSplineKernel>();
  check_hydrostatic<WendlandC2Kernel>();
  check_wave<CubicSplineKernel>();
  check_wave<WendlandC2Kernel>();
  if (sluice::unit::failures == 0)
    std::printf("sph density diffusion: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
