// The self-induced velocity of self_induced_velocity.h is the fluid's measured
// response convolved with each particle's force history. Checked here on
// made-up tables whose answers are known in closed form:
//  - a steady force on a particle at rest gives the running sum of the
//    response at zero distance, up to the table's length and no further;
//  - the response splits into A F + B (r.F) r (along the offset: 'along',
//    across it: 'across'), linear in |r| between the table's offsets, zero
//    beyond them;
//  - distances are the nearest periodic image; a particle missing from a
//    step forgets its history.

#include <sluice/coupling/self_induced_velocity.h>

#include <deal.II/base/mpi.h>

#include "check.h"

#include <cmath>

using namespace sluice;
using unit::check;
using unit::failures;

namespace
{
  bool near(const Vec3 &a, const Vec3 &b) { return norm(a - b) <= 1e-12 * (1. + norm(b)); }

  SelfResponseTable table(const unsigned int steps, const unsigned int offsets,
                          const double along, const double across, const double spacing)
  {
    SelfResponseTable t;
    t.spacing = spacing;
    for (unsigned int m = 0; m < steps; ++m)
      {
        // A response that decays in time: (m + 1)^-3/2, as diffusion does.
        const double decay = std::pow(m + 1., -1.5);
        t.along.emplace_back(offsets, along * decay);
        t.across.emplace_back(offsets, across * decay);
        t.along.back()[0] = t.across.back()[0] = across * decay; // isotropic at r = 0
      }
    return t;
  }
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  MPI_Comm                                 comm = MPI_COMM_WORLD;
  const PeriodicBox open_box(Vec3(0., 0., 0.), Vec3(1., 1., 1.), {{false, false, false}});

  // 1. Steady force, particle at rest: u_n = sum_{m < min(n, N)} R_m(0) F.
  {
    const unsigned int  N = 5;
    SelfInducedVelocity self(table(N, 4, 1., 1., 0.1), open_box);
    const Vec3          F(0., 0., -2.);
    double              sum = 0.;
    for (unsigned int n = 1; n <= 8; ++n)
      {
        self.record({7}, {F}, {Vec3(0.5, 0.5, 0.5)}, comm);
        if (n <= N)
          sum += std::pow(static_cast<double>(n), -1.5);
        const Vec3 u = self.velocity(7, Vec3(0.5, 0.5, 0.5));
        check(near(u, sum * F), "steady force: running sum of the response", u.z, sum * F.z);
      }
    check(norm(self.velocity(8, Vec3(0.5, 0.5, 0.5))) == 0., "unknown particle: no velocity",
          norm(self.velocity(8, Vec3())), 0.);
  }

  // 2. Along and across the offset, linear in |r|, zero beyond the table.
  {
    SelfResponseTable t = table(1, 5, 3., 1., 0.1);
    for (unsigned int j = 0; j < 5; ++j)
      {
        t.along[0][j]  = 3. * (1. - 0.2 * j); // falls to 0.6 at j = 4
        t.across[0][j] = 1. * (1. - 0.2 * j);
      }
    t.along[0][0] = t.across[0][0] = 1.;
    const Vec3 Fx(1., 0., 0.), Fy(0., 1., 0.);
    const Vec3 r(0.25, 0., 0.); // 2.5 offsets: along 3 (1 - 0.5) = 1.5, across 0.5
    check(near(t.response(0, r, Fx), Vec3(1.5, 0., 0.)), "force along the offset",
          t.response(0, r, Fx).x, 1.5);
    check(near(t.response(0, r, Fy), Vec3(0., 0.5, 0.)), "force across the offset",
          t.response(0, r, Fy).y, 0.5);
    // At 45 degrees: A F + (B (r.F)) r_hat with A = 0.5, B = 1.
    const Vec3 F45(std::sqrt(0.5), std::sqrt(0.5), 0.);
    const Vec3 expected = 0.5 * F45 + (1. * std::sqrt(0.5)) * Vec3(1., 0., 0.);
    check(near(t.response(0, r, F45), expected), "force at 45 degrees",
          t.response(0, r, F45).x, expected.x);
    check(norm(t.response(0, Vec3(0.45, 0., 0.), Fx)) == 0., "beyond the table: zero",
          t.response(0, Vec3(0.45, 0., 0.), Fx).x, 0.);
  }

  // 3. Periodic images, and a particle that misses a step starts afresh.
  {
    const PeriodicBox   box(Vec3(0., 0., 0.), Vec3(1., 1., 1.), {{true, false, false}});
    SelfResponseTable   t = table(3, 5, 1., 1., 0.1);
    for (unsigned int j = 0; j < 5; ++j)
      t.along[0][j] = t.across[0][j] = 1. - 0.2 * j;
    SelfInducedVelocity self(t, box);
    self.record({1}, {Vec3(1., 0., 0.)}, {Vec3(0.05, 0.5, 0.5)}, comm);
    // 0.97 - 0.05 = 0.92, nearest image -0.08: 0.8 offsets, 1 - 0.16 = 0.84.
    const Vec3 u = self.velocity(1, Vec3(0.97, 0.5, 0.5));
    check(near(u, Vec3(0.84, 0., 0.)), "nearest periodic image", u.x, 0.84);
    self.record({2}, {Vec3(1., 0., 0.)}, {Vec3(0.5, 0.5, 0.5)}, comm);
    check(norm(self.velocity(1, Vec3(0.97, 0.5, 0.5))) == 0., "history dropped when absent",
          self.velocity(1, Vec3(0.97, 0.5, 0.5)).x, 0.);
  }
  return failures == 0 ? 0 : 1;
}
