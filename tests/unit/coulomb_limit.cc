// Coulomb's law in oblique impacts: a spinning sphere strikes a rigid plane.
//
// At every step of every impact the tangential contact force (spring and
// dashpot together) must satisfy |F_t| <= mu max(F_n, 0), so the tangential
// impulse is at most mu times the compressive normal impulse. When the contact
// point slides throughout (slip speed above 7/2 mu (1 + e) v_n), the rebound must
// follow the rigid-body sliding solution (e.g. Brach 1991; Maw, Barber &
// Fawcett 1976): the tangential impulse mu J_n opposes the slip, so
//   v_t' = v_t - mu J_n / m s,   w' = w + mu J_n R / I (n x s),
// with s the unit slip direction and J_n the normal impulse the contact gave.
// Both laws, restitution 0.1 to 1, friction 0.1 to 0.9, slip from zero to far
// past the sliding limit, with and without spin.

#include <sluice/dem/contact_forces.h>
#include <sluice/dem/velocity_verlet.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace sluice;
using sluice::unit::check;

namespace
{
  struct Impact
  {
    double max_force_ratio     = 0.;    // max over steps of |F_t| / (mu max(F_n, 0))
    double compressive_impulse = 0.;    // J_n+, the impulse of F_n > 0
    double impulse_ratio       = 0.;    // |J_t| / (mu J_n+)
    double attractive_share    = 0.;    // -(tensile normal impulse) / J_n+
    bool   tension_friction    = false; // a tangential force while F_n <= 0
    Vec3   velocity, angular_velocity;  // after the rebound
  };

  /// One sphere of radius R above the plane z = 0, touching it, moving with v
  /// and spinning with w; integrated with the DEM's own velocity-Verlet pieces
  /// and contact kernel until it leaves the wall.
  Impact impact(const ContactProperties &props, const ContactForceKernel kernel, const double R,
                const double density, const double mu, const Vec3 &v, const Vec3 &w,
                const double dt)
  {
    ParticleStorage P;
    P.push_back(0, Vec3(0., 0., R), v, w, R, 0, density);
    P.n_local = 1;
    const PeriodicBox            box(Vec3(-0.05, -0.05, 0.), Vec3(0.05, 0.05, 0.05), {{false, false, false}});
    const WallSet walls({{Vec3(), Vec3(0., 0., 1.), 1, "floor", "", ""}}, {}, box, "test");
    std::vector<Vec3>            wall_forces(1);
    NeighbourList                list;
    list.build(P, box, walls, R, R, true, ContactHistoryMap());

    Impact     result;
    double     J_n_plus = 0., J_n_minus = 0.;
    Vec3       J_t;
    bool       touched = false;
    const Vec3 g;
    for (unsigned int step = 0; step < 10000000; ++step)
      {
        half_kick(P, 0.5 * dt, g);
        drift(P, dt);
        kernel(P, list, props, walls, box, dt, wall_forces, nullptr);
        half_kick(P, 0.5 * dt, g);
        const Vec3   F   = P.force[0];
        const double F_n = F.z;
        const Vec3   F_t(F.x, F.y, 0.);
        const double limit = mu * std::max(F_n, 0.);
        if (limit > 0.)
          result.max_force_ratio = std::max(result.max_force_ratio, norm(F_t) / limit);
        else if (norm(F_t) > 0.)
          result.tension_friction = true;
        (F_n > 0. ? J_n_plus : J_n_minus) += F_n * dt;
        J_t += dt * F_t;
        const bool in_contact = P.position[0].z < R;
        touched               = touched || in_contact;
        if (touched && !in_contact)
          break;
      }
    result.impulse_ratio       = norm(J_t) / (mu * J_n_plus);
    result.compressive_impulse = J_n_plus;
    result.attractive_share = -J_n_minus / J_n_plus;
    result.velocity         = P.velocity[0];
    result.angular_velocity = P.angular_velocity[0];
    return result;
  }
} // namespace

