// The DEM's walls holding SPH fluid particles (sph/sph_solid_walls.h), one
// particle (radius R = dx/2) at a time, integrated with a fine step:
// - a floor of two triangles gives the trajectory a plane floor gives, to
//   round-off, whether the particle lands inside a triangle or on the
//   diagonal edge the two share (one contact there, not two);
// - thrown at the floor without gravity, it leaves with the speed of the
//   linear spring-dashpot whose dashpot may not pull (the force ends where
//   k delta = c v_n, before the overlap does: the closed form below, 0.5%),
//   and never comes within R/2 of the floor;
// - at rest under gravity it sits at the overlap m g / k and the floor
//   carries m g; every step, the walls' load is minus the force on the
//   particle (action and reaction, to round-off);
// - a floor moving up at 0.1 m/s lifts a particle resting on it to its speed
//   and gives it the power F . v_wall;
// - the contact's stable step is 0.2 sqrt(m / k).

#include <sluice/dem/contact_properties.h>
#include <sluice/sph/sph_solid_walls.h>

#include "check.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double dx = 1e-3, R = 0.5 * dx, m = 1e-6, k = 10.;
  const PeriodicBox box(Vec3(-0.01, -0.01, -0.01), Vec3(0.01, 0.01, 0.01), {{false, false, false}});

  /// A square floor [-L, L]^2 at z = 0 of two triangles, their shared
  /// diagonal from (-L, -L) to (L, L), as a gmsh 2.2 file.
  std::string floor_mesh_file()
  {
    const std::string path =
      (std::filesystem::temp_directory_path() / "sluice_unit_sph_solid_walls_floor.msh").string();
    std::ofstream out(path);
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n"
        << "1 -0.008 -0.008 0\n2 0.008 -0.008 0\n3 0.008 0.008 0\n4 -0.008 0.008 0\n"
        << "$EndNodes\n$Elements\n2\n1 2 2 1 1 1 2 3\n2 2 2 1 1 1 3 4\n$EndElements\n";
    return path;
  }

  SphParticles one_particle(const Vec3 &x, const Vec3 &v)
  {
    SphParticles P;
    P.id           = {0};
    P.position     = {x};
    P.velocity     = {v};
    P.acceleration = {Vec3()};
    P.mass         = {m};
    P.wall         = {0};
    P.n_local      = 1;
    return P;
  }

  struct Flight
  {
    std::vector<double> z;          // the height at every step
    double              closest = 1e300; // the least distance to the floor [m]
    double              worst_balance = 0.; // |load + m a_wall| / (m |a_wall|)
    Vec3                velocity;   // at the end
    // Means over the last quarter of the steps.
    double              mean_power = 0., mean_speed = 0.;
  };

  /// The restitution of a linear spring-dashpot of damping ratio zeta whose
  /// force is cut at zero: the contact ends when k delta + c delta' = 0, at
  /// omega_d t = pi - atan(2 zeta sqrt(1 - zeta^2) / (1 - 2 zeta^2)), and
  /// the particle leaves with delta' there (delta = A e^(-zeta omega t)
  /// sin(omega_d t)). For zeta < 1/sqrt(2).
  double cut_dashpot_restitution(const double zeta)
  {
    const double s     = std::sqrt(1. - zeta * zeta);
    const double phase = M_PI - std::atan(2. * zeta * s / (1. - 2. * zeta * zeta));
    return std::exp(-zeta * phase / s) * std::abs(std::cos(phase) - zeta / s * std::sin(phase));
  }

  /// Symplectic Euler in steps of 'dt' for 'n' steps against 'walls' (moved
  /// each step), under gravity g.
  Flight fly(WallSet &walls, const double e, const Vec3 &x0, const Vec3 &v0, const Vec3 &g,
             const double dt, const unsigned int n)
  {
    SphSolidWalls solid(walls, {k, damping_ratio_from_restitution(e), R}, box.lower, box.upper);
    SphParticles  P = one_particle(x0, v0);
    Flight        f;
    for (unsigned int step = 0; step < n; ++step)
      {
        walls.move(step * dt, dt);
        P.acceleration[0] = Vec3();
        solid.add_accelerations(P);
        const Vec3 wall_acceleration = P.acceleration[0];
        Vec3       load;
        for (const Vec3 &F : solid.wall_forces())
          load += F;
        if (norm(wall_acceleration) > 0.)
          f.worst_balance = std::max(f.worst_balance, norm(load + m * wall_acceleration) /
                                                        (m * norm(wall_acceleration)));
        P.velocity[0] += dt * (wall_acceleration + g);
        P.position[0] += dt * P.velocity[0];
        f.z.push_back(P.position[0].z);
        const double floor_z = walls.n_planes() > 0 ? walls[0].point.z :
                                                      walls.meshes()[0].mesh().vertices[0].z;
        f.closest = std::min(f.closest, P.position[0].z - floor_z);
        if (4 * step >= 3 * n)
          {
            f.mean_power += solid.wall_powers()[0] / (n - 3 * n / 4);
            f.mean_speed += P.velocity[0].z / (n - 3 * n / 4);
          }
      }
    f.velocity = P.velocity[0];
    return f;
  }
} // namespace

