// The density side of an SPH step (sph/sph_density.h, sph/sph_pairs.h):
// - the pairs: on a jittered periodic lattice with smoothing lengths varying
//   by 30%, every pair within 2 max(h_a, h_b) that a brute-force search over
//   all pairs and periodic images finds, and no other;
// - on a periodic simple cubic lattice (spacing dx, m = rho_0 dx^3,
//   h = 1.5 dx): the summation density is the lattice constant of the kernel
//   at every particle, to round-off, and smoothing_lengths() gives h back;
// - Omega against its definition by central differences of the summation
//   density in h: 1 + h / (3 rho) d(rho)/dh;
// - the continuity equation: zero for a uniform translation (round-off), and
//   for a linear expansion v = alpha (x - c) of an open block, -3 alpha rho
//   at the block's centre to round-off. That is exact, not approximate:
//   with dW/dh = -(3 W + r dW/dr) / h, sum_b m_b r W' = -3 rho Omega, so
//   Price's 1/Omega turns the lattice's divergence into the continuum's;
// - the step's one pass for Omega and the continuity sums gives both to the
//   bit as the two separate functions do (jittered lattice, h and
//   velocities varying, pairs with a skin), and the kernel derivatives it
//   keeps for the accelerations are pair_kernels' to the bit, 0 in the skin;
// - with a fixed smoothing length (grad_h = false) both give Omega = 1 and
//   the same continuity sums to the bit, the sums with Omega times Omega
//   (1e-13).

