#pragma once
// The contacts of a sphere with a triangle mesh: one per contiguous contact
// patch, not one per triangle (doc/geometry.md).
//
// Each triangle within reach gives its closest point to the sphere's centre
// and the region of the triangle it lies in (face, edge, vertex;
// triangle_geometry.h). A point is a contact only if it is a local minimum of
// the distance over the whole surface:
//   - a point inside a face always is;
//   - a point on an edge is one only if the triangle across that edge has its
//     own closest point on the same edge too (otherwise that triangle holds a
//     closer point, and the edge point is the boundary of its patch, not a
//     contact of its own);
//   - a point at a vertex is one only if every triangle at that vertex has its
//     closest point there.
// The same edge or vertex reached from several triangles, and (on a tie) a
// face point that coincides with another contact's point, count once. So a
// sphere rolling over a shared edge or vertex of coplanar triangles feels one
// contact with the plane's normal; at a convex edge it feels the edge, once;
// in a concave corner it feels each face. The normal points from the contact
// point to the centre, so both sides of a triangle work (a thin plate).
// At a shallow concave fold (face normals less than 45 degrees apart) the
// shallower of the two face contacts loses max(0, r - distance to the shared
// edge) of its overlap, so that it grows from zero instead of appearing with
// nearly the other's overlap as the centre enters the wedge above the edge
// where both faces' normal regions overlap (the force would jump there).

#include <sluice/core/vector3.h>
#include <sluice/dem/triangle_geometry.h>
#include <sluice/dem/triangle_mesh.h>

#include <vector>

namespace sluice
{
  struct MeshContact
  {
    unsigned int   triangle; // the triangle the contact is attributed to
    TriangleRegion region;   // of that triangle
    Vec3           point;    // on the surface
    Vec3           normal;   // unit, from the point towards the sphere's centre
    double         overlap;  // radius - distance, > 0
  };

  /// The contacts of the sphere (centre x, radius r) with the triangles
  /// 'candidates' of 'mesh' (every triangle that may lie within r; others are
  /// not looked at), appended to 'contacts' in the order of 'candidates'.
  void mesh_contacts(const TriangleMesh &mesh, const Vec3 &x, double r,
                     const std::vector<unsigned int> &candidates,
                     std::vector<MeshContact> &contacts);
} // namespace sluice
