// The Hertz–Mindlin force sweep two and four contacts at a time
// (contact_lanes.h; four where the processor has AVX2) against the
// one-at-a-time sweep, to the bit.
//
// The contact pass takes the lanes for Hertz–Mindlin without an observer;
// with an observer it runs the scalar law (contact_law.h, with the rolling
// resistance's torque) one contact at a time, and the observer only
// records. So the same bed passed through both kernels must give the same forces,
// torques, coordination numbers, tangential histories and statistics, bit
// for bit. The bed: 400 spheres of two materials and radii from 0.8 to
// 1.2 mm packed into overlap, periodic in x (pairs across the face take the
// nearest image), with random velocities and spins; the pass is repeated
// 40 times on the same positions so that the histories grow from sticking
// into sliding. A copy with friction 1e9 never slides: the pairs whose
// histories part from it slid, and the test asks for both kinds (and for
// a block of spheres whose count of touching pairs is not a multiple of the
// width, whose last lanes are filled with copies). With and without
// friction, and with both rolling-resistance models. Then the bed is spread
// so that contacts end: after the pass no pair apart keeps a history.

#include <sluice/dem/contact_forces.h>

#include "check.h"

#include <algorithm>
#include <cstring>
#include <utility>
#include <random>
#include <vector>

using namespace sluice;
using sluice::unit::check;

namespace
{
  bool same_bits(const Vec3 &a, const Vec3 &b) { return std::memcmp(&a, &b, sizeof a) == 0; }

  SceneParameters materials(const double friction, const double rolling_friction = 0.)
  {
    SceneParameters p;
    p.density                 = {2500., 7800.};
    p.young_modulus           = {1e7, 2e8};
    p.poisson_ratio           = {0.3, 0.25};
    p.normal_model            = NormalContactModel::hertz_mindlin;
    p.restitution             = 0.5;
    p.friction                = friction;
    p.rolling_friction        = rolling_friction;
    p.characteristic_velocity = 1.;
    return p;
  }

  /// A bed whose spheres overlap their neighbours by up to a few per cent.
  ParticleStorage bed()
  {
    std::mt19937_64                        random(20261207);
    std::uniform_real_distribution<double> unit(0., 1.);
    const auto around = [&](const double s) { return s * (2. * unit(random) - 1.); };
    ParticleStorage P;
    const double    spacing = 1.95e-3;
    std::uint64_t   id      = 0;
    for (unsigned int a = 0; a < 10; ++a)
      for (unsigned int b = 0; b < 8; ++b)
        for (unsigned int c = 0; c < 5; ++c, ++id)
          {
            const Vec3 x((a + 0.5) * spacing + around(2e-4),
                         (b + 0.5) * spacing + around(2e-4), (c + 0.5) * spacing + around(2e-4));
            const Vec3 v(around(0.5), around(0.5), around(0.5));
            const Vec3 w(around(300.), around(300.), around(300.));
            P.push_back(id, x, v, w, 1e-3 + around(2e-4), id % 2, id % 2 ? 7800. : 2500.);
          }
    P.n_local = P.size();
    return P;
  }
} // namespace