#include <sluice/sph/sph_density.h>
#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_pairs.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <utility>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double rho_0 = 1000., dx = 1e-3;

  /// n^3 particles on a lattice of spacing dx from 'lower' + dx/2.
  SphParticles lattice(const unsigned int n, const Vec3 &lower, const double jitter = 0.,
                       const double h_spread = 0.)
  {
    std::mt19937                           random(11);
    std::uniform_real_distribution<double> u(-1., 1.);
    SphParticles                           P;
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int i = 0; i < n; ++i)
          {
            const Vec3 x = lower + dx * Vec3(i + 0.5 + jitter * u(random),
                                             j + 0.5 + jitter * u(random),
                                             k + 0.5 + jitter * u(random));
            P.push_back(P.size(), x, rho_0 * dx * dx * dx, rho_0,
                        1.5 * dx * (1. + h_spread * u(random)));
          }
    P.n_local = P.size();
    return P;
  }

  PeriodicBox periodic_cube(const unsigned int n)
  {
    return PeriodicBox(Vec3(), Vec3(n * dx, n * dx, n * dx), {{true, true, true}});
  }

  void check_pairs()
  {
    const unsigned int n   = 8;
    SphParticles       P   = lattice(n, Vec3(), 0.3, 0.3);
    const PeriodicBox  box = periodic_cube(n);
    SphPairs           pairs;
    pairs.build(P, box, 0.);
    std::set<std::pair<unsigned int, unsigned int>> listed, found;
    for (unsigned int a = 0; a < P.n_local; ++a)
      for (unsigned int k = pairs.offset[a]; k < pairs.offset[a + 1]; ++k)
        listed.insert({std::min(a, pairs.partner[k]), std::max(a, pairs.partner[k])});
    for (unsigned int a = 0; a < P.size(); ++a)
      for (unsigned int b = a + 1; b < P.size(); ++b)
        {
          // Every image, not only the nearest.
          double closest = 1e300;
          for (int i = -1; i <= 1; ++i)
            for (int j = -1; j <= 1; ++j)
              for (int k = -1; k <= 1; ++k)
                closest = std::min(closest, norm(P.position[a] - P.position[b] +
                                                 (n * dx) * Vec3(i, j, k)));
          if (closest < 2. * std::max(P.smoothing[a], P.smoothing[b]))
            found.insert({a, b});
        }
    std::printf("pairs: %zu listed, %zu by brute force\n", listed.size(), found.size());
    check(listed == found, "pairs: the brute-force set", listed.size(), found.size());
  }

  template <typename Kernel>
  void check_lattice()
  {
    const std::string  name = Kernel::name;
    const unsigned int n    = 10;
    SphParticles       P    = lattice(n, Vec3());
    const PeriodicBox  box  = periodic_cube(n);
    SphPairs           pairs;
    pairs.build(P, box, 0.);
    summation_density<Kernel>(P, pairs, box);
    // The lattice constant of the kernel, summed directly.
    double constant = 0.;
    for (int i = -4; i <= 4; ++i)
      for (int j = -4; j <= 4; ++j)
        for (int k = -4; k <= 4; ++k)
          constant += kernel_value<Kernel>(dx * std::sqrt(double(i * i + j * j + k * k)), 1.5 * dx);
    constant *= rho_0 * dx * dx * dx;
    double worst = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      worst = std::max(worst, std::abs(P.density[a] - constant) / constant);
    check(worst < 1e-13, (name + ": summation density on the lattice").c_str(), worst, 0.);
    std::printf("%s: lattice density %.6f rho_0\n", Kernel::name, constant / rho_0);

    // Omega against differences of the summation in h.
    correction_factors<Kernel>(P, pairs, box);
    const double d     = 1e-6 * dx;
    auto         shift = [&](const double by) {
      SphParticles Q = P;
      for (double &h : Q.smoothing)
        h += by;
      summation_density<Kernel>(Q, pairs, box);
      return Q.density[0];
    };
    const double slope = (shift(d) - shift(-d)) / (2. * d);
    const double omega = 1. + 1.5 * dx / (3. * P.density[0]) * slope;
    std::printf("%s: Omega %.10f (differences %.10f)\n", Kernel::name, P.omega[0], omega);
    check(std::abs(P.omega[0] - omega) < 1e-7, (name + ": Omega").c_str(), P.omega[0], omega);

    // h from the density, and back.
    SphParticles Q = P;
    smoothing_lengths(Q, 1.5 * std::cbrt(constant / rho_0));
    check(std::abs(Q.smoothing[7] - 1.5 * dx) < 1e-15, (name + ": h from the density").c_str(),
          Q.smoothing[7], 1.5 * dx);

    // A uniform translation does not compress.
    for (Vec3 &v : P.velocity)
      v = Vec3(0.3, -0.2, 0.1);
    density_rates<Kernel>(P, pairs, box);
    double rate = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      rate = std::max(rate, std::abs(P.density_rate[a]));
    check(rate < 1e-9, (name + ": no compression in a translation").c_str(), rate, 0.);
  }

  template <typename Kernel>
  void check_expansion()
  {
    const std::string  name = Kernel::name;
    const unsigned int n    = 15;
    SphParticles       P    = lattice(n, Vec3());
    const PeriodicBox  box(Vec3(-dx, -dx, -dx), Vec3(n + 1, n + 1, n + 1) * dx, {{false, false, false}});
    SphPairs           pairs;
    pairs.build(P, box, 0.);
    summation_density<Kernel>(P, pairs, box);
    correction_factors<Kernel>(P, pairs, box);
    const Vec3   centre = 0.5 * n * dx * Vec3(1., 1., 1.);
    const double alpha  = 0.7; // [1/s]
    for (unsigned int a = 0; a < P.size(); ++a)
      P.velocity[a] = alpha * (P.position[a] - centre);
    density_rates<Kernel>(P, pairs, box);
    const unsigned int middle = (n / 2) * (1 + n + n * n);
    const double       exact  = -3. * alpha * P.density[middle];
    std::printf("%s: expansion rate %.6f, continuum %.6f\n", Kernel::name,
                P.density_rate[middle], exact);
    check(std::abs(P.density_rate[middle] - exact) < 1e-12 * std::abs(exact),
          (name + ": a linear expansion").c_str(), P.density_rate[middle], exact);
  }
} // namespace

