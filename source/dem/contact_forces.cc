#include <sluice/dem/contact_forces.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  namespace
  {
    /// Normal and tangential force on particle i at one contact.
    ///
    /// n points from j to i, v_c is the velocity of i relative to j at the contact
    /// point. Normal force (Gao & Sun Eqs. 4-5 for the linear law; Hertz with the
    /// damping of Tsuji et al. as used by LIGGGHTS): F_n = k delta - c v_n, with the
    /// damping coefficient chosen from the restitution (zeta = -ln e/sqrt(pi^2+ln^2 e),
    /// Gao & Sun Eq. 10; times sqrt(5/6) for the Hertz law, whose realised restitution
    /// then equals e). The force may turn slightly attractive at the end of a contact;
    /// clipping it would raise the realised restitution (REFERENCE_CASES.md A.1).
    /// Tangential force (Gao & Sun Eqs. 6-9): a spring on the tangential displacement
    /// accumulated over the contact, plus a dashpot; the sum is truncated at
    /// mu max(F_n, 0).
    template <NormalContactModel normal, bool tangential>
    __attribute__((always_inline)) inline void contact_response(const PairProperties &pair, const ContactProperties &props,
                                 const Vec3 &n, const double overlap, const double R_eff,
                                 const double m_eff, const Vec3 &v_c, Vec3 *history,
                                 const double dt, Vec3 &force, Vec3 &tangential_force,
                                 double &normal_force)
    {
      const double v_n = dot(v_c, n);
      double       k_t = 0., c_t = 0.;
      if constexpr (normal == NormalContactModel::hertz_mindlin)
        {
          const double a   = std::sqrt(R_eff * overlap); // contact radius
          const double S_n = 2. * pair.E_star * a;       // dF_n/d(delta)
          const double c_n = 2. * sqrt_five_sixths * pair.damping_ratio * std::sqrt(S_n * m_eff);
          normal_force     = (2. / 3.) * S_n * overlap - c_n * v_n;
          if constexpr (tangential)
            {
              // Mindlin: k_t = 8 G* a = (4 G*/E*) S_n, so c_t is c_n times the
              // square root of that fixed ratio.
              k_t = 8. * pair.G_star * a;
              c_t = c_n * pair.sqrt_tangential_to_normal_stiffness;
            }
        }
      else
        {
          const double k_n = props.linear_stiffness(pair, R_eff, m_eff);
          const double c_n = 2. * pair.damping_ratio * std::sqrt(k_n * m_eff);
          normal_force     = k_n * overlap - c_n * v_n;
          if constexpr (tangential)
            {
              k_t = props.tangential_stiffness_ratio * k_n;
              c_t = 2. * pair.damping_ratio * std::sqrt(k_t * m_eff);
            }
        }
      force = normal_force * n;

      if constexpr (tangential)
        {
          const Vec3 v_t = v_c - v_n * n;
          Vec3       h   = *history;
          // Keep the spring in the current tangent plane as the contact rotates
          // (projection, as in LAMMPS' and LIGGGHTS' history models).
          h -= dot(h, n) * n;
          h += dt * v_t;
          tangential_force = -k_t * h - c_t * v_t;
          // Coulomb: |F_t| <= mu max(F_n, 0) at every instant, for the whole
          // tangential force (spring and dashpot), and none while the dashpot
          // pulls the surfaces together at the end of a contact. When sliding,
          // the spring is shortened to carry the capped force alone (Cundall &
          // Strack 1979), so that the next step starts from the Coulomb force.
          // Resetting it so that spring plus dashpot give the capped force
          // (LAMMPS' gran/hertz/history, Luding 2008 Eq. 20) pre-stretches the
          // spring against the dashpot; with Hertz's k_t growing with the
          // contact radius, friction then pushes along the slip (doc/dem.md 3).
          // (Comparing squares spares a sticking contact the square root.)
          const double limit = pair.friction * std::max(normal_force, 0.);
          const double F_t_2 = norm_square(tangential_force);
          if (F_t_2 > limit * limit)
            {
              tangential_force *= limit / std::sqrt(F_t_2);
              h = (-1. / k_t) * tangential_force;
            }
          *history = h;
          force += tangential_force;
        }
    }

    /// Rolling resistance torque on i for a relative angular velocity w_rel.
    template <RollingResistanceModel rolling>
    inline Vec3 rolling_torque(const double mu_r, const double R_eff, const double normal_force,
                               const Vec3 &w_rel, const double v_char)
    {
      const double w = norm(w_rel);
      if (!(w > 0.) || mu_r == 0.)
        return {};
      // Like sliding friction, rolling resistance needs compression.
      double magnitude = mu_r * R_eff * std::max(normal_force, 0.);
      if constexpr (rolling == RollingResistanceModel::viscous)
        magnitude *= R_eff * w / v_char;
      return (-magnitude / w) * w_rel;
    }

    template <NormalContactModel normal, bool tangential, RollingResistanceModel rolling,
              bool moving_walls, bool observed>
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

      for (unsigned int i = 0; i < n_local; ++i)
        {
          const Vec3   xi = x[i];
          const double ri = r[i];
          for (unsigned int k = L.offset[i]; k < L.offset[i + 1]; ++k)
            {
              const unsigned int j = L.partner[k];
              Vec3               d = xi - x[j];
              if (box.any_periodic)
                d = box.minimum_image(d);
              const double r_sum  = ri + r[j];
              const double dist_2 = norm_square(d);
              if (dist_2 >= r_sum * r_sum)
                {
                  if constexpr (tangential)
                    L.history[k] = Vec3();
                  continue;
                }
              const double dist    = std::sqrt(dist_2);
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
              if constexpr (observed)
                {
                  // Apart one step ago (contact_observer.h): the contact starts.
                  const Vec3 v_rel = v[i] - v[j];
                  if (norm_square(d - dt * v_rel) >= r_sum * r_sum)
                    {
                      const double v_n = dot(v_rel, n), energy = 0.5 * m_eff * v_n * v_n;
                      observer->impact(P.id[i], type[i], type[j], false, energy);
                      if (j < n_local)
                        observer->impact(P.id[j], type[j], type[i], false, energy);
                    }
                }
              f[i] += F;
              f[j] -= F;
              if constexpr (tangential)
                {
                  const Vec3 n_cross_F = cross(n, F_t);
                  t[i] -= arm_i * n_cross_F;
                  t[j] -= arm_j * n_cross_F;
                }
              if constexpr (rolling != RollingResistanceModel::none)
                {
                  const Vec3 M =
                    rolling_torque<rolling>(pair.rolling_friction, R_eff, F_n, w[i] - w[j], v_char);
                  t[i] += M;
                  t[j] -= M;
                }
              ++P.coordination[i];
              if (j < n_local)
                {
                  ++P.coordination[j];
                  stats.n_particle_contacts += 1.;
                }
              else
                stats.n_particle_contacts += 0.5;
              // (A division only when the maximum grows.)
              const double r_small = std::min(ri, r[j]);
              if (overlap > stats.max_overlap_ratio * r_small)
                stats.max_overlap_ratio = overlap / r_small;
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
              if constexpr (observed)
                {
                  // v_c . n is the approach speed to the wall's surface (the
                  // spin adds nothing along n): no overlap one step ago, a start.
                  const double v_n = dot(v_c, n);
                  if (overlap + dt * v_n <= 0.)
                    observer->impact(P.id[i], type[i], L.wall_partner[k], true,
                                     0.5 * m[i] * v_n * v_n);
                  if constexpr (tangential)
                    observer->wall_shear(L.wall_partner[k], -dot(F_t, v_c - v_n * n) * dt);
                }
              f[i] += F;
              wall_forces[L.wall_partner[k]] -= F;
              if constexpr (tangential)
                t[i] -= arm * cross(n, F_t);
              if constexpr (rolling != RollingResistanceModel::none)
                t[i] += rolling_torque<rolling>(pair.rolling_friction, ri, F_n, w[i], v_char);
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
    };

    template <NormalContactModel normal, bool tangential, RollingResistanceModel rolling,
              bool moving_walls>
    ContactForceKernel select_observed(const KernelChoice &c)
    {
      return c.observed ? &contact_forces<normal, tangential, rolling, moving_walls, true> :
                          &contact_forces<normal, tangential, rolling, moving_walls, false>;
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

  ContactForceKernel select_contact_kernel(const NormalContactModel     normal,
                                           const bool                   tangential,
                                           const RollingResistanceModel rolling,
                                           const bool moving_walls, const bool observed)
  {
    const KernelChoice c{tangential, rolling, moving_walls, observed};
    return normal == NormalContactModel::linear ?
             select_tangential<NormalContactModel::linear>(c) :
             select_tangential<NormalContactModel::hertz_mindlin>(c);
  }
} // namespace sluice
