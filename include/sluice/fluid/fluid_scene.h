#pragma once
// Runs a scene with 'simulation/physics = fluid'.

#include <sluice/core/scene_parameters.h>

#include <mpi.h>

namespace sluice
{
  /// Returns the process exit code: 0, or 3 when a validation error is above
  /// 'fluid validation/tolerance'. Throws InputError (before writing anything)
  /// and SolverFailure.
  int run_fluid_scene(const SceneParameters &parameters, MPI_Comm communicator);
} // namespace sluice