int main()
{
  const std::string file = floor_mesh_file();
  MeshWallParameters mesh;
  mesh.file = file;
  mesh.name = "floor";
  const PlaneWall plane{Vec3(), Vec3(0., 0., 1.), 0, "floor", "", ""};
  const double    dt = 1e-6; // 2000 steps per period 2 pi sqrt(m / k)
  const Vec3      down(0., 0., -0.05), no_gravity;

  // Plane and mesh, inside a triangle and on the shared diagonal.
  for (const Vec3 &landing : {Vec3(0.003, -0.002, 0.), Vec3(0.001, 0.001, 0.)})
    {
      WallSet     plane_walls({plane}, {}, box, "test"), mesh_walls({}, {mesh}, box, "test");
      const Vec3  x0 = landing + Vec3(0., 0., R + 1e-5);
      const Flight a = fly(plane_walls, 0.5, x0, down, no_gravity, dt, 3000);
      const Flight b = fly(mesh_walls, 0.5, x0, down, no_gravity, dt, 3000);
      double worst = 0.;
      for (std::size_t s = 0; s < a.z.size(); ++s)
        worst = std::max(worst, std::abs(a.z[s] - b.z[s]));
      std::printf("landing at (%g, %g): mesh vs plane %.3g m, rebound %.4f m/s\n", landing.x,
                  landing.y, worst, a.velocity.z);
      check(worst < 1e-15, "the two-triangle floor's trajectory equals the plane's [m]", worst,
            0.);
    }

  // Restitution and no crossing, at three restitutions.
  for (const double e : {0.1, 0.5, 0.9})
    {
      WallSet      walls({}, {mesh}, box, "test");
      const Flight f = fly(walls, e, Vec3(0.002, -0.001, R + 1e-5), down, no_gravity, dt, 3000);
      const double realised = f.velocity.z / -down.z;
      const double expected = cut_dashpot_restitution(damping_ratio_from_restitution(e));
      std::printf("e = %.1f: realised %.5f (closed form %.5f), closest approach %.4f R\n", e,
                  realised, expected, f.closest / R);
      // (first-order steps of omega dt = 0.003 with a dashpot: 0.3% at e = 0.1)
      check(std::abs(realised - expected) < 5e-3 * expected, "realised restitution", realised,
            expected);
      check(f.closest > 0.5 * R, "closest approach to the floor [R]", f.closest / R, 0.5);
      check(f.worst_balance < 1e-14, "wall load + particle force", f.worst_balance, 0.);
    }

  // At rest under gravity: overlap m g / k, load m g.
  {
    WallSet       walls({}, {mesh}, box, "test");
    const Vec3    g(0., 0., -9.81);
    SphSolidWalls solid(walls, {k, damping_ratio_from_restitution(0.1), R}, box.lower, box.upper);
    const Flight  f        = fly(walls, 0.1, Vec3(0.001, 0.002, R), Vec3(), g, dt, 20000);
    const double  expected = R - m * 9.81 / k;
    std::printf("at rest: height %.9g m, expected %.9g m\n", f.z.back(), expected);
    check(std::abs(f.z.back() - expected) < 1e-6 * R, "resting height R - m g / k [m]",
          f.z.back(), expected);
    SphParticles P = one_particle(Vec3(0.001, 0.002, f.z.back()), Vec3());
    solid.add_accelerations(P);
    check(std::abs(solid.wall_forces()[0].z + m * 9.81) < 1e-6 * m * 9.81,
          "the floor's load at rest [N]", solid.wall_forces()[0].z, -m * 9.81);
    check(std::abs(solid.stable_time_step(P) - 0.2 * std::sqrt(m / k)) < 1e-18,
          "the contact's stable step [s]", solid.stable_time_step(P), 0.2 * std::sqrt(m / k));
  }

  // A floor rising at 0.1 m/s lifts a particle resting on it.
  {
    PlaneWall rising = plane;
    rising.velocity  = "0, 0, 0.1";
    WallSet      walls({rising}, {}, box, "test");
    const Flight f = fly(walls, 0.1, Vec3(0., 0., R), Vec3(), Vec3(0., 0., -9.81), dt, 40000);
    std::printf("rising floor: particle at %.6f m/s, power %.4g W\n", f.mean_speed,
                f.mean_power);
    check(std::abs(f.mean_speed - 0.1) < 1e-4, "the lifted particle's mean speed [m/s]",
          f.mean_speed, 0.1);
    check(std::abs(f.mean_power - m * 9.81 * 0.1) < 1e-3 * m * 9.81 * 0.1,
          "the mean power the floor gives, m g v [W]", f.mean_power, m * 9.81 * 0.1);
  }
  std::filesystem::remove(file);
  return sluice::unit::failures == 0 ? 0 : 1;
}
