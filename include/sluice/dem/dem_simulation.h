#pragma once
// A DEM scene from start to end: set-up (checks first, then particles, lists and
// output files), the velocity-Verlet time loop, output and the final summary.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/scene_extension.h>

#include <mpi.h>

namespace sluice
{
  /// Runs the scene; returns the process exit code (0, or 3 when a validation
  /// error exceeds the tolerance set in the .prm). Throws InputError for bad input
  /// before anything is written. An extension (scene_extension.h) takes over
  /// the step and adds its fields, records and lines.
  int run_dem_scene(const SceneParameters &parameters, MPI_Comm communicator,
                    DemSceneExtension *extension = nullptr);
} // namespace sluice
