#pragma once
// The validation of the mesh walls against the plane wall (prm/geometry/
// mesh_plane_equivalence.prm): the scene is run twice in lockstep, once with
// its mesh walls and without the extra planes of 'walls/planes', once with
// those planes and without the meshes, and the two are compared at every step
// (doc/geometry.md). A triangulated plane must give the plane's motion and
// forces to round-off: across edges and vertices, where a sphere overlaps
// several triangles, the one-contact-per-patch rule leaves one contact with
// the plane's normal, so the normal force cannot jump there.

#include <sluice/core/scene_parameters.h>

#include <mpi.h>

namespace sluice
{
  /// Runs the comparison; the result line's value is the largest relative
  /// difference (positions over the radius; velocities, spins and contact
  /// forces over their largest magnitude in the plane run). Returns the exit
  /// code (3 above 'validation/tolerance'). One MPI rank only (InputError).
  int run_mesh_plane_equivalence(const SceneParameters &parameters, MPI_Comm communicator);
} // namespace sluice
