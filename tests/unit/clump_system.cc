// The rigid bodies of a clump scene (dem/clump_system.h), one rod of three
// overlapping spheres:
// - thrown and spinning under gravity: its centroid on the parabola
//   x0 + v0 t + g t^2 / 2 to round-off, its angular momentum in space kept to
//   round-off, its members rigidly apart;
// - the members' velocities v + w x (R r_m) against central differences of
//   their positions (error O(dt^2));
// - a constant force on one member, off the centroid, from rest: the work it
//   does (sum of F . dx_m) against the body's kinetic energy, translation and
//   rotation, converging as dt^2; the momentum F t exact.

#include <sluice/dem/clump_system.h>
#include <sluice/dem/particle_exchange.h>
#include <sluice/dem/velocity_verlet.h>

#include "check.h"

#include <cmath>
#include <cstdio>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double density = 2500.;

  /// One rod at (0, 0, 1), turned by 0.4 rad about (1, 1, 0), moving with v
  /// and spinning with w; its members in 'members'.
  ClumpSystem one_rod(const Vec3 &v, const Vec3 &w, ParticleStorage &members)
  {
    ClumpTemplateParameters t;
    t.shape         = ClumpShape::rod;
    t.rod_members   = 3;
    t.member_radius = 0.01;
    t.overlap       = 0.2;
    ClumpParameters parameters;
    parameters.templates = {t};
    ParticleFieldRegistry fields;
    ClumpSystem::declare_fields(fields);
    ClumpSystem      clumps(parameters, fields);
    ParticleStorage &B = clumps.bodies;
    B.push_back(0, Vec3(0., 0., 1.), v, w, clumps.templates[0].bounding_radius(), 0, density);
    B.n_extra = fields.doubles_per_particle();
    B.extra.assign(B.n_extra, 0.);
    B.n_local = 1;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized()));
    double *e = B.extra_of(0);
    const double quaternion[4] = {q.w(), q.x(), q.y(), q.z()};
    for (unsigned int k = 0; k < 4; ++k)
      e[fields.find(clump_fields::orientation)->offset + k] = quaternion[k];
    e[fields.find(clump_fields::scale)->offset] = 1.;
    clumps.set_mass_properties({density}, false);
    clumps.set_momenta_from_angular_velocity(0, 1);
    clumps.set_mass_properties({density});
    clumps.expand(members);
    return clumps;
  }

  /// A velocity-Verlet half kick of the body: centroid and rotation.
  void half_kick_body(ClumpSystem &clumps, const double h, const Vec3 &gravity)
  {
    half_kick(clumps.bodies, h, gravity);
    clumps.kick_rotation(h);
  }

  double kinetic_energy(const ClumpSystem &c)
  {
    return 0.5 * c.bodies.mass[0] * norm_square(c.bodies.velocity[0]) + c.rotational_energy();
  }

  Eigen::Vector3d angular_momentum(const ClumpSystem &c)
  {
    const RigidRotation r = c.rotation_of(0);
    return r.orientation * r.body_momentum;
  }

  void check_free_flight()
  {
    const Vec3            v0(1., 0., 2.), w0(0.3, 5., -2.), g(0., 0., -9.81);
    ParticleStorage       members;
    ClumpSystem           clumps = one_rod(v0, w0, members);
    const ParticleStorage start  = members;
    const double          dt     = 1e-4;
    const Eigen::Vector3d L0     = angular_momentum(clumps);
    for (unsigned int s = 0; s < 5000; ++s)
      {
        half_kick_body(clumps, 0.5 * dt, g);
        clumps.drift(dt);
        half_kick_body(clumps, 0.5 * dt, g);
      }
    const double t        = 5000 * dt;
    const Vec3   expected = Vec3(0., 0., 1.) + t * v0 + (0.5 * t * t) * g;
    check(norm(clumps.bodies.position[0] - expected) < 1e-12, "thrown rod: centroid on the parabola",
          norm(clumps.bodies.position[0] - expected), 0.);
    const Eigen::Vector3d L = angular_momentum(clumps);
    check((L - L0).norm() < 1e-12 * L0.norm(), "thrown rod: angular momentum kept",
          (L - L0).norm() / L0.norm(), 0.);
    clumps.move_members(members);
    double worst = 0.;
    for (unsigned int a = 0; a < members.size(); ++a)
      for (unsigned int b = a + 1; b < members.size(); ++b)
        worst = std::max(worst, std::abs(norm(members.position[a] - members.position[b]) -
                                         norm(start.position[a] - start.position[b])));
    check(worst < 1e-14, "thrown rod: members rigidly apart", worst, 0.);
  }

  void check_member_velocities()
  {
    ParticleStorage   now, a, b;
    const ClumpSystem clumps = one_rod(Vec3(0.2, -0.1, 0.3), Vec3(3., -1., 4.), now);
    const double      delta  = 1e-5;
    ClumpSystem       ahead = clumps, behind = clumps;
    ahead.drift(delta);
    behind.drift(-delta);
    ahead.expand(a);
    behind.expand(b);
    double worst = 0., scale = 0.;
    for (unsigned int k = 0; k < now.size(); ++k)
      {
        worst = std::max(worst, norm((1. / (2. * delta)) * (a.position[k] - b.position[k]) -
                                     now.velocity[k]));
        scale = std::max(scale, norm(now.velocity[k]));
      }
    check(worst < 1e-7 * scale, "member velocities v + w x (R r)", worst / scale, 0.);
  }

  /// Work of a constant force on member 0 against the kinetic energy gained.
  double work_energy_mismatch(const double dt, double &momentum_error)
  {
    ParticleStorage members;
    ClumpSystem     clumps = one_rod(Vec3(), Vec3(), members);
    const Vec3      F(0., 0.3, 1.);
    const auto      loads = [&]() {
      std::fill(members.force.begin(), members.force.end(), Vec3());
      members.force[0] = F;
      clumps.gather(members);
    };
    loads();
    double             work = 0.;
    const unsigned int n    = std::lround(0.2 / dt);
    for (unsigned int s = 0; s < n; ++s)
      {
        const Vec3 before = members.position[0];
        half_kick_body(clumps, 0.5 * dt, Vec3());
        clumps.drift(dt);
        clumps.move_members(members);
        loads();
        half_kick_body(clumps, 0.5 * dt, Vec3());
        work += dot(F, members.position[0] - before);
      }
    const ParticleStorage &B = clumps.bodies;
    momentum_error = norm(B.mass[0] * B.velocity[0] - (n * dt) * F) / norm((n * dt) * F);
    return std::abs(kinetic_energy(clumps) - work) / work;
  }

  void check_work_energy()
  {
    double       p_coarse = 0., p_fine = 0.;
    const double coarse = work_energy_mismatch(2e-4, p_coarse);
    const double fine   = work_energy_mismatch(1e-4, p_fine);
    std::printf("work against kinetic energy: %.2e at dt = 2e-4 s, %.2e at 1e-4 s (order %.2f); "
                "momentum error %.1e\n",
                coarse, fine, std::log2(coarse / fine), p_fine);
    check(fine < 1e-5, "work = kinetic energy gained", fine, 0.);
    check(std::log2(coarse / fine) > 1.8, "work-energy mismatch falls as dt^2",
          std::log2(coarse / fine), 2.);
    check(p_fine < 1e-12, "momentum = F t", p_fine, 0.);
  }
} // namespace

int main()
{
  check_free_flight();
  check_member_velocities();
  check_work_energy();
  if (sluice::unit::failures == 0)
    std::printf("clump system: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
