#pragma once
// A coupled CFD-DEM scene: the DEM sub-cycles inside each fluid step with the
// drag integrated implicitly, the fluid advances with the particles' porosity
// and reaction, and the validation cases print their 'result:' line.

#include <sluice/core/scene_parameters.h>

#include <mpi.h>

namespace sluice
{
  /// Returns the process exit code: 0, or 3 when a validation error is above
  /// 'cfd-dem validation/tolerance'. Throws InputError (before writing
  /// anything) and SolverFailure.
  int run_cfd_dem_scene(const SceneParameters &parameters, MPI_Comm communicator);
} // namespace sluice
