// What the SPH fluid and the DEM's particles exchange (see the header).

#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_solid_exchange.h>

#include <cmath>

namespace sluice
{
  template <typename Kernel>
  void SphSolidPairs::build(const SphParticles &P, const SolidPoints &solids,
                            const PeriodicBox &box, const double coupling_length)
  {
    const unsigned int n_sph = P.n_local, n_solid = solids.position.size();
    const double       reach = Kernel::support * coupling_length;
    all.assign(P.position.begin(), P.position.begin() + n_sph);
    all.insert(all.end(), solids.position.begin(), solids.position.end());
    grid.build(all, n_sph + n_solid, box, reach);

    // Along a periodic direction narrower than twice the reach, a pair has
    // more than one image within it, and each adds to the sums: the shifts
    // of the minimum image to try (only the zero shift otherwise).
    std::vector<Vec3> shifts{Vec3()};
    for (unsigned int k = 0; k < 3; ++k)
      if (box.periodic[k] && reach > 0.5 * box.length[k])
        {
          const int         m = static_cast<int>(std::ceil(reach / box.length[k]));
          std::vector<Vec3> more;
          for (const Vec3 &s : shifts)
            for (int j = -m; j <= m; ++j)
              {
                Vec3 t = s;
                t[k] += j * box.length[k];
                more.push_back(t);
              }
          shifts = std::move(more);
        }

    offset.assign(n_solid + 1, 0);
    partner.clear(), weight.clear(), kernel.clear();
    weight_sum.assign(n_solid, 0.);
    for (unsigned int i = 0; i < n_solid; ++i)
      {
        grid.stencil(n_sph + i, stencil);
        for (const unsigned int cell : stencil)
          for (unsigned int k = grid.cell_start[cell]; k < grid.cell_start[cell + 1]; ++k)
            {
              const unsigned int a = grid.cell_particles[k];
              if (a >= n_sph || P.wall[a])
                continue;
              Vec3 image = solids.position[i] - P.position[a];
              if (box.any_periodic)
                image = box.minimum_image(image);
              for (const Vec3 &shift : shifts)
                {
                  const Vec3   d = image + shift;
                  const double r = norm(d);
                  if (r >= reach)
                    continue;
                  const double W = kernel_value<Kernel>(r, coupling_length);
                  partner.push_back(a);
                  kernel.push_back(W);
                  weight.push_back(P.mass[a] / P.density[a] * W);
                  weight_sum[i] += weight.back();
                }
            }
        offset[i + 1] = partner.size();
      }
  }

  template <typename Kernel>
  std::vector<double> SphSolidPairs::fluid_fractions(const SphParticles &P,
                                                     const SolidPoints &solids) const
  {
    std::vector<double> eps(P.size(), 1.);
    for (unsigned int i = 0; i + 1 < offset.size(); ++i)
      for (unsigned int k = offset[i]; k < offset[i + 1]; ++k)
        eps[partner[k]] -= solids.volume[i] * kernel[k];
    return eps;
  }

  template <typename Value>
  std::vector<Value> SphSolidPairs::weighted_sums(const std::vector<Value> &field) const
  {
    std::vector<Value> sums(offset.size() - 1);
    for (unsigned int i = 0; i + 1 < offset.size(); ++i)
      for (unsigned int k = offset[i]; k < offset[i + 1]; ++k)
        sums[i] += weight[k] * field[partner[k]];
    return sums;
  }

  template <typename Value>
  std::vector<Value> SphSolidPairs::normalised(std::vector<Value> sums,
                                               const Value       &fallback) const
  {
    for (unsigned int i = 0; i < sums.size(); ++i)
      sums[i] = weight_sum[i] > 0. ? (1. / weight_sum[i]) * sums[i] : fallback;
    return sums;
  }

  std::vector<Vec3> SphSolidPairs::spread(const std::vector<Vec3> &solid_forces,
                                          const unsigned int n_sph) const
  {
    std::vector<Vec3> force(n_sph);
    for (unsigned int i = 0; i + 1 < offset.size(); ++i)
      if (weight_sum[i] > 0.)
        for (unsigned int k = offset[i]; k < offset[i + 1]; ++k)
          force[partner[k]] -= (weight[k] / weight_sum[i]) * solid_forces[i];
    return force;
  }

  unsigned int SphSolidPairs::n_unreached() const
  {
    unsigned int n = 0;
    for (const double S : weight_sum)
      n += !(S > 0.);
    return n;
  }

#define SLUICE_SPH_SOLID_EXCHANGE(Kernel)                                                    \
  template void SphSolidPairs::build<Kernel>(const SphParticles &, const SolidPoints &,      \
                                             const PeriodicBox &, double);                   \
  template std::vector<double> SphSolidPairs::fluid_fractions<Kernel>(const SphParticles &, \
                                                                      const SolidPoints &) const;
  SLUICE_SPH_SOLID_EXCHANGE(CubicSplineKernel)
  SLUICE_SPH_SOLID_EXCHANGE(WendlandC2Kernel)
#undef SLUICE_SPH_SOLID_EXCHANGE
  template std::vector<double> SphSolidPairs::weighted_sums(const std::vector<double> &) const;
  template std::vector<Vec3>   SphSolidPairs::weighted_sums(const std::vector<Vec3> &) const;
  template std::vector<double> SphSolidPairs::normalised(std::vector<double>, const double &) const;
  template std::vector<Vec3>   SphSolidPairs::normalised(std::vector<Vec3>, const Vec3 &) const;
} // namespace sluice
