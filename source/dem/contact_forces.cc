#include <sluice/dem/contact_forces.h>
#include <sluice/dem/contact_lanes.h>
#include <sluice/dem/contact_law.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace sluice
{
  namespace
  {
    /// The listed pairs that touch, into L.touching; the tangential history
    /// of the others back to zero. In a dense bed about half of the listed
    /// pairs touch, so a branch on it per pair mostly guesses wrong: the
    /// compare feeds a count, and the force pass runs through the touching
    /// pairs alone, in the list's order. A history is zeroed only where a
    /// contact ended since the last pass (a byte per pair says where one
    /// was), a branch that is rarely taken: the others are zero already.
    template <bool tangential>
    void find_touching_pairs(const ParticleStorage &P, NeighbourList &L, const PeriodicBox &box)
    {
      L.touching_offset.resize(P.n_local + 1);
      L.touching.resize(L.partner.size());
      if (tangential && L.history_may_be_nonzero.size() != L.partner.size())
        L.history_may_be_nonzero.assign(L.partner.size(), 1);
      // (Plain pointers and a local flag: the stores below would otherwise
      // make the compiler read the vectors' data and the flag again per pair.)
      const Vec3 *const         x               = P.position.data();
      const double *const       r               = P.radius.data();
      const unsigned int *const offset          = L.offset.data();
      const unsigned int *const partner         = L.partner.data();
      unsigned int *const       touching        = L.touching.data();
      unsigned int *const       touching_offset = L.touching_offset.data();
      Vec3 *const               history         = L.history.data();
      std::uint8_t *const       may_be_nonzero  = L.history_may_be_nonzero.data();
      const bool                periodic        = box.any_periodic;
      const unsigned int        n_local         = P.n_local;
      unsigned int              n               = 0;
      touching_offset[0]                        = 0;
      for (unsigned int i = 0; i < n_local; ++i)
        {
          const Vec3   xi = x[i];
          const double ri = r[i];
          for (unsigned int k = offset[i]; k < offset[i + 1]; ++k)
            {
              const unsigned int j = partner[k];
              Vec3               d = xi - x[j];
              if (periodic)
                d = box.minimum_image(d);
              const double r_sum = ri + r[j];
              // (Written as the negation, so that a NaN distance counts as
              // touching and reaches the state checks.)
              const bool touch = !(norm_square(d) >= r_sum * r_sum);
              touching[n]      = k;
              n += touch;
              if constexpr (tangential)
                {
                  if (may_be_nonzero[k] > touch)
                    history[k] = Vec3();
                  may_be_nonzero[k] = touch;
                }
            }
          touching_offset[i + 1] = n;
        }
    }

    /// A touching pair's partner j counted, and the largest overlap ratio
    /// noted (r_i: the other sphere's radius).
    inline void count_contact(ParticleStorage &P, const unsigned int j, const double r_i,
                              const double overlap, ContactStatistics &stats)
    {
      if (j < P.n_local)
        {
          ++P.coordination[j];
          stats.n_particle_contacts += 1.;
        }
      else
        stats.n_particle_contacts += 0.5;
      // (A division only when the maximum grows.)
      const double r_small = std::min(r_i, P.radius[j]);
      if (overlap > stats.max_overlap_ratio * r_small)
        stats.max_overlap_ratio = overlap / r_small;
    }

    /// One pair's force and torques added to i and j, in the order the sweep
    /// has always added them.
    template <bool tangential>
    inline void add_contact(ParticleStorage &P, const unsigned int i, const unsigned int j,
                            const ContactOutput &o, ContactStatistics &stats)
    {
      P.force[i] += o.force;
      P.force[j] -= o.force;
      if constexpr (tangential)
        {
          P.torque[i] -= o.torque_i;
          P.torque[j] -= o.torque_j;
        }
      ++P.coordination[i];
      count_contact(P, j, P.radius[i], o.overlap, stats);
    }

    /// add_contact() for all touching pairs of i, with i's sums held in
    /// registers: a pair never has i as its partner, so each sum still takes
    /// the same terms in the same order, without a store and a load of i's
    /// force and torque per pair.
    template <bool tangential, RollingResistanceModel rolling>
    inline void add_contacts_of(ParticleStorage &P, const NeighbourList &L, const unsigned int i,
                                const ContactOutput *o, ContactStatistics &stats)
    {
      const unsigned int begin = L.touching_offset[i], end = L.touching_offset[i + 1];
      if (begin == end)
        return;
      Vec3         f_i = P.force[i], t_i = P.torque[i];
      const double r_i = P.radius[i];
      for (unsigned int c = begin; c < end; ++c, ++o)
        {
          const unsigned int j = L.partner[L.touching[c]];
          f_i += o->force;
          P.force[j] -= o->force;
          if constexpr (tangential)
            {
              t_i -= o->torque_i;
              P.torque[j] -= o->torque_j;
            }
          if constexpr (rolling != RollingResistanceModel::none)
            {
              t_i += o->rolling_torque;
              P.torque[j] -= o->rolling_torque;
            }
          count_contact(P, j, r_i, o->overlap, stats);
        }
      P.force[i] = f_i;
      P.torque[i] = t_i;
      P.coordination[i] += end - begin;
    }

    /// f(0, 1, ..., W - 1), the lanes' indices as constants.
    template <class F, std::size_t... l>
    __attribute__((always_inline)) inline void apply_lanes(const F &f, std::index_sequence<l...>)
    {
      f(std::integral_constant<unsigned int, l>()...);
    }
    template <unsigned int W, class F>
    __attribute__((always_inline)) inline void apply_lanes(const F &f)
    {
      apply_lanes(f, std::make_index_sequence<W>());
    }

    /// The Hertz–Mindlin forces of the touching pairs of particles
    /// [i_begin, i_end), W at a time (contact_lanes.h), into out[c - first]
    /// for touching pair c; the histories updated.
    template <unsigned int W, bool tangential, RollingResistanceModel rolling>
    __attribute__((always_inline)) inline void
    hertz_mindlin_pairs(const ParticleStorage &P, NeighbourList &L,
                        const ContactProperties &props, const PeriodicBox &box, const double dt,
                        const unsigned int i_begin, const unsigned int i_end,
                        ContactOutput *const out)
    {
      const unsigned int first  = L.touching_offset[i_begin];
      const double       v_char = props.characteristic_velocity;
      const auto         input  = [&](const unsigned int i,
                                 const unsigned int c) __attribute__((always_inline)) {
        const unsigned int k = L.touching[c];
        const unsigned int j = L.partner[k];
        Vec3               d = P.position[i] - P.position[j];
        if (box.any_periodic)
          d = box.minimum_image(d);
        return ContactInput{d,
                            P.radius[i],
                            P.radius[j],
                            P.mass[i],
                            P.mass[j],
                            P.velocity[i],
                            P.velocity[j],
                            P.angular_velocity[i],
                            P.angular_velocity[j],
                            &props(P.type[i], P.type[j]),
                            tangential ? &L.history[k] : nullptr};
      };
      // The touching pairs waiting for the lanes to fill: particle, pair.
      unsigned int waiting_i[W], waiting_c[W], n_waiting = 0;
      const auto   run = [&](auto... l) __attribute__((always_inline)) {
        const ContactInput in[W]       = {input(waiting_i[l], waiting_c[l])...};
        ContactOutput *const lane_out[W] = {out + (waiting_c[l] - first)...};
        hertz_mindlin_in_lanes<W, tangential, rolling>(in, dt, v_char, lane_out);
      };
      for (unsigned int i = i_begin; i < i_end; ++i)
        for (unsigned int c = L.touching_offset[i]; c < L.touching_offset[i + 1]; ++c)
          {
            waiting_i[n_waiting] = i;
            waiting_c[n_waiting] = c;
            if (++n_waiting == W)
              {
                apply_lanes<W>(run);
                n_waiting = 0;
              }
          }
      if (n_waiting > 0)
        {
          // The last ones: copies of the first, with scratch histories and
          // outputs, fill the lanes.
          ContactInput in[W];
          ContactOutput *lane_out[W];
          ContactOutput  unused;
          Vec3           scratch[W];
          for (unsigned int l = 0; l < W; ++l)
            {
              const bool filler = l >= n_waiting;
              in[l] = input(waiting_i[filler ? 0 : l], waiting_c[filler ? 0 : l]);
              lane_out[l] = filler ? &unused : out + (waiting_c[l] - first);
              if (filler && tangential)
                {
                  scratch[l]    = *in[l].history;
                  in[l].history = &scratch[l];
                }
            }
          hertz_mindlin_in_lanes<W, tangential, rolling>(in, dt, v_char, lane_out);
        }
    }

#if defined(__x86_64__)
    /// hertz_mindlin_pairs() four at a time, compiled for AVX2 without FMA
    /// (so the same roundings); called only where the processor has AVX2.
    template <bool tangential, RollingResistanceModel rolling>
    __attribute__((target("avx2"), noinline)) void
    hertz_mindlin_pairs_avx2(const ParticleStorage &P, NeighbourList &L,
                             const ContactProperties &props, const PeriodicBox &box,
                             const double dt, const unsigned int i_begin,
                             const unsigned int i_end, ContactOutput *const out)
    {
      hertz_mindlin_pairs<4, tangential, rolling>(P, L, props, box, dt, i_begin, i_end, out);
    }
#endif

    /// lane_width: 2 or 4 contacts at a time for Hertz–Mindlin without an
    /// observer, else 0 (one at a time).
    template <NormalContactModel normal, bool tangential, RollingResistanceModel rolling,
              bool moving_walls, bool observed, unsigned int lane_width>
    ContactStatistics contact_forces(ParticleStorage &P, NeighbourList &L,
                                     const ContactProperties &props,
                                     const WallSet &walls,
                                     const PeriodicBox &box, const double dt,
                                     std::vector<Vec3> &wall_forces,
                                     ContactObserver *const observer)
    {
      ContactStatistics  stats;
      const unsigned int n_local = P.n_local;
      std::fill(P.force.begin(), P.force.end(), Vec3());
      std::fill(P.torque.begin(), P.torque.end(), Vec3());
      std::fill(P.coordination.begin(), P.coordination.end(), 0u);
      std::fill(wall_forces.begin(), wall_forces.end(), Vec3());

      Vec3 *const        x = P.position.data();
      Vec3 *const        v = P.velocity.data();
      Vec3 *const        w = P.angular_velocity.data();
      Vec3 *const        f = P.force.data();
      Vec3 *const        t = P.torque.data();
      const double *const r = P.radius.data();
      const double *const m = P.mass.data();
      const unsigned int *const type = P.type.data();
      const double v_char = props.characteristic_velocity;

      find_touching_pairs<tangential>(P, L, box);
      // Hertz-Mindlin without an observer, the common case: the forces of a
      // block of particles' pairs two or four at a time (contact_lanes.h),
      // then added up pair by pair in the list's order.
      constexpr bool in_lanes = lane_width > 0;
      static_assert(!in_lanes || (normal == NormalContactModel::hertz_mindlin && !observed));
      constexpr unsigned int     lane_block = 64; // particles: their pairs' outputs stay in L1
      std::vector<ContactOutput> outputs;
      unsigned int               first_output = 0; // the touching pair at outputs[0]
      for (unsigned int i = 0; i < n_local; ++i)
        {
          const Vec3   xi = x[i];
          const double ri = r[i];
          if constexpr (in_lanes)
            {
              if (i % lane_block == 0)
                {
                  const unsigned int i_end = std::min(n_local, i + lane_block);
                  first_output             = L.touching_offset[i];
                  outputs.resize(std::max<std::size_t>(outputs.size(),
                                                        L.touching_offset[i_end] - first_output));
#if defined(__x86_64__)
                  if constexpr (lane_width == 4)
                    hertz_mindlin_pairs_avx2<tangential, rolling>(P, L, props, box, dt, i,
                                                                  i_end, outputs.data());
                  else
#endif
                    hertz_mindlin_pairs<2, tangential, rolling>(P, L, props, box, dt, i, i_end,
                                                                outputs.data());
                }
              add_contacts_of<tangential, rolling>(
                P, L, i, outputs.data() + (L.touching_offset[i] - first_output), stats);
            }
          else
            for (unsigned int c = L.touching_offset[i]; c < L.touching_offset[i + 1]; ++c)
              {
                const unsigned int k = L.touching[c];
                const unsigned int j = L.partner[k];
                Vec3               d = xi - x[j];
                if (box.any_periodic)
                  d = box.minimum_image(d);
                const double r_sum   = ri + r[j];
                const double dist    = std::sqrt(norm_square(d));
                const Vec3   n       = (1. / dist) * d;
                const double overlap = r_sum - dist;
                const double m_eff   = m[i] * m[j] / (m[i] + m[j]);
                const double R_eff   = ri * r[j] / r_sum;
                // Lever arms to the contact point; they add up to the distance of
                // the centres, so the tangential force conserves angular momentum.
                const double arm_i = ri - 0.5 * overlap, arm_j = r[j] - 0.5 * overlap;
                const Vec3   v_c   = v[i] - v[j] - cross(arm_i * w[i] + arm_j * w[j], n);
                const PairProperties &pair = props(type[i], type[j]);

                Vec3   F, F_t;
                double F_n;
                contact_response<normal, tangential>(pair, props, n, overlap, R_eff, m_eff, v_c,
                                                     tangential ? &L.history[k] : nullptr, dt, F,
                                                     F_t, F_n);
                Vec3 M;
                if constexpr (rolling != RollingResistanceModel::none)
                  M = rolling_torque<rolling>(pair.rolling_friction, R_eff, F_n, w[i] - w[j],
                                              v_char);
                if constexpr (observed)
                  {
                    // Apart one step ago (contact_observer.h): the contact starts.
                    const Vec3 v_rel = v[i] - v[j];
                    if (norm_square(d - dt * v_rel) >= r_sum * r_sum)
                      {
                        const double v_n = dot(v_rel, n), energy = 0.5 * m_eff * v_n * v_n;
                        observer->impact(P.id[i], i, type[i], type[j], false, energy);
                        if (j < n_local)
                          observer->impact(P.id[j], j, type[j], type[i], false, energy);
                      }
                    const ElasticParts e =
                      elastic_parts<normal>(pair, props, overlap, R_eff, m_eff);
                    const double       share = j < n_local ? 1. : 0.5;
                    observer->contact({i, j, ContactEnergyRecord::none, ContactEnergyRecord::none,
                                       n, arm_i, arm_j, F, F_n - e.normal_force, F_t, M, Vec3(),
                                       Vec3(), share});
                    observer->stored(false, share, e.normal_energy,
                                     tangential ? 0.5 * e.tangential_stiffness *
                                                    norm_square(L.history[k]) :
                                                  0.);
                  }
                ContactOutput o{F, Vec3(), Vec3(), overlap, Vec3()};
                if constexpr (tangential)
                  {
                    const Vec3 n_cross_F = cross(n, F_t);
                    o.torque_i           = arm_i * n_cross_F;
                    o.torque_j           = arm_j * n_cross_F;
                  }
                add_contact<tangential>(P, i, j, o, stats);
                if constexpr (rolling != RollingResistanceModel::none)
                  {
                    t[i] += M;
                    t[j] -= M;
                  }
              }

          for (unsigned int k = L.wall_offset[i]; k < L.wall_offset[i + 1]; ++k)
            {
              const Plane &wall    = walls[L.wall_partner[k]];
              const double     overlap = ri - dot(xi - wall.point, wall.normal);
              if (overlap <= 0.)
                {
                  if constexpr (tangential)
                    L.wall_history[k] = Vec3();
                  continue;
                }
              const Vec3           n   = wall.normal;
              const double         arm = ri - overlap; // centre to wall surface
              Vec3                 v_c = v[i] - cross(arm * w[i], n);
              if constexpr (moving_walls)
                v_c -= wall.velocity_at(xi - arm * n);
              const PairProperties &pair = props(type[i], wall.material);
              Vec3                 F, F_t;
              double               F_n;
              contact_response<normal, tangential>(pair, props, n, overlap, ri, m[i], v_c,
                                                   tangential ? &L.wall_history[k] : nullptr,
                                                   dt, F, F_t, F_n);
              Vec3 M;
              if constexpr (rolling != RollingResistanceModel::none)
                M = rolling_torque<rolling>(pair.rolling_friction, ri, F_n, w[i], v_char);
              if constexpr (observed)
                {
                  // v_c . n is the approach speed to the wall's surface (the
                  // spin adds nothing along n): no overlap one step ago, a start.
                  const double v_n = dot(v_c, n);
                  if (overlap + dt * v_n <= 0.)
                    observer->impact(P.id[i], i, type[i], L.wall_partner[k], true,
                                     0.5 * m[i] * v_n * v_n);
                  const ElasticParts e = elastic_parts<normal>(pair, props, overlap, ri, m[i]);
                  // (A plane's rolling resistance uses the sphere's own spin.)
                  observer->contact({i, ContactEnergyRecord::none, L.wall_partner[k],
                                     ContactEnergyRecord::none, n, arm, 0., F,
                                     F_n - e.normal_force, F_t, M,
                                     moving_walls ? wall.velocity_at(xi - arm * n) : Vec3(), Vec3(),
                                     1.});
                  observer->stored(true, 1., e.normal_energy,
                                   tangential ? 0.5 * e.tangential_stiffness *
                                                  norm_square(L.wall_history[k]) :
                                                0.);
                }
              f[i] += F;
              wall_forces[L.wall_partner[k]] -= F;
              if constexpr (tangential)
                t[i] -= arm * cross(n, F_t);
              if constexpr (rolling != RollingResistanceModel::none)
                t[i] += M;
              ++P.coordination[i];
              stats.n_wall_contacts += 1.;
              if (overlap > stats.max_overlap_ratio * ri)
                stats.max_overlap_ratio = overlap / ri;
            }
        }
      return stats;
    }

    /// The run-time choices, one at a time, into template arguments.
    struct KernelChoice
    {
      bool                   tangential;
      RollingResistanceModel rolling;
      bool                   moving_walls, observed;
      unsigned int           lane_width;
    };

    template <NormalContactModel normal, bool tangential, RollingResistanceModel rolling,
              bool moving_walls>
    ContactForceKernel select_observed(const KernelChoice &c)
    {
      if (c.observed)
        return &contact_forces<normal, tangential, rolling, moving_walls, true, 0>;
      if constexpr (normal == NormalContactModel::hertz_mindlin)
        return c.lane_width == 4 ?
                 &contact_forces<normal, tangential, rolling, moving_walls, false, 4> :
                 &contact_forces<normal, tangential, rolling, moving_walls, false, 2>;
      else
        return &contact_forces<normal, tangential, rolling, moving_walls, false, 0>;
    }

    template <NormalContactModel normal, bool tangential, RollingResistanceModel rolling>
    ContactForceKernel select_walls(const KernelChoice &c)
    {
      return c.moving_walls ? select_observed<normal, tangential, rolling, true>(c) :
                              select_observed<normal, tangential, rolling, false>(c);
    }

    template <NormalContactModel normal, bool tangential>
    ContactForceKernel select_rolling(const KernelChoice &c)
    {
      switch (c.rolling)
        {
          case RollingResistanceModel::constant_torque:
            return select_walls<normal, tangential, RollingResistanceModel::constant_torque>(c);
          case RollingResistanceModel::viscous:
            return select_walls<normal, tangential, RollingResistanceModel::viscous>(c);
          default:
            return select_walls<normal, tangential, RollingResistanceModel::none>(c);
        }
    }

    template <NormalContactModel normal>
    ContactForceKernel select_tangential(const KernelChoice &c)
    {
      return c.tangential ? select_rolling<normal, true>(c) : select_rolling<normal, false>(c);
    }
  } // namespace

  unsigned int widest_contact_lanes()
  {
#if defined(__x86_64__)
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2 ? 4 : 2;
#else
    return 2;
#endif
  }

  ContactForceKernel select_contact_kernel(const NormalContactModel     normal,
                                           const bool                   tangential,
                                           const RollingResistanceModel rolling,
                                           const bool moving_walls, const bool observed,
                                           const unsigned int lane_width)
  {
    if (!(lane_width == 0 || lane_width == 2 || (lane_width == 4 && widest_contact_lanes() == 4)))
      throw std::invalid_argument("contact lanes: 0, 2, or 4 where the processor has AVX2");
    const KernelChoice c{tangential, rolling, moving_walls, observed,
                         lane_width == 0 ? widest_contact_lanes() : lane_width};
    return normal == NormalContactModel::linear ?
             select_tangential<NormalContactModel::linear>(c) :
             select_tangential<NormalContactModel::hertz_mindlin>(c);
  }
} // namespace sluice
