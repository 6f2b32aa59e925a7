// Rigid clump bodies (dem/clump_bodies.h):
// - a rod of three overlapping spheres thrown and spinning under gravity:
//   its centroid on the parabola x0 + v0 t + g t^2 / 2 to round-off, its
//   angular momentum in space kept to round-off, its members rigidly apart;
// - the members' velocities v + w x (R r_m) against central differences of
//   their positions (error O(dt^2));
// - a constant force on one member, off the centroid, from rest: the work
//   it does (sum of F . dx_m) against the body's kinetic energy,
//   translation and rotation, converging as dt^2; the momentum F t exact.

#include <sluice/dem/clump_bodies.h>

#include "check.h"

#include <cmath>
#include <cstdio>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double density = 2500.;

  ClumpBodies one_rod(const std::vector<ClumpTemplate> &templates, const Vec3 &v, const Vec3 &w)
  {
    ClumpBodies bodies;
    bodies.add(templates[0], 0, density, Vec3(0., 0., 1.),
               Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized())), v,
               w);
    return bodies;
  }

  double kinetic_energy(const ClumpBodies &b)
  {
    return 0.5 * b.mass[0] * norm_square(b.velocity[0]) + rotational_energy(b.rotation[0], b.inertia[0]);
  }

  void check_free_flight(const std::vector<ClumpTemplate> &templates)
  {
    const Vec3   v0(1., 0., 2.), w0(0.3, 5., -2.), g(0., 0., -9.81);
    ClumpBodies  bodies = one_rod(templates, v0, w0);
    const double dt = 1e-4;
    const Eigen::Vector3d L0 = bodies.rotation[0].orientation * bodies.rotation[0].body_momentum;
    const ClumpMembers    start = expand_members(bodies, templates);
    for (unsigned int s = 0; s < 5000; ++s)
      {
        half_kick_bodies(bodies, 0.5 * dt, g);
        drift_bodies(bodies, dt);
        half_kick_bodies(bodies, 0.5 * dt, g);
      }
    const double t = 5000 * dt;
    const Vec3   expected = Vec3(0., 0., 1.) + t * v0 + (0.5 * t * t) * g;
    check(norm(bodies.position[0] - expected) < 1e-12, "thrown rod: centroid on the parabola",
          norm(bodies.position[0] - expected), 0.);
    const Eigen::Vector3d L = bodies.rotation[0].orientation * bodies.rotation[0].body_momentum;
    check((L - L0).norm() < 1e-12 * L0.norm(), "thrown rod: angular momentum kept",
          (L - L0).norm() / L0.norm(), 0.);
    const ClumpMembers end = expand_members(bodies, templates);
    double             worst = 0.;
    for (std::size_t a = 0; a < end.size(); ++a)
      for (std::size_t b = a + 1; b < end.size(); ++b)
        worst = std::max(worst, std::abs(norm(end.position[a] - end.position[b]) -
                                         norm(start.position[a] - start.position[b])));
    check(worst < 1e-14, "thrown rod: members rigidly apart", worst, 0.);
  }

  void check_member_velocities(const std::vector<ClumpTemplate> &templates)
  {
    const ClumpBodies  bodies = one_rod(templates, Vec3(0.2, -0.1, 0.3), Vec3(3., -1., 4.));
    const ClumpMembers now    = expand_members(bodies, templates);
    const double       delta  = 1e-5;
    ClumpBodies        ahead = bodies, behind = bodies;
    drift_bodies(ahead, delta);
    drift_bodies(behind, -delta);
    const ClumpMembers a = expand_members(ahead, templates), b = expand_members(behind, templates);
    double             worst = 0., scale = 0.;
    for (std::size_t k = 0; k < now.size(); ++k)
      {
        worst = std::max(worst, norm((1. / (2. * delta)) * (a.position[k] - b.position[k]) - now.velocity[k]));
        scale = std::max(scale, norm(now.velocity[k]));
      }
    check(worst < 1e-7 * scale, "member velocities v + w x (R r)", worst / scale, 0.);
  }

  /// Work of a constant force on member 0 against the kinetic energy gained.
  double work_energy_mismatch(const std::vector<ClumpTemplate> &templates, const double dt,
                              double &momentum_error)
  {
    ClumpBodies       bodies = one_rod(templates, Vec3(), Vec3());
    const Vec3        F(0., 0.3, 1.);
    const Vec3        none;
    const auto        loads = [&](const ClumpMembers &m) {
      std::vector<Vec3> f(m.size()), tau(m.size());
      f[0] = F;
      gather_loads(bodies, m, f, tau);
    };
    ClumpMembers members = expand_members(bodies, templates);
    loads(members);
    double             work = 0.;
    const unsigned int n    = std::lround(0.2 / dt);
    for (unsigned int s = 0; s < n; ++s)
      {
        const Vec3 before = members.position[0];
        half_kick_bodies(bodies, 0.5 * dt, none);
        drift_bodies(bodies, dt);
        members = expand_members(bodies, templates);
        loads(members);
        half_kick_bodies(bodies, 0.5 * dt, none);
        work += dot(F, members.position[0] - before);
      }
    momentum_error = norm(bodies.mass[0] * bodies.velocity[0] - (n * dt) * F) / norm((n * dt) * F);
    return std::abs(kinetic_energy(bodies) - work) / work;
  }

  void check_work_energy(const std::vector<ClumpTemplate> &templates)
  {
    double       p_coarse = 0., p_fine = 0.;
    const double coarse = work_energy_mismatch(templates, 2e-4, p_coarse);
    const double fine   = work_energy_mismatch(templates, 1e-4, p_fine);
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
  const std::vector<ClumpTemplate> templates = {rod_clump(3, 0.01, 0.2)};
  check_free_flight(templates);
  check_member_velocities(templates);
  check_work_energy(templates);
  if (sluice::unit::failures == 0)
    std::printf("clump bodies: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
