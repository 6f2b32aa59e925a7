#pragma once
// A DEM scene from start to end: set-up (checks first, then particles, lists and
// output files), the velocity-Verlet time loop, output and the final summary.

#include <sluice/core/scene_parameters.h>

#include <mpi.h>

namespace sluice
{
  /// Runs the scene; returns the process exit code (0, or 3 when a validation
  /// error exceeds the tolerance set in the .prm). Throws InputError for bad input
  /// before anything is written.
  int run_dem_scene(const SceneParameters &parameters, MPI_Comm communicator);
} // namespace sluice
