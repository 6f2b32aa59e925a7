// What the SPH fluid and the DEM's particles exchange (sph/sph_solid_exchange.h),
// with the coupling length h_c = 1.5 dx:
// - the pairs: every SPH fluid particle within 2 h_c of each solid particle
//   that a brute-force search over all periodic images finds, no other, and
//   no wall particle;
// - the fluid fraction: solids of volume V on a lattice of spacing dx / 2
//   (grains smaller than the SPH spacing, as in Robinson et al.'s scenes),
//   inside a periodic SPH lattice of spacing dx: eps = 1 - V / (dx / 2)^3 at
//   every SPH particle within 1e-4 of the solid fraction (2e-6 with the
//   spline, 1e-5 with Wendland: the kernel's sums over a lattice are not
//   exactly one; over one as coarse as 2 dx, 1.33 h_c, they miss by 6% and
//   14%: h_c must exceed the grains' spacing);
// - Shepard's interpolation: a constant at any point to round-off; a linear
//   field p_0 + G . x at jittered points of a regular SPH lattice within
//   1% of |G| dx (Shepard's weights are centred only up to the lattice's
//   sums);
// - the reaction: on jittered particles with unequal densities, random
//   forces on random solids come back on the SPH particles equal and
//   opposite, to round-off; a solid out of reach samples the fallback and
//   spreads nothing;
// - periodic images: in a box 4 dx wide across, narrower than the kernel's
//   support 2 x 2 h_c, the fluid fractions, Shepard's sums and samples
//   equal those of the same lattice tiled 2 x 2 in a box twice as wide,
//   to round-off (with the minimum image alone Shepard's sums came 2-3%
//   short and eps 6e-4 to 9e-4 high).