int main()
{
  const double R = 0.0025, density = 2500., v_n = 1.;
  int          n_impacts = 0, n_sliding = 0;
  double       worst_force_ratio = 0., worst_impulse_ratio = 0., worst_rigid_body = 0.;
  double       worst_attraction  = 0.;
  for (const auto law : {NormalContactModel::linear, NormalContactModel::hertz_mindlin})
    for (const double e : {0.1, 0.3, 0.5, 0.7, 0.9, 1.0})
      for (const double mu : {0.1, 0.3, 0.5, 0.7, 0.9})
        {
          SceneParameters p;
          p.density                 = {density, density};
          p.young_modulus           = {7e10, 7e19}; // glass on a rigid plane
          p.poisson_ratio           = {0.25, 0.25};
          p.normal_model            = law;
          p.restitution             = e;
          p.friction                = mu;
          p.characteristic_velocity = v_n;
          const ContactProperties  props(p);
          const ContactForceKernel kernel =
            select_contact_kernel(law, true, RollingResistanceModel::none, false);
          // The step the automatic choice would take, at t_c/100.
          const double dt = std::min(0.01 * props.contact_time(0, 1, R, true),
                                     props.damping_time_step(0, 1, R, true, 0.005));

          const double m = density * 4. / 3. * M_PI * R * R * R, I = 0.4 * m * R * R;
          // Slip speed in units of the sliding limit 7/2 mu (1 + e) v_n.
          for (const double s : {0., 0.3, 0.8, 1.3, 2., 5., 20.})
            for (const int spin_form : {0, 1, 2})
              {
                const double u0 = s * 3.5 * mu * (1. + e) * v_n;
                // Slip u0 = v_t - R w_y along x: by sliding alone, by spin alone
                // (back spin), or by both (the ball moves forward at 2 u0).
                const double vt = spin_form == 0 ? u0 : spin_form == 1 ? 0. : 2. * u0;
                const double wy = (vt - u0) / R;
                const Vec3   v0(vt, 0., -v_n), w0(0., wy, 0.);
                const Impact r = impact(props, kernel, R, density, mu, v0, w0, dt);
                ++n_impacts;
                worst_force_ratio   = std::max(worst_force_ratio, r.max_force_ratio);
                worst_impulse_ratio = std::max(worst_impulse_ratio, r.impulse_ratio);
                worst_attraction    = std::max(worst_attraction, r.attractive_share);
                check(!r.tension_friction, "no friction without compression", 1., 0.);
                check(r.max_force_ratio <= 1. + 1e-9, "|F_t| / (mu max(F_n, 0))",
                      r.max_force_ratio, 1.);
                check(r.impulse_ratio <= 1. + 1e-9, "|J_t| / (mu J_n+)", r.impulse_ratio, 1.);
                if (s < 1.3 || u0 == 0.)
                  continue;
                // Gross sliding: the rigid-body solution with the compressive
                // normal impulse. (A damped contact ends with the dashpot
                // pulling, up to 12% of J_n+ at e = 0.1; friction needs
                // compression, so that part carries none.)
                ++n_sliding;
                const double J_n   = r.compressive_impulse;
                const double dv_t  = mu * J_n / m; // along -x
                const double dw_y  = mu * J_n * R / I; // along n x s = z x x = y
                const double err_v = std::abs(r.velocity.x - (vt - dv_t)) / dv_t;
                const double err_w = std::abs(r.angular_velocity.y - (wy + dw_y)) / dw_y;
                worst_rigid_body   = std::max({worst_rigid_body, err_v, err_w});
                if (err_v > 0.01 || err_w > 0.01)
                  std::printf("  in: law %d, e %g, mu %g, slip %g x the limit, spin form %d\n",
                              static_cast<int>(law), e, mu, s, spin_form);
                check(err_v < 0.01, "sliding rebound: tangential velocity change", r.velocity.x,
                      vt - dv_t);
                check(err_w < 0.01, "sliding rebound: spin change", r.angular_velocity.y,
                      wy + dw_y);
              }
        }
  std::printf("%d impacts, %d in gross sliding: max |F_t|/(mu F_n+) = %.12f, max |J_t|/(mu J_n+) "
              "= %.12f, max tensile/compressive normal impulse = %.2e, worst rigid-body "
              "rebound error = %.2e (of the change)\n",
              n_impacts, n_sliding, worst_force_ratio, worst_impulse_ratio, worst_attraction,
              worst_rigid_body);
  check(worst_force_ratio > 0.999, "friction reaches the Coulomb limit", worst_force_ratio, 1.);
  return sluice::unit::failures == 0 ? 0 : 1;
}
