// XSPH's drift correction (sph/sph_xsph.h), on a jittered periodic lattice
// with densities and h varying:
// - it moves no momentum: sum_a m_a dv_a vanishes to round-off for random
//   velocities;
// - a uniform velocity gets none;
// - a particle moving against still neighbours is slowed by epsilon times
//   the kernel-weighted share of them, 2 sum_b m_b W / (rho_a + rho_b) of its
//   speed (the sum computed here directly), and each neighbour pulled along;
// - wall particles neither get a correction nor give one.

#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_xsph.h>

#include "check.h"
#include "sph_lattice.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double rho_0 = 1000., dx = 1e-3, epsilon = 0.5;

  template <typename Kernel>
  void check_xsph()
  {
    const std::string  name = Kernel::name;
    const unsigned int n    = 8;
    SphParticles       P    = sluice::unit::sph_lattice(n, n, n, dx, rho_0, 0.2, 0.01, 0.2, 3);
    const PeriodicBox  box(Vec3(), n * dx * Vec3(1., 1., 1.), {{true, true, true}});
    SphPairs           pairs;
    pairs.build(P, box, 0.);
    std::mt19937                           random(9);
    std::uniform_real_distribution<double> u(-1., 1.);
    std::vector<Vec3>                      v(P.size());
    for (Vec3 &w : v)
      w = Vec3(u(random), u(random), u(random));

    // Momentum.
    std::vector<Vec3> c;
    xsph_corrections<Kernel>(P, pairs, box, epsilon, v, c);
    Vec3   sum;
    double scale = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      sum += P.mass[a] * c[a], scale += P.mass[a] * norm(c[a]);
    check(scale > 0. && norm(sum) < 1e-14 * scale, (name + ": no momentum moved").c_str(),
          norm(sum) / scale, 0.);

    // A uniform velocity.
    std::vector<Vec3> uniform(P.size(), Vec3(0.3, -0.1, 0.2));
    xsph_corrections<Kernel>(P, pairs, box, epsilon, uniform, c);
    double largest = 0.;
    for (const Vec3 &w : c)
      largest = std::max(largest, norm(w));
    check(largest < 1e-15, (name + ": a uniform velocity").c_str(), largest, 0.);

    // One particle moving against still neighbours.
    std::vector<Vec3> one(P.size());
    const unsigned int moving = 100;
    one[moving]               = Vec3(1., 0., 0.);
    xsph_corrections<Kernel>(P, pairs, box, epsilon, one, c);
    double share = 0.;
    for (unsigned int b = 0; b < P.size(); ++b)
      if (b != moving)
        {
          const double r = norm(box.minimum_image(P.position[moving] - P.position[b]));
          share += 2. * P.mass[b] *
                   kernel_value<Kernel>(r, 0.5 * (P.smoothing[moving] + P.smoothing[b])) /
                   (P.density[moving] + P.density[b]);
        }
    std::printf("%s: the moving particle's correction %.6f, expected %.6f\n", Kernel::name,
                c[moving].x, -epsilon * share);
    check(std::abs(c[moving].x + epsilon * share) < 1e-13 && c[moving].y == 0.,
          (name + ": a particle against still neighbours").c_str(), c[moving].x,
          -epsilon * share);

    // Walls out: the moving particle a wall, nothing anywhere.
    P.wall[moving] = 1;
    xsph_corrections<Kernel>(P, pairs, box, epsilon, one, c);
    largest = 0.;
    for (const Vec3 &w : c)
      largest = std::max(largest, norm(w));
    check(largest == 0., (name + ": walls take no part").c_str(), largest, 0.);
  }
} // namespace

int main()
{
  check_xsph<CubicSplineKernel>();
  check_xsph<WendlandC2Kernel>();
  if (sluice::unit::failures == 0)
    std::printf("sph xsph: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