#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_solid_exchange.h>

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
  const double       rho_0 = 1000., dx = 1e-3, h_c = 1.5 * dx;
  const unsigned int n     = 12;

  PeriodicBox periodic_cube()
  {
    return PeriodicBox(Vec3(), Vec3(n * dx, n * dx, n * dx), {{true, true, true}});
  }

  SolidPoints random_solids(const unsigned int count, const unsigned int seed)
  {
    std::mt19937                           random(seed);
    std::uniform_real_distribution<double> u(0., n * dx);
    SolidPoints                            S;
    for (unsigned int i = 0; i < count; ++i)
      {
        S.position.emplace_back(u(random), u(random), u(random));
        S.volume.push_back(1e-10);
      }
    return S;
  }

  template <typename Kernel>
  void check_pairs()
  {
    const std::string name = Kernel::name;
    SphParticles      P    = unit::sph_lattice(n, n, n, dx, rho_0, 0.3, 0.01, 0., 7);
    for (unsigned int a = 0; a < P.size(); a += 17)
      P.wall[a] = true;
    const PeriodicBox box = periodic_cube();
    const SolidPoints S   = random_solids(40, 3);
    SphSolidPairs     pairs;
    pairs.build<Kernel>(P, S, box, h_c);
    unsigned int missing = 0, extra = 0;
    for (unsigned int i = 0; i < S.position.size(); ++i)
      {
        std::vector<unsigned int> listed(pairs.partner.begin() + pairs.offset[i],
                                         pairs.partner.begin() + pairs.offset[i + 1]);
        std::sort(listed.begin(), listed.end());
        std::vector<unsigned int> found;
        for (unsigned int a = 0; a < P.size(); ++a)
          {
            double closest = 1e300;
            for (int x = -1; x <= 1; ++x)
              for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z)
                  closest = std::min(closest, norm(S.position[i] - P.position[a] +
                                                   (n * dx) * Vec3(x, y, z)));
            if (closest < 2. * h_c && !P.wall[a])
              found.push_back(a);
          }
        for (const unsigned int a : found)
          missing += !std::binary_search(listed.begin(), listed.end(), a);
        extra += listed.size() + missing - found.size();
      }
    std::printf("%s: solid-SPH pairs: %u missing, %u extra\n", Kernel::name, missing, extra);
    check(missing == 0 && extra == 0, (name + ": the pairs of a brute-force search").c_str(),
          missing + extra, 0.);
  }

  template <typename Kernel>
  void check_fluid_fraction()
  {
    const std::string name = Kernel::name;
    const SphParticles P   = unit::sph_lattice(n, n, n, dx, rho_0);
    SolidPoints        S;
    const double       V = 0.3 * dx * dx * dx / 8.; // a solid fraction of 0.3
    for (unsigned int k = 0; k < 2 * n; ++k)
      for (unsigned int j = 0; j < 2 * n; ++j)
        for (unsigned int i = 0; i < 2 * n; ++i)
          {
            S.position.push_back(0.5 * dx * Vec3(i + 0.25, j + 0.5, k + 0.75));
            S.volume.push_back(V);
          }
    SphSolidPairs pairs;
    pairs.build<Kernel>(P, S, periodic_cube(), h_c);
    const std::vector<double> eps = pairs.fluid_fractions<Kernel>(P, S);
    double                    worst = 0.;
    for (const double e : eps)
      worst = std::max(worst, std::abs((1. - e) / 0.3 - 1.));
    std::printf("%s: solid fraction 0.3 by kernel sums, largest deviation %.2g of it\n",
                Kernel::name, worst);
    check(worst < 1e-4, (name + ": the fluid fraction of a solid lattice").c_str(), worst, 0.);
  }

  template <typename Kernel>
  void check_sampling()
  {
    const std::string  name = Kernel::name;
    const SphParticles P    = unit::sph_lattice(n, n, n, dx, rho_0);
    // Not periodic: a linear field; the solids well inside the block.
    const PeriodicBox box(Vec3(), Vec3(n * dx, n * dx, n * dx), {{false, false, false}});
    SolidPoints       S;
    std::mt19937                           random(9);
    std::uniform_real_distribution<double> u(4. * dx, (n - 4) * dx);
    for (unsigned int i = 0; i < 50; ++i)
      {
        S.position.emplace_back(u(random), u(random), u(random));
        S.volume.push_back(1e-10);
      }
    SphSolidPairs pairs;
    pairs.build<Kernel>(P, S, box, h_c);
    const Vec3          G(3e3, -1e3, 2e3); // [Pa/m]
    std::vector<double> constant(P.size(), 7.5), linear(P.size());
    for (unsigned int a = 0; a < P.size(); ++a)
      linear[a] = 1e4 + dot(G, P.position[a]);
    const std::vector<double> c = pairs.sample(constant, 0.), l = pairs.sample(linear, 0.);
    double constant_error = 0., linear_error = 0.;
    for (unsigned int i = 0; i < S.position.size(); ++i)
      {
        constant_error = std::max(constant_error, std::abs(c[i] / 7.5 - 1.));
        linear_error = std::max(linear_error, std::abs(l[i] - 1e4 - dot(G, S.position[i])));
      }
    std::printf("%s: Shepard: a constant within %.2g, a linear field within %.4f |G| dx\n",
                Kernel::name, constant_error, linear_error / (norm(G) * dx));
    check(constant_error < 1e-14, (name + ": Shepard gives a constant back").c_str(),
          constant_error, 0.);
    check(linear_error < 0.01 * norm(G) * dx, (name + ": Shepard on a linear field").c_str(),
          linear_error, 0.01 * norm(G) * dx);
  }

  template <typename Kernel>
  void check_reaction()
  {
    const std::string name = Kernel::name;
    SphParticles      P    = unit::sph_lattice(n, n, n, dx, rho_0, 0.3, 0.05, 0., 4);
    SolidPoints       S    = random_solids(60, 5);
    std::mt19937                           random(8);
    std::uniform_real_distribution<double> u(-1., 1.);
    std::vector<Vec3>                      f;
    for (unsigned int i = 0; i < S.position.size(); ++i)
      f.emplace_back(u(random), u(random), u(random));
    SphSolidPairs pairs;
    pairs.build<Kernel>(P, S, periodic_cube(), h_c);
    const std::vector<Vec3> F = pairs.spread(f, P.size());
    Vec3                    total;
    double                  scale = 0.;
    for (const Vec3 &x : F)
      total += x;
    for (const Vec3 &x : f)
      total += x, scale += norm(x);
    std::printf("%s: reaction: |sum F_a + sum f_i| = %.3g of sum |f_i|\n", Kernel::name,
                norm(total) / scale);
    check(norm(total) < 1e-14 * scale, (name + ": the reaction is equal and opposite").c_str(),
          norm(total) / scale, 0.);

    // A solid out of reach of an open block samples the fallback and adds nothing.
    const PeriodicBox open(Vec3(), Vec3(n * dx, n * dx, 3. * n * dx), {{false, false, false}});
    SolidPoints       T;
    T.position = {Vec3(0.5, 0.5, 0.5) * (n * dx), Vec3(0.5 * n * dx, 0.5 * n * dx, 2.5 * n * dx)};
    T.volume   = {1e-10, 1e-10};
    pairs.build<Kernel>(P, T, open, h_c);
    const std::vector<Vec3> v = pairs.sample(P.velocity, Vec3(9., 9., 9.));
    const std::vector<Vec3> G = pairs.spread({Vec3(1., 0., 0.), Vec3(0., 1., 0.)}, P.size());
    Vec3                    sum;
    for (const Vec3 &x : G)
      sum += x;
    const bool out = pairs.n_unreached() == 1 && v[1].x == 9. && v[0].x == 0. &&
                     std::abs(sum.x + 1.) < 1e-14 && sum.y == 0.;
    check(out, (name + ": a solid out of reach takes and gives nothing").c_str(),
          pairs.n_unreached(), 1.);
  }

  template <typename Kernel>
  void check_periodic_images()
  {
    const std::string  name = Kernel::name;
    const unsigned int m    = 4, nz = 6; // across: 4 dx < 2 x (2 h_c) = 6 dx
    const SphParticles small = unit::sph_lattice(m, m, nz, dx, rho_0, 0.2, 0.02, 0., 3);
    std::mt19937                           random(4);
    std::uniform_real_distribution<double> u(0., 1.);
    SolidPoints                            S;
    for (unsigned int i = 0; i < 6; ++i)
      {
        S.position.emplace_back(m * dx * u(random), m * dx * u(random), nz * dx * u(random));
        S.volume.push_back(0.1 * dx * dx * dx);
      }
    // The same, tiled 2 x 2 across in a box twice as wide (the minimum
    // image is then the only one in reach).
    SphParticles wide;
    SolidPoints  T;
    for (unsigned int tile = 0; tile < 4; ++tile)
      {
        const Vec3 shift = (m * dx) * Vec3(tile % 2, tile / 2, 0.);
        for (unsigned int a = 0; a < small.size(); ++a)
          wide.push_back(wide.size(), small.position[a] + shift, small.mass[a],
                         small.density[a], small.smoothing[a]);
        for (unsigned int i = 0; i < S.position.size(); ++i)
          {
            T.position.push_back(S.position[i] + shift);
            T.volume.push_back(S.volume[i]);
          }
      }
    wide.n_local = wide.size();
    const PeriodicBox narrow_box(Vec3(), Vec3(m * dx, m * dx, nz * dx), {{true, true, false}});
    const PeriodicBox wide_box(Vec3(), Vec3(2 * m * dx, 2 * m * dx, nz * dx),
                               {{true, true, false}});
    SphSolidPairs narrow_pairs, wide_pairs;
    narrow_pairs.build<Kernel>(small, S, narrow_box, h_c);
    wide_pairs.build<Kernel>(wide, T, wide_box, h_c);
    const std::vector<double> eps_narrow = narrow_pairs.fluid_fractions<Kernel>(small, S);
    const std::vector<double> eps_wide   = wide_pairs.fluid_fractions<Kernel>(wide, T);
    std::vector<double>       field(small.size()), tiled;
    for (unsigned int a = 0; a < small.size(); ++a)
      field[a] = small.position[a].z + 3. * small.position[a].x;
    for (unsigned int tile = 0; tile < 4; ++tile)
      tiled.insert(tiled.end(), field.begin(), field.end());
    const std::vector<double> at_narrow = narrow_pairs.sample(field, 0.);
    const std::vector<double> at_wide   = wide_pairs.sample(tiled, 0.);
    double eps_error = 0., sum_error = 0., sample_error = 0.;
    for (unsigned int a = 0; a < small.size(); ++a)
      eps_error = std::max(eps_error, std::abs(eps_narrow[a] - eps_wide[a]));
    for (unsigned int i = 0; i < S.position.size(); ++i)
      {
        sum_error = std::max(sum_error, std::abs(narrow_pairs.weight_sum[i] /
                                                   wide_pairs.weight_sum[i] - 1.));
        sample_error = std::max(sample_error, std::abs(at_narrow[i] - at_wide[i]));
      }
    std::printf("%s: a box 4 dx across against it tiled 2 x 2: eps within %.2g, Shepard's "
                "sums within %.2g, samples within %.2g m\n",
                Kernel::name, eps_error, sum_error, sample_error);
    check(eps_error < 1e-14 && sum_error < 1e-13 && sample_error < 1e-15,
          (name + ": every periodic image in reach adds to the sums").c_str(),
          std::max(eps_error, sum_error), 0.);
  }
} // namespace

int main()
{
  check_pairs<CubicSplineKernel>();
  check_pairs<WendlandC2Kernel>();
  check_fluid_fraction<CubicSplineKernel>();
  check_fluid_fraction<WendlandC2Kernel>();
  check_sampling<CubicSplineKernel>();
  check_sampling<WendlandC2Kernel>();
  check_reaction<CubicSplineKernel>();
  check_reaction<WendlandC2Kernel>();
  check_periodic_images<CubicSplineKernel>();
  check_periodic_images<WendlandC2Kernel>();
  if (sluice::unit::failures == 0)
    std::printf("sph solid exchange: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
