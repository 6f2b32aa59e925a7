// Solid walls of wall particles (see the header).

#include <sluice/sph/sph_boundary.h>
#include <sluice/sph/sph_kernel.h>

#include <algorithm>

namespace sluice
{
  template <typename Kernel>
  void WallStates::update(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                          const TaitEquation &state, const Vec3 &gravity)
  {
    const unsigned int  n = P.size();
    std::vector<double> weight(n, 0.), pressure(n, 0.);
    std::vector<Vec3>   momentum(n), velocity(n);
    // A wall particle's sums over the fluid particles of its pairs.
    const auto add = [&](const unsigned int w, const unsigned int f, const Vec3 &r_wf,
                         const double r) {
      const double W = kernel_value<Kernel>(r, P.smoothing[w]);
      weight[w] += W;
      pressure[w] += P.pressure[f] * W;
      momentum[w] += (P.density[f] * W) * r_wf;
      velocity[w] += W * P.velocity[f];
    };
    for (unsigned int a = 0; a < P.n_local; ++a)
      for (unsigned int k = pairs.offset[a]; k < pairs.offset[a + 1]; ++k)
        {
          const unsigned int b = pairs.partner[k];
          if (P.wall[a] == P.wall[b])
            continue;
          Vec3 d = P.position[a] - P.position[b];
          if (box.any_periodic)
            d = box.minimum_image(d);
          const double r = norm(d);
          if (P.wall[a])
            add(a, b, d, r);
          else if (b < P.n_local)
            add(b, a, -1. * d, r);
        }
    no_slip.assign(P.velocity.begin(), P.velocity.end());
    for (unsigned int w = 0; w < P.n_local; ++w)
      if (P.wall[w])
        {
          if (weight[w] > 0.)
            {
              const Vec3 a_w; // walls at rest or moving uniformly
              P.pressure[w] = std::max(
                0., (pressure[w] + dot(gravity - a_w, momentum[w])) / weight[w]);
              no_slip[w] = 2. * P.wall_velocity[w] - (1. / weight[w]) * velocity[w];
            }
          else
            {
              P.pressure[w] = 0.;
              no_slip[w]    = P.wall_velocity[w];
            }
          P.density[w]  = state.density(P.pressure[w], P.porosity[w]);
          P.omega[w]    = 1.;
          P.velocity[w] = P.wall_velocity[w];
        }
  }

  template void WallStates::update<CubicSplineKernel>(SphParticles &, const SphPairs &,
                                                      const PeriodicBox &, const TaitEquation &,
                                                      const Vec3 &);
  template void WallStates::update<WendlandC2Kernel>(SphParticles &, const SphPairs &,
                                                     const PeriodicBox &, const TaitEquation &,
                                                     const Vec3 &);
} // namespace sluice
