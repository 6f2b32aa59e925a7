// A moving wall follows its prescribed motion, and the neighbour list sees it:
// - a plane turning at a steady w for time T has its normal turned by |w| T
//   about w (to round-off: each step is an exact rotation about the same axis);
// - a plane moving with v(t) = (0, 0, A sin t) is at A (1 - cos T) after T,
//   to second order in the step (midpoint velocity);
// - the surface velocity is v + w x (x - x0);
// - the displacement the list test reads is the largest change of the signed
//   distance over the box, so a turning plane that passes through the box
//   centre moves most at the corners;
// - checkpoint state round-trips exactly.

#include <sluice/dem/wall_set.h>

#include "check.h"

#include <cmath>

using namespace sluice;
using sluice::unit::check;

int main()
{
  const PeriodicBox box(Vec3(-1., -1., -1.), Vec3(1., 1., 1.), {{false, false, false}});

  // Turning about x at 0.3 rad/s through the origin, for 2 s in steps of 1e-3 s.
  {
    PlaneWall spec{Vec3(), Vec3(0., 0., 1.), 0, "turning", "", ""};
    spec.angular_velocity = "0.3, 0, 0";
    WallSet walls({spec}, {}, box, "test");
    check(walls.any_moving(), "a wall with an angular velocity moves", 0., 1.);
    const double dt = 1e-3;
    for (unsigned int k = 0; k < 2000; ++k)
      walls.move(k * dt, dt);
    const double angle = 0.6;
    const Vec3   n     = walls[0].normal;
    check(std::abs(n.x) < 1e-15 && std::abs(n.y + std::sin(angle)) < 1e-12 &&
            std::abs(n.z - std::cos(angle)) < 1e-12,
          "normal after 0.6 rad about x (y component)", n.y, -std::sin(angle));
    // The corners (y, z) = (1, 1) and (-1, -1) move most: |z' - z| with
    // z' = -y sin a + z cos a, i.e. |-(sin a) + cos a - 1| at (1, 1).
    const double expected = std::abs(-std::sin(angle) + std::cos(angle) - 1.);
    check(std::abs(walls.max_displacement_since_build() - expected) < 1e-12,
          "largest displacement over the box of the turning plane",
          walls.max_displacement_since_build(), expected);
    // Surface velocity at (0, 0, 1) after the turn: w x x = 0.3 e_x x e_z = -0.3 e_y.
    const Vec3 u = walls[0].velocity_at(Vec3(0., 0., 1.));
    check(std::abs(u.y + 0.3) < 1e-15 && u.x == 0. && std::abs(u.z) < 1e-15,
          "surface velocity w x (x - x0), y component", u.y, -0.3);
    walls.mark_list_build();
    check(walls.max_displacement_since_build() == 0., "no displacement right after a build",
          walls.max_displacement_since_build(), 0.);

    // Checkpoint state round-trips.
    WallSet copy({spec}, {}, box, "test");
    copy.set_state(walls.state());
    check(copy.state() == walls.state(), "wall state restored exactly", 0., 0.);
  }

  // Oscillating along z: v = (0, 0, A sin t), second order in dt.
  {
    PlaneWall spec{Vec3(), Vec3(0., 0., 1.), 0, "oscillating", "", ""};
    spec.velocity = "0, 0, 0.01*sin(t)";
    double errors[2];
    for (const unsigned int refinement : {0u, 1u})
      {
        WallSet      walls({spec}, {}, box, "test");
        const double dt = 0.01 / (1u << refinement);
        const double T  = 2.;
        for (unsigned int k = 0; k < std::lround(T / dt); ++k)
          walls.move(k * dt, dt);
        errors[refinement] = std::abs(walls[0].point.z - 0.01 * (1. - std::cos(T)));
      }
    // Midpoint rule: error about A dt^2 T / 24 = 8e-8.
    check(errors[0] < 1e-7, "oscillating plane position error at dt = 0.01", errors[0], 0.);
    check(errors[0] / errors[1] > 3.9 && errors[0] / errors[1] < 4.1,
          "second order: error ratio when the step halves", errors[0] / errors[1], 4.);
  }

  // At rest: no motion, no displacement, nothing evaluated.
  {
    WallSet walls({PlaneWall{Vec3(), Vec3(0., 0., 1.), 0, "floor", "", ""}}, {}, box, "test");
    walls.move(0., 1.);
    check(!walls.any_moving() && walls.max_displacement_since_build() == 0. &&
            walls[0].point.z == 0.,
          "a wall without a motion stays", walls[0].point.z, 0.);
  }
  return sluice::unit::failures == 0 ? 0 : 1;
}
