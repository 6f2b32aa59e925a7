#pragma once
// A wall's surface as a triangle mesh, read from STL (ASCII or binary) or
// gmsh's ASCII .msh (formats 2.2 and 4.1, the 3-node triangles), and placed in
// the scene by a scale, a rotation and an offset.
//
// STL stores every facet with its own three vertices. The reader welds
// vertices closer than 1e-9 of the mesh's bounding-box diagonal into one (a
// generator's cos(2 pi) and sin(2 pi) do not give exactly the first vertex
// back), so that triangles sharing an edge know each other: the contact with a
// surface is one contact per contiguous patch, which needs the neighbours
// across edges and at vertices (doc/geometry.md).
//
// A file that is not a triangle mesh, a vertex that is not a finite number,
// a degenerate triangle (area below 1e-12 of its longest edge squared), or,
// where a closed surface is asked for, an edge with one triangle only, stops
// the scene with an InputError naming the file and the facet (counted from 1
// in the file's order).

#include <sluice/core/vector3.h>

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace sluice
{
  /// How a mesh file is placed in the scene: x_scene = R (scale x_file) + offset,
  /// R the rotation by 'angle' [rad] about 'axis' (right-handed).
  struct MeshPlacement
  {
    double scale = 1.;
    Vec3   axis{0., 0., 1.};
    double angle = 0.;
    Vec3   offset;
  };

  struct TriangleMesh
  {
    static constexpr unsigned int none = std::numeric_limits<unsigned int>::max();

    std::vector<Vec3>                        vertices;
    std::vector<std::array<unsigned int, 3>> triangles; // vertex indices, the file's order
    std::vector<Vec3>                        normals;   // unit, (b - a) x (c - a)
    std::vector<double>                      areas;
    /// neighbours[t][k]: the triangle across edge k (vertices k and k + 1 mod 3)
    /// of triangle t, or 'none' on an open edge or one shared by more than two
    /// triangles.
    std::vector<std::array<unsigned int, 3>> neighbours;
    unsigned int n_open_edges = 0, n_nonmanifold_edges = 0;
    /// The triangles at vertex v: vertex_triangles[vertex_offset[v] ...
    /// vertex_offset[v + 1] - 1].
    std::vector<unsigned int> vertex_offset, vertex_triangles;

    unsigned int size() const { return triangles.size(); }
    double       total_area() const;
  };

  /// Reads 'file' (.msh, binary or ASCII STL, by its content), places it, welds
  /// its vertices and finds the neighbours. 'context' starts every error
  /// message (e.g. "error in 'scene.prm': entry 'walls/mesh files'"); with
  /// 'closed' an open edge is an error. Throws InputError.
  TriangleMesh read_triangle_mesh(const std::string &file, const MeshPlacement &placement,
                                  bool closed, const std::string &context);

  /// The mesh from triangles given as three vertices each (welded, placed as
  /// is); 'where' names the source in error messages. Throws InputError.
  TriangleMesh make_triangle_mesh(const std::vector<std::array<Vec3, 3>> &facets, bool closed,
                                  const std::string &where);
} // namespace sluice
