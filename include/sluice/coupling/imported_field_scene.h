#pragma once
// A DEM scene whose particles an imported flow field drives one way
// ('imported field' subsection; Gao & Sun 2021 §5.1): each step the field is
// sampled at every particle after the drift (imported_field_series.h) and
// the drag (any of the closures) and the pressure-gradient force are frozen
// for the half kicks, the drag integrated exactly (implicit_drag.h). Nothing
// goes back to the fluid and no fluid system is built; a particle outside
// the field feels no fluid force and is counted. Everything else (walls,
// meshes, streams, wear, output, checkpoints) is the DEM scene's.

#include <sluice/core/scene_parameters.h>

#include <mpi.h>

namespace sluice
{
  /// Returns the exit code (0, or 3 when 'imported field/check' is above
  /// 'validation/tolerance'). Throws InputError before anything is written.
  int run_imported_field_scene(const SceneParameters &parameters, MPI_Comm communicator);
} // namespace sluice
