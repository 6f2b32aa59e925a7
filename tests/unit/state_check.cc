// The DEM's health checks find and name what went wrong:
// - a NaN or infinite position or velocity makes the per-step motion test
//   report an infinite displacement (max() alone would skip a NaN), and the
//   failure names the particle that is not finite;
// - coincident particles and a centre behind a wall are refused at the start,
//   naming them; a deep overlap during the run names the pair.
// Inputs the scene checks refuse cannot reach the run-time path, so it is
// tested here directly.

#include <sluice/dem/state_check.h>
#include <sluice/dem/velocity_verlet.h>

#include <deal.II/base/mpi.h>

#include "check.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  ParticleStorage three_particles()
  {
    ParticleStorage P;
    P.push_back(0, Vec3(0.010, 0.01, 0.01), Vec3(), Vec3(), 0.001, 0, 2500.);
    P.push_back(1, Vec3(0.013, 0.01, 0.01), Vec3(), Vec3(), 0.001, 0, 2500.);
    P.push_back(2, Vec3(0.016, 0.01, 0.01), Vec3(), Vec3(), 0.001, 0, 2500.);
    P.n_local = P.size();
    return P;
  }

  /// Whether f() throws E with a message containing 'text'.
  template <typename E, typename F>
  bool throws_naming(const F &f, const std::string &text)
  {
    try
      {
        f();
      }
    catch (const E &e)
      {
        const bool found = std::string(e.what()).find(text) != std::string::npos;
        if (!found)
          std::printf("message without '%s': %s\n", text.c_str(), e.what());
        return found;
      }
    return false;
  }
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const PeriodicBox box(Vec3(), Vec3(0.03, 0.03, 0.03), {{false, false, false}});
  const WallSet walls({{Vec3(), Vec3(0., 0., 1.), 0, "floor", "", ""}}, {}, box, "test");
  const StepInfo               where{17, 0.0017, 1e-4, 0.0005, 1.};

  for (const double bad : {std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()})
    {
      ParticleStorage P = three_particles();
      NeighbourList   L;
      L.build(P, box, walls, 0.001, 0.0002, false, ContactHistoryMap());
      check(std::isfinite(L.max_displacement_square(P)),
            "finite state: finite displacement", 0., 0.);
      P.position[1].y = bad;
      check(std::isinf(L.max_displacement_square(P)),
            "non-finite position: infinite displacement", 0., 1.);
      P.position[1].y = 0.01;
      P.velocity[2].z = bad;
      drift(P, 1e-6);
      check(std::isinf(L.max_displacement_square(P)),
            "non-finite velocity, drifted: infinite displacement", 0., 1.);
      check(throws_naming<SimulationFailure>([&] { fail_non_finite(P, where, MPI_COMM_WORLD); },
                                             "particle 2 "),
            "the failure names the non-finite particle", 0., 1.);
      check(throws_naming<SimulationFailure>([&] { fail_non_finite(P, where, MPI_COMM_WORLD); },
                                             "at step 17"),
            "the failure names the step", 0., 1.);
    }

  {
    ParticleStorage P = three_particles();
    P.position[2]     = P.position[1];
    NeighbourList L;
    L.build(P, box, walls, 0.001, 0.0002, false, ContactHistoryMap());
    check(throws_naming<InputError>(
            [&] { check_initial_state(P, L, walls, box, 0.05, "scene.prm", MPI_COMM_WORLD); },
            "particles 1 and 2 are at the same position"),
          "coincident particles are refused by name", 0., 1.);
  }
  {
    ParticleStorage P = three_particles();
    P.position[0].z   = -0.0005;
    NeighbourList L;
    L.build(P, box, walls, 0.001, 0.0002, false, ContactHistoryMap());
    check(throws_naming<InputError>(
            [&] { check_initial_state(P, L, walls, box, 0.05, "scene.prm", MPI_COMM_WORLD); },
            "particle 0 at (0.01, 0.01, -0.0005) and wall 'floor': its centre is behind"),
          "a centre behind a wall is refused by name", 0., 1.);
  }
  {
    ParticleStorage P = three_particles();
    P.position[1].x   = 0.0115; // overlaps particle 0 by half a radius
    NeighbourList L;
    L.build(P, box, walls, 0.001, 0.0002, false, ContactHistoryMap());
    check(throws_naming<SimulationFailure>(
            [&] { fail_deep_overlap(P, L, walls, box, 0.2, where, MPI_COMM_WORLD); },
            "particles 0 and 1 overlap by 0.5 of the smaller radius"),
          "a deep overlap names the pair", 0., 1.);
    // A well-separated state passes the start check.
    P.position[1].x = 0.013;
    L.build(P, box, walls, 0.001, 0.0002, false, ContactHistoryMap());
    check(!throws_naming<InputError>(
            [&] { check_initial_state(P, L, walls, box, 0.05, "scene.prm", MPI_COMM_WORLD); },
            ""),
          "a valid state is accepted", 0., 1.);
  }
  std::printf("%s\n", sluice::unit::failures == 0 ? "state checks: ok" : "state checks: FAILED");
  return sluice::unit::failures == 0 ? 0 : 1;
}
