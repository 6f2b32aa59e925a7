// One contact per patch between a sphere and a triangle mesh (see the header).

#include <sluice/dem/mesh_contact.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  namespace
  {
    ClosestPoint closest_on(const TriangleMesh &mesh, const unsigned int t, const Vec3 &x)
    {
      const auto &v = mesh.triangles[t];
      return closest_point_on_triangle(x, mesh.vertices[v[0]], mesh.vertices[v[1]],
                                       mesh.vertices[v[2]]);
    }

    /// The edge (0: ab, 1: bc, 2: ca) or the vertex (0: a, 1: b, 2: c) of a region.
    int edge_of(const TriangleRegion r)
    {
      return r == TriangleRegion::edge_ab ? 0 :
             r == TriangleRegion::edge_bc ? 1 :
             r == TriangleRegion::edge_ca ? 2 :
                                            -1;
    }
    int vertex_of(const TriangleRegion r)
    {
      return r == TriangleRegion::vertex_a ? 0 :
             r == TriangleRegion::vertex_b ? 1 :
             r == TriangleRegion::vertex_c ? 2 :
                                             -1;
    }

    /// Whether triangle t's closest point to x lies on the edge from vertex
    /// p to vertex q of the mesh (either direction).
    bool closest_on_edge(const TriangleMesh &mesh, const unsigned int t, const Vec3 &x,
                         const unsigned int p, const unsigned int q)
    {
      const TriangleRegion r = closest_on(mesh, t, x).region;
      const auto          &v = mesh.triangles[t];
      const int            e = edge_of(r);
      if (e < 0)
        return false;
      const unsigned int a = v[e], b = v[(e + 1) % 3];
      return (a == p && b == q) || (a == q && b == p);
    }

    /// Whether every triangle at vertex w has its closest point to x there.
    bool closest_at_vertex(const TriangleMesh &mesh, const unsigned int w, const Vec3 &x)
    {
      for (unsigned int k = mesh.vertex_offset[w]; k < mesh.vertex_offset[w + 1]; ++k)
        {
          const unsigned int t = mesh.vertex_triangles[k];
          const int          c = vertex_of(closest_on(mesh, t, x).region);
          if (c < 0 || mesh.triangles[t][c] != w)
            return false;
        }
      return true;
    }

    /// An edge or vertex point is a contact of its own: a local minimum of the
    /// distance over the surface. (The triangles that share it all find it;
    /// mesh_contacts() keeps the first.)
    bool is_own_contact(const TriangleMesh &mesh, const unsigned int t, const ClosestPoint &c,
                        const Vec3 &x)
    {
      const auto &v = mesh.triangles[t];
      if (const int e = edge_of(c.region); e >= 0)
        {
          const unsigned int across = mesh.neighbours[t][e];
          if (across == TriangleMesh::none)
            return true; // an open (or non-manifold) edge: the sphere meets the rim
          return closest_on_edge(mesh, across, x, v[e], v[(e + 1) % 3]);
        }
      return closest_at_vertex(mesh, v[vertex_of(c.region)], x);
    }
    /// The distance from x to the segment from a to b.
    double distance_to_segment(const Vec3 &x, const Vec3 &a, const Vec3 &b)
    {
      const Vec3   e = b - a;
      const double s = std::clamp(dot(x - a, e) / norm_square(e), 0., 1.);
      return norm(x - (a + s * e));
    }

    /// Two face contacts on the two triangles of a shallow concave fold (their
    /// normals less than 45 degrees apart): the shallower one's overlap less
    /// max(0, r - distance to the shared edge), so that it grows from zero as
    /// the centre enters the wedge where both faces' normal regions overlap,
    /// instead of appearing with nearly the other's overlap (doc/geometry.md).
    /// Right-angled and steeper folds keep each face as a plane's.
    void soften_shallow_folds(const TriangleMesh &mesh, const Vec3 &x, const double r,
                              const std::size_t first, std::vector<MeshContact> &contacts)
    {
      const double cos_45 = std::sqrt(0.5);
      for (std::size_t k = first; k < contacts.size(); ++k)
        for (std::size_t l = k + 1; l < contacts.size(); ++l)
          {
            MeshContact &a = contacts[k], &b = contacts[l];
            if (a.region != TriangleRegion::face || b.region != TriangleRegion::face ||
                !(dot(a.normal, b.normal) > cos_45))
              continue;
            for (unsigned int e = 0; e < 3; ++e)
              if (mesh.neighbours[a.triangle][e] == b.triangle)
                {
                  const auto  &v       = mesh.triangles[a.triangle];
                  const double reach   = r - distance_to_segment(x, mesh.vertices[v[e]],
                                                                 mesh.vertices[v[(e + 1) % 3]]);
                  MeshContact &shallow = a.overlap < b.overlap ? a : b;
                  shallow.overlap -= std::max(0., reach);
                }
          }
      // A softened contact may have no overlap left.
      contacts.erase(std::remove_if(contacts.begin() + first, contacts.end(),
                                    [](const MeshContact &c) { return !(c.overlap > 0.); }),
                     contacts.end());
    }
  } // namespace

  void mesh_contacts(const TriangleMesh &mesh, const Vec3 &x, const double r,
                     const std::vector<unsigned int> &candidates,
                     std::vector<MeshContact> &contacts)
  {
    const std::size_t first = contacts.size();
    for (const unsigned int t : candidates)
      {
        const ClosestPoint c = closest_on(mesh, t, x);
        const Vec3         d = x - c.point;
        const double       distance_2 = norm_square(d);
        if (distance_2 >= r * r)
          continue;
        // The same edge or vertex from each triangle that shares it, or a tie
        // between regions at one point (a centre right above a shared edge,
        // seen as a face point by one triangle): once, and its neighbours are
        // asked only the first time.
        bool seen = false;
        for (std::size_t k = first; k < contacts.size() && !seen; ++k)
          seen = norm_square(contacts[k].point - c.point) <= 1e-24 * r * r;
        if (seen || (c.region != TriangleRegion::face && !is_own_contact(mesh, t, c, x)))
          continue;
        const double distance = std::sqrt(distance_2);
        // A centre on the surface itself: the face's normal (the side it came
        // from is not known here).
        const Vec3 n = distance > 0. ? (1. / distance) * d : mesh.normals[t];
        contacts.push_back({t, c.region, c.point, n, r - distance});
      }
    soften_shallow_folds(mesh, x, r, first, contacts);
  }
} // namespace sluice
