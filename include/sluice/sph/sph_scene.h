#pragma once
// An SPH fluid scene (simulation/physics = sph; doc/sph.md): a block of
// fluid particles on a lattice, walls of wall particles on the domain's
// faces, the leap-frog step, output (.pvd/.vtu of the particles, .csv),
// checkpoint and restart, and the validation case with its 'result:' line.

#include <sluice/core/scene_parameters.h>

#include <mpi.h>

namespace sluice
{
  /// Returns the exit code: 0, or 3 when the validation error is above
  /// 'sph/tolerance'. Throws InputError (before writing anything) and
  /// SimulationFailure (a non-finite state, a particle through a wall, a
  /// step above the stable one).
  int run_sph_scene(const SceneParameters &parameters, MPI_Comm communicator);
} // namespace sluice
