#pragma once
// The fluid block cut to the solid walls ('sph/solid walls'). The block is
// given as a box, which a curved or tilted wall can cross (a mill's shell):
// before the run, the lattice points the walls cut off are left out, so that
// the fluid starts inside its container and at rest. A point goes when it is
//   - behind a plane, or nearer to it than the contact radius R;
//   - nearer to a mesh than R;
//   - outside a closed mesh: an odd number of its triangles crossed by a ray
//     from the point (Jordan's parity; the ray's direction is chosen off the
//     axes, so that it misses edges of axis-aligned meshes).
// A point exactly R from a wall (a lattice laid on a floor) stays. The wall
// particles and the hydrostatic densities of the kept points are unchanged.

#include <sluice/dem/wall_set.h>
#include <sluice/sph/sph_setup.h>

namespace sluice
{
  /// Leaves out the fluid particles of 'setup' the walls cut off (above) and
  /// returns how many.
  unsigned int remove_fluid_beyond_walls(SphSetup &setup, const WallSet &walls, double radius);

  /// Whether x lies inside the closed surface 'mesh' (ray parity).
  bool inside_closed_mesh(const TriangleMesh &mesh, const Vec3 &x);
} // namespace sluice
