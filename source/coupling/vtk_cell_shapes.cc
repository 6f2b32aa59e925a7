// Linear VTK cells (see the header).

#include <sluice/coupling/vtk_cell_shapes.h>

#include <cmath>

namespace sluice
{
  namespace vtk_cell
  {
    namespace
    {
      /// The trilinear hexahedron's nodes in VTK's order, as (r, s, t) corners.
      constexpr int hex_corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
      /// A voxel's node k is the hexahedron's node voxel_as_hex[k].
      constexpr int voxel_as_hex[8] = {0, 1, 3, 2, 4, 5, 7, 6};

      double linear(const int corner, const double x) { return corner ? x : 1. - x; }
      double slope(const int corner) { return corner ? 1. : -1.; }

      void trilinear(const Vec3 &r, const int corner[3], double &N, Vec3 &dN)
      {
        const double a = linear(corner[0], r.x), b = linear(corner[1], r.y),
                     c = linear(corner[2], r.z);
        N  = a * b * c;
        dN = Vec3(slope(corner[0]) * b * c, a * slope(corner[1]) * c, a * b * slope(corner[2]));
      }
    } // namespace

    unsigned int n_nodes(const std::uint8_t type)
    {
      switch (type)
        {
          case 10: return 4;
          case 11: case 12: return 8;
          case 13: return 6;
          case 14: return 5;
          default: return 0;
        }
    }

    void shape(const std::uint8_t type, const Vec3 &r, double *N, Vec3 *dN)
    {
      if (type == 10)
        {
          N[0]  = 1. - r.x - r.y - r.z;
          N[1]  = r.x, N[2] = r.y, N[3] = r.z;
          dN[0] = Vec3(-1., -1., -1.);
          dN[1] = Vec3(1., 0., 0.), dN[2] = Vec3(0., 1., 0.), dN[3] = Vec3(0., 0., 1.);
        }
      else if (type == 11 || type == 12)
        for (unsigned int k = 0; k < 8; ++k)
          trilinear(r, hex_corner[type == 11 ? voxel_as_hex[k] : k], N[k], dN[k]);
      else if (type == 13)
        {
          const double tri[3]     = {1. - r.x - r.y, r.x, r.y};
          const Vec3   d_tri[3]   = {Vec3(-1., -1., 0.), Vec3(1., 0., 0.), Vec3(0., 1., 0.)};
          for (unsigned int k = 0; k < 3; ++k)
            {
              N[k]      = tri[k] * (1. - r.z);
              N[k + 3]  = tri[k] * r.z;
              dN[k]     = (1. - r.z) * d_tri[k] + Vec3(0., 0., -tri[k]);
              dN[k + 3] = r.z * d_tri[k] + Vec3(0., 0., tri[k]);
            }
        }
      else // 14, the pyramid
        {
          for (unsigned int k = 0; k < 4; ++k)
            {
              const int corner[3] = {hex_corner[k][0], hex_corner[k][1], 0};
              trilinear(r, corner, N[k], dN[k]);
            }
          N[4]  = r.z;
          dN[4] = Vec3(0., 0., 1.);
        }
    }

    Vec3 centre(const std::uint8_t type)
    {
      if (type == 10)
        return Vec3(0.25, 0.25, 0.25);
      if (type == 13)
        return Vec3(1. / 3., 1. / 3., 0.5);
      if (type == 14)
        return Vec3(0.5, 0.5, 0.2);
      return Vec3(0.5, 0.5, 0.5);
    }

    bool contains(const std::uint8_t type, const Vec3 &r, const double tolerance)
    {
      const double lo = -tolerance, hi = 1. + tolerance;
      if (r.x < lo || r.y < lo || r.z < lo || r.z > hi)
        return false;
      if (type == 10)
        return r.x + r.y + r.z <= hi;
      if (type == 13)
        return r.x + r.y <= hi;
      return r.x <= hi && r.y <= hi;
    }
  } // namespace vtk_cell

  namespace
  {
    /// Solves J^T y = b for y, with J = [c0 c1 c2] as columns; false when singular.
    bool solve(const Vec3 c[3], const Vec3 &b, Vec3 &y, const bool transposed)
    {
      // Cramer's rule; J's columns are c[k] (or its rows when transposed).
      Vec3 row[3];
      for (unsigned int i = 0; i < 3; ++i)
        row[i] = transposed ? c[i] : Vec3(c[0][i], c[1][i], c[2][i]);
      const double det = dot(row[0], cross(row[1], row[2]));
      if (!(std::abs(det) > 0.))
        return false;
      // y = M^-1 b for the matrix with these rows.
      const Vec3 a = cross(row[1], row[2]), bb = cross(row[2], row[0]), cc = cross(row[0], row[1]);
      y = (1. / det) * Vec3(a.x * b.x + bb.x * b.y + cc.x * b.z, a.y * b.x + bb.y * b.y + cc.y * b.z,
                            a.z * b.x + bb.z * b.y + cc.z * b.z);
      return true;
    }
  } // namespace

  bool locate_in_cell(const std::uint8_t type, const Vec3 *X, const Vec3 &x, CellPoint &point)
  {
    const unsigned int n = vtk_cell::n_nodes(type);
    double             N[vtk_cell::max_nodes];
    Vec3               dN[vtk_cell::max_nodes];
    Vec3               r = vtk_cell::centre(type), J[3];
    bool               converged = false;
    for (unsigned int iteration = 0; iteration < 20 && !converged; ++iteration)
      {
        vtk_cell::shape(type, r, N, dN);
        Vec3 residual = -x;
        J[0] = J[1] = J[2] = Vec3(); // J[k] = dx/dr_k
        for (unsigned int a = 0; a < n; ++a)
          {
            residual += N[a] * X[a];
            for (unsigned int k = 0; k < 3; ++k)
              J[k] += dN[a][k] * X[a];
          }
        Vec3 step;
        if (!solve(J, residual, step, false))
          return false;
        r -= step;
        converged = norm_square(step) < 1e-24;
        // Far outside after a few steps: not this cell.
        if (iteration > 3 && std::abs(r.x) + std::abs(r.y) + std::abs(r.z) > 10.)
          return false;
      }
    if (!vtk_cell::contains(type, r, 1e-9))
      return false;
    vtk_cell::shape(type, r, N, dN);
    J[0] = J[1] = J[2] = Vec3();
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int k = 0; k < 3; ++k)
        J[k] += dN[a][k] * X[a];
    point.n_nodes = n;
    for (unsigned int a = 0; a < n; ++a)
      {
        point.N[a] = N[a];
        // grad_x N = J^-T grad_r N: solve J^T g = dN.
        if (!solve(J, dN[a], point.gradient[a], true))
          return false;
      }
    return true;
  }
} // namespace sluice