namespace
{
  template <typename Kernel>
  void check_one_pass()
  {
    const std::string  name = Kernel::name;
    const unsigned int n    = 8;
    SphParticles       P    = lattice(n, Vec3(), 0.3, 0.3);
    const PeriodicBox  box  = periodic_cube(n);
    std::mt19937                           random(3);
    std::uniform_real_distribution<double> u(-1., 1.);
    for (unsigned int a = 0; a < P.size(); ++a)
      P.velocity[a] = Vec3(u(random), u(random), u(random));
    SphPairs pairs;
    pairs.build(P, box, 0.5 * dx); // with a skin: pairs beyond both supports too
    summation_density<Kernel>(P, pairs, box);
    SphParticles Q = P, fixed_two = P, fixed_one = P;
    correction_factors<Kernel>(P, pairs, box);
    density_rates<Kernel>(P, pairs, box);
    SphPairKernels kept, alone;
    correction_factors_and_density_rates<Kernel>(Q, pairs, box, kept);
    const bool same = P.omega == Q.omega && P.density_rate == Q.density_rate;
    std::printf("%s: one pass for Omega and drho/dt %s the two\n", Kernel::name,
                same ? "equals" : "differs from");
    check(same, (name + ": one pass equals the two, to the bit").c_str(), same, 1.);

    // The kernels the pass keeps for the accelerations are pair_kernels'
    // to the bit, r is |d|, and beyond both supports dW/dr is 0.
    pair_kernels<Kernel>(Q, pairs, box, alone);
    const bool kept_same = kept.r == alone.r && kept.dW_a == alone.dW_a &&
                           kept.dW_b == alone.dW_b && kept.r.size() == pairs.partner.size();
    check(kept_same, (name + ": the kept kernels are pair_kernels'").c_str(), kept_same, 1.);
    unsigned int in_skin = 0;
    double       worst   = 0.;
    for (unsigned int a = 0; a < Q.n_local; ++a)
      for (unsigned int k = pairs.offset[a]; k < pairs.offset[a + 1]; ++k)
        {
          const unsigned int b = pairs.partner[k];
          const double       r = norm(box.minimum_image(Q.position[a] - Q.position[b]));
          worst                = std::max(worst, std::abs(kept.r[k] - r));
          if (!(r < Kernel::support * std::max(Q.smoothing[a], Q.smoothing[b])))
            {
              ++in_skin;
              worst = std::max({worst, std::abs(kept.dW_a[k]), std::abs(kept.dW_b[k])});
            }
        }
    std::printf("%s: %u of %zu pairs in the skin\n", Kernel::name, in_skin,
                pairs.partner.size());
    check(in_skin > 0 && worst == 0., (name + ": r exact, dW/dr 0 in the skin").c_str(), worst,
          0.);

    // A fixed h: no Omega, in either form.
    correction_factors<Kernel>(fixed_two, pairs, box, false);
    density_rates<Kernel>(fixed_two, pairs, box);
    SphPairKernels unused;
    correction_factors_and_density_rates<Kernel>(fixed_one, pairs, box, unused, false);
    bool   ones     = true;
    double deviation = 0., largest = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        ones      = ones && fixed_two.omega[a] == 1. && fixed_one.omega[a] == 1.;
        deviation = std::max(deviation, std::abs(fixed_one.density_rate[a] -
                                                 P.density_rate[a] * P.omega[a]));
        largest   = std::max(largest, std::abs(fixed_one.density_rate[a]));
      }
    const bool fixed_same = ones && fixed_one.density_rate == fixed_two.density_rate;
    std::printf("%s: fixed h: Omega = 1 %s, the sums against Omega drho/dt %.1e\n", Kernel::name,
                fixed_same ? "in both forms, the same sums" : "NOT in both forms",
                deviation / largest);
    check(fixed_same, (name + ": fixed h, Omega = 1 and the same sums").c_str(), fixed_same, 1.);
    check(deviation < 1e-13 * largest, (name + ": fixed h, the plain continuity sums").c_str(),
          deviation / largest, 0.);
  }
} // namespace

int main()
{
  check_pairs();
  check_lattice<CubicSplineKernel>();
  check_lattice<WendlandC2Kernel>();
  check_expansion<CubicSplineKernel>();
  check_expansion<WendlandC2Kernel>();
  check_one_pass<CubicSplineKernel>();
  check_one_pass<WendlandC2Kernel>();
  if (sluice::unit::failures == 0)
    std::printf("sph density: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
