// The forces a coupled scene puts on the SPH particles (the grains'
// reactions, SphSolver::set_external_forces) stay with their particles when a
// rebuild of the pairs moves them to other ranks (sph_solver.h), run on 1, 2
// and 3 ranks: a jittered lattice, periodic in all three directions, crosses
// its box diagonally at 1 m/s through several rebuilds, each particle pushed
// by a force of its own. Then
// - particles have changed ranks (on more than one rank);
// - each owned particle's force is the one given to its id;
// - the fluid's momentum has grown by the forces' sum times the time, to
//   round-off: the pair forces cancel, and no force was lost or doubled.

#include <sluice/sph/sph_solver.h>

#include "check.h"
#include "sph_lattice.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <set>

using namespace sluice;
using sluice::unit::check;

namespace
{
  /// The force given to particle 'id' [N]: of the order of its weight.
  Vec3 force_of(const std::uint64_t id)
  {
    return 1e-8 * Vec3(std::sin(0.37 * id), std::cos(0.11 * id), std::sin(0.73 * id + 1.));
  }

  /// The sum over the ranks' owned particles of m v [kg m/s].
  Vec3 momentum(const SphParticles &P, MPI_Comm comm)
  {
    double sum[3] = {0., 0., 0.};
    for (unsigned int a = 0; a < P.n_local; ++a)
      for (unsigned int d = 0; d < 3; ++d)
        sum[d] += P.mass[a] * P.velocity[a][d];
    MPI_Allreduce(MPI_IN_PLACE, sum, 3, MPI_DOUBLE, MPI_SUM, comm);
    return Vec3(sum[0], sum[1], sum[2]);
  }
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  MPI_Comm                                 comm = MPI_COMM_WORLD;
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);

  const double dx = 1e-3;
  const unsigned int n = 16;
  SphParticles all = sluice::unit::sph_lattice(n, n, n, dx, 1000., 0.1);
  const Vec3   velocity(0.8, 0.5, 0.3);
  for (Vec3 &v : all.velocity)
    v = velocity;
  const PeriodicBox box(Vec3(), dx * Vec3(n, n, n), {{true, true, true}});
  SphSettings       settings;
  settings.forces.state.sound_speed = 10.;
  SphSolver solver(all, box, settings, comm);

  std::set<std::uint64_t> owned_at_start;
  for (unsigned int a = 0; a < solver.particles().n_local; ++a)
    owned_at_start.insert(solver.particles().id[a]);
  std::vector<Vec3> forces(solver.particles().n_local);
  Vec3              total_force;
  for (unsigned int a = 0; a < solver.particles().n_local; ++a)
    forces[a] = force_of(solver.particles().id[a]);
  for (std::uint64_t id = 0; id < all.size(); ++id)
    total_force += force_of(id);
  solver.set_external_forces(forces);

  const Vec3         start = momentum(solver.particles(), comm);
  const double       dt    = 3e-5;
  const unsigned int steps = 80; // 2.4 mm along x, about 0.6 of a rank's cell
  for (unsigned int k = 0; k < steps; ++k)
    solver.step(dt);

  const SphParticles &P     = solver.particles();
  unsigned int        moved = 0, wrong = 0;
  for (unsigned int a = 0; a < P.n_local; ++a)
    {
      moved += owned_at_start.count(P.id[a]) == 0;
      wrong += !(norm(solver.external_forces()[a] - force_of(P.id[a])) == 0.);
    }
  moved = dealii::Utilities::MPI::sum(moved, comm);
  wrong = dealii::Utilities::MPI::sum(wrong, comm);
  check(solver.n_pair_builds() > 2, "the pairs were rebuilt as the fluid moved",
        solver.n_pair_builds(), 3);
  if (n_ranks > 1)
    check(moved > 0, "particles changed ranks", moved, 1);
  check(wrong == 0 && solver.external_forces().size() == P.n_local,
        "each owned particle keeps its own force", wrong, 0);

  const Vec3 gained = momentum(P, comm) - start, expected = (steps * dt) * total_force;
  const double scale = norm(all.mass[0] * double(all.size()) * velocity);
  check(norm(gained - expected) <= 1e-12 * scale, "momentum gained = sum F t",
        norm(gained - expected) / scale, 0.);
  return sluice::unit::failures == 0 ? 0 : 1;
}
