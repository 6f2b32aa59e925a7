#pragma once
// The SPH particles' pairs: every pair closer than the larger of the two
// supports, 2 max(h_a, h_b) (Price's variable-h equations evaluate the
// kernel with each particle's own h), plus a skin, from the DEM's cell grid
// (dem/cell_grid.h). Each pair is listed once, from its owned particle with
// the lower index; pairs with ghosts are listed from the owned side. Pairs of
// two wall particles are left out: a wall particle's state comes from the
// fluid around it (sph_boundary.h), and nothing moves it.

#include <sluice/dem/cell_grid.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_particles.h>

#include <vector>

namespace sluice
{
  class SphPairs
  {
  public:
    /// Lists the pairs of P within 2 max(h_a, h_b) + skin.
    void build(const SphParticles &P, const PeriodicBox &box, double skin);

    // Compressed rows: the partners of owned particle a are
    // partner[offset[a]] ... partner[offset[a + 1] - 1].
    std::vector<unsigned int> offset, partner;

  private:
    CellGrid                  grid;
    std::vector<unsigned int> stencil;
  };

  /// Per listed pair, in the list's order: its distance r and the kernel's
  /// radial derivatives dW/dr at h_a and h_b (0 beyond the support). The
  /// step's density pass computes them and its accelerations reuse them: both
  /// see the same positions and smoothing lengths.
  struct SphPairKernels
  {
    std::vector<double> r, dW_a, dW_b;

    /// n pairs, all zero.
    void reset(const std::size_t n)
    {
      r.assign(n, 0.);
      dW_a.assign(n, 0.);
      dW_b.assign(n, 0.);
    }
  };

  /// Calls f(k, a, b, d, r) for every listed pair k: d = x_a - x_b (the
  /// minimum image), r = |d|.
  template <typename Function>
  void for_each_indexed_pair(const SphParticles &P, const SphPairs &pairs,
                             const PeriodicBox &box, const Function &f)
  {
    for (unsigned int a = 0; a < P.n_local; ++a)
      for (unsigned int k = pairs.offset[a]; k < pairs.offset[a + 1]; ++k)
        {
          const unsigned int b = pairs.partner[k];
          Vec3               d = P.position[a] - P.position[b];
          if (box.any_periodic)
            d = box.minimum_image(d);
          f(k, a, b, d, norm(d));
        }
  }

  /// Calls f(a, b, d, r) for every listed pair.
  template <typename Function>
  void for_each_pair(const SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                     const Function &f)
  {
    for_each_indexed_pair(P, pairs, box,
                          [&](const unsigned int, const unsigned int a, const unsigned int b,
                              const Vec3 &d, const double r) { f(a, b, d, r); });
  }
} // namespace sluice