int main()
{
  const PeriodicBox box(Vec3(0., 0., 0.), Vec3(10 * 1.95e-3, 0.1, 0.1), {{true, false, false}});
  const WallSet     walls({}, {}, box, "test");
  const double      dt = 2e-6;

  const RollingResistanceModel none = RollingResistanceModel::none;
  std::vector<unsigned int>    widths{2};
  if (widest_contact_lanes() == 4)
    widths.push_back(4);
  else
    std::printf("this processor has no AVX2: four lanes not tested\n");
  for (const unsigned int width : widths)
    for (const auto &[tangential, rolling] :
         {std::pair{true, none}, std::pair{false, none},
          std::pair{true, RollingResistanceModel::constant_torque},
          std::pair{true, RollingResistanceModel::viscous},
          std::pair{false, RollingResistanceModel::viscous}})
      {
        const double            mu_r = rolling == none ? 0. : 0.1;
        const ContactProperties props(materials(tangential ? 0.3 : 0., mu_r)),
          sticking(materials(1e9, mu_r));
        const ContactForceKernel lanes =
          select_contact_kernel(NormalContactModel::hertz_mindlin, tangential, rolling, false,
                                false, width);
        const ContactForceKernel one_at_a_time =
          select_contact_kernel(NormalContactModel::hertz_mindlin, tangential, rolling, false,
                                true);

        ParticleStorage A = bed(), B = A, C = A;
        NeighbourList   LA, LB, LC;
        for (NeighbourList *L : {&LA, &LB, &LC})
          L->build(A, box, walls, 1.2e-3, 2e-4, tangential, ContactHistoryMap());
        std::vector<Vec3> wall_forces;
        ContactObserver   observer(0);

        unsigned int n_touching = 0, mismatches = 0, n_slid = 0, filled_blocks = 0;
        for (unsigned int pass = 0; pass < 40; ++pass)
          {
            const ContactStatistics sa = lanes(A, LA, props, walls, box, dt, wall_forces, nullptr);
            const ContactStatistics sb =
              one_at_a_time(B, LB, props, walls, box, dt, wall_forces, &observer);
            if (tangential)
              lanes(C, LC, sticking, walls, box, dt, wall_forces, nullptr);
            n_touching = LA.touching_offset.back();
            for (unsigned int i = 0; i < A.n_local; i += 64)
              filled_blocks += (LA.touching_offset[std::min(A.n_local, i + 64)] -
                                LA.touching_offset[i]) % width != 0;
            for (unsigned int i = 0; i < A.n_local; ++i)
              mismatches += !same_bits(A.force[i], B.force[i]) +
                            !same_bits(A.torque[i], B.torque[i]) +
                            (A.coordination[i] != B.coordination[i]);
            for (std::size_t k = 0; k < LA.history.size(); ++k)
              mismatches += !same_bits(LA.history[k], LB.history[k]);
            mismatches += (sa.n_particle_contacts != sb.n_particle_contacts) +
                          (sa.max_overlap_ratio != sb.max_overlap_ratio);
          }
        for (std::size_t k = 0; k < LA.history.size(); ++k)
          n_slid += !same_bits(LA.history[k], LC.history[k]);

        // The bed spread by 2%, so that contacts end: the pass zeroes their
        // histories, and every listed pair that does not touch has none.
        unsigned int n_ended = 0, stale = 0;
        if (tangential)
          {
            for (unsigned int i = 0; i < A.n_local; ++i)
              A.position[i] = 1.02 * A.position[i];
            lanes(A, LA, props, walls, box, dt, wall_forces, nullptr);
            for (unsigned int i = 0; i < A.n_local; ++i)
              for (unsigned int k = LA.offset[i]; k < LA.offset[i + 1]; ++k)
                {
                  const unsigned int j     = LA.partner[k];
                  const double       r_sum = A.radius[i] + A.radius[j];
                  if (norm_square(box.minimum_image(A.position[i] - A.position[j])) <
                      r_sum * r_sum)
                    continue;
                  n_ended += norm_square(LB.history[k]) > 0.;
                  stale += norm_square(LA.history[k]) > 0.;
                }
          }

        const char *law  = tangential ? "with friction" : "frictionless";
        const char *roll = rolling == none                            ? "" :
                           rolling == RollingResistanceModel::viscous ? ", viscous rolling" :
                                                                        ", constant rolling torque";
        std::printf("%u lanes, %s%s: %u touching pairs of %u listed, %u slid, %u mismatches, "
                    "%u contacts ended, %u histories left\n",
                    width, law, roll, n_touching, LA.n_pairs(), n_slid, mismatches, n_ended,
                    stale);
        check(mismatches == 0, "lanes against one at a time: differing numbers", mismatches, 0);
        check(n_touching > 200, "touching pairs", n_touching, 200);
        check(filled_blocks > 0, "blocks of 64 spheres (contact_forces.cc) with lanes filled",
              filled_blocks, 1);
        if (tangential)
          {
            check(n_slid > n_touching / 10, "pairs that slid", n_slid, n_touching / 10);
            check(n_slid < n_touching * 9 / 10, "pairs that stuck", n_touching - n_slid,
                  n_touching / 10);
            check(n_ended > 10, "contacts ended by the spreading", n_ended, 10);
            check(stale == 0, "histories of pairs apart after the pass", stale, 0);
          }
      }
  return sluice::unit::failures == 0 ? 0 : 1;
}
