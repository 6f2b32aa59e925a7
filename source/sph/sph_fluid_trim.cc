// The fluid block cut to the solid walls (see the header).

#include <sluice/dem/triangle_geometry.h>
#include <sluice/sph/sph_fluid_trim.h>

#include <cmath>
#include <stdexcept>

namespace sluice
{
  namespace
  {
    enum class Crossing
    {
      no,
      yes,
      unclear // through an edge or a vertex, or along the plane: try another ray
    };

    /// Whether the ray x + t d, t > 0, crosses triangle (a, b, c)
    /// (Moeller & Trumbore 1997).
    Crossing ray_crosses(const Vec3 &x, const Vec3 &d, const Vec3 &a, const Vec3 &b,
                         const Vec3 &c)
    {
      constexpr double eps = 1e-9; // of the barycentric coordinates
      const Vec3       e1 = b - a, e2 = c - a, p = cross(d, e2);
      const double     det = dot(e1, p);
      const Vec3       s = x - a;
      if (std::abs(det) < 1e-12 * norm(e1) * norm(e2))
        {
          // Parallel: no crossing, unless the ray runs in the triangle's plane.
          const Vec3 n = cross(e1, e2);
          return std::abs(dot(s, n)) < 1e-12 * norm(n) * (norm(s) + norm(e1)) ?
                   Crossing::unclear :
                   Crossing::no;
        }
      const double u = dot(s, p) / det;
      const Vec3   q = cross(s, e1);
      const double v = dot(d, q) / det;
      const double t = dot(e2, q) / det;
      if (u < -eps || v < -eps || u + v > 1. + eps || t <= 0.)
        return Crossing::no;
      if (u < eps || v < eps || u + v > 1. - eps)
        return Crossing::unclear;
      return Crossing::yes;
    }

    /// The distance from x to the nearest triangle of 'mesh'.
    double distance_to_mesh(const TriangleMesh &mesh, const Vec3 &x)
    {
      double nearest = INFINITY;
      for (const auto &t : mesh.triangles)
        {
          const ClosestPoint c = closest_point_on_triangle(x, mesh.vertices[t[0]],
                                                           mesh.vertices[t[1]],
                                                           mesh.vertices[t[2]]);
          nearest = std::min(nearest, norm(x - c.point));
        }
      return nearest;
    }

    /// Whether the walls leave the point x (a fluid particle of radius R) in.
    bool inside_walls(const WallSet &walls, const Vec3 &x, const double R)
    {
      // A point laid exactly R from a wall stays: a relative tolerance.
      const double at_least = R * (1. - 1e-9);
      for (const Plane &plane : walls.planes())
        if (dot(x - plane.point, plane.normal) < at_least)
          return false;
      for (const MeshWall &wall : walls.meshes())
        {
          const TriangleMesh &mesh = wall.mesh();
          if (distance_to_mesh(mesh, x) < at_least)
            return false;
          if (mesh.n_open_edges == 0 && mesh.n_nonmanifold_edges == 0 &&
              !inside_closed_mesh(mesh, x))
            return false;
        }
      return true;
    }
  } // namespace

  bool inside_closed_mesh(const TriangleMesh &mesh, const Vec3 &x)
  {
    // Directions off the axes and off each other's planes; a ray through an
    // edge or a vertex is not counted, the next one is cast.
    const Vec3 directions[] = {Vec3(0.7971, 0.5407, 0.2687), Vec3(-0.3119, 0.8378, 0.4481),
                               Vec3(0.1712, -0.4286, 0.8873), Vec3(-0.6437, -0.2939, -0.7066)};
    for (const Vec3 &d : directions)
      {
        unsigned int crossings = 0;
        bool         clear     = true;
        for (const auto &t : mesh.triangles)
          {
            const Crossing c = ray_crosses(x, d, mesh.vertices[t[0]], mesh.vertices[t[1]],
                                           mesh.vertices[t[2]]);
            if (c == Crossing::unclear)
              {
                clear = false;
                break;
              }
            crossings += c == Crossing::yes;
          }
        if (clear)
          return crossings % 2 == 1;
      }
    throw std::runtime_error("inside_closed_mesh: every ray met an edge or a vertex");
  }

  unsigned int remove_fluid_beyond_walls(SphSetup &setup, const WallSet &walls,
                                         const double radius)
  {
    SphParticles     &P = setup.particles;
    std::vector<bool> keep(P.size());
    for (unsigned int a = 0; a < P.size(); ++a)
      keep[a] = P.wall[a] || inside_walls(walls, P.position[a], radius);
    // Every array of the particles, compacted in step.
    const auto compact = [&keep](auto &values) {
      std::size_t kept = 0;
      for (std::size_t a = 0; a < values.size(); ++a)
        if (keep[a])
          values[kept++] = values[a];
      values.resize(kept);
    };
    compact(P.id), compact(P.position), compact(P.velocity), compact(P.acceleration);
    compact(P.mass), compact(P.density), compact(P.density_rate), compact(P.smoothing);
    compact(P.omega), compact(P.pressure), compact(P.porosity), compact(P.wall);
    compact(P.wall_velocity);
    const unsigned int removed = keep.size() - P.size();
    P.n_local                  = P.size(); // one rank: every particle is owned
    setup.n_fluid -= removed;
    setup.n_cut_by_walls += removed;
    return removed;
  }
} // namespace sluice
