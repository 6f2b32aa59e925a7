#pragma once
// The contact law at one contact, shared by the particle, plane and mesh
// contact passes (contact_forces.cc, mesh_contact_forces.cc): forced inline,
// so that each pass compiles it into its own loop.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/vector3.h>
#include <sluice/dem/contact_properties.h>

#include <algorithm>
#include <cmath>

namespace sluice
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
} // namespace sluice

namespace sluice
{
  /// The conservative parts of a contact at an overlap: the elastic normal
  /// force, the energy stored in the normal spring (linear: k_n delta^2 / 2;
  /// Hertz: integral of F_el = (4/15) S_n delta^2) and the tangential
  /// stiffness, for the energy bookkeeping (contact_observer.h).
  struct ElasticParts
  {
    double normal_force, normal_energy, tangential_stiffness;
  };

  template <NormalContactModel normal>
  inline ElasticParts elastic_parts(const PairProperties &pair, const ContactProperties &props,
                                    const double overlap, const double R_eff, const double m_eff)
  {
    if constexpr (normal == NormalContactModel::hertz_mindlin)
      {
        const double a   = std::sqrt(R_eff * overlap);
        const double S_n = 2. * pair.E_star * a;
        return {(2. / 3.) * S_n * overlap, (4. / 15.) * S_n * overlap * overlap,
                8. * pair.G_star * a};
      }
    else
      {
        const double k_n = props.linear_stiffness(pair, R_eff, m_eff);
        return {k_n * overlap, 0.5 * k_n * overlap * overlap,
                props.tangential_stiffness_ratio * k_n};
      }
  }
} // namespace sluice
