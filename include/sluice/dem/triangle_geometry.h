#pragma once
// The point of a triangle closest to a point, and which part of the triangle
// it lies on: the face, one of the three edges, or one of the three vertices
// (the Voronoi regions of Ericson, Real-Time Collision Detection, 2005,
// Sec. 5.1.5). A sphere's contact with a triangle mesh is decided on these
// regions: a contact on an edge or a vertex is shared with the neighbouring
// triangles and must be counted once (doc/geometry.md).

#include <sluice/core/vector3.h>

namespace sluice
{
  enum class TriangleRegion
  {
    face,
    edge_ab,
    edge_bc,
    edge_ca,
    vertex_a,
    vertex_b,
    vertex_c
  };

  struct ClosestPoint
  {
    Vec3           point;
    TriangleRegion region;
  };

  /// The point of triangle (a, b, c) closest to p, by Ericson's region tests
  /// (barycentric coordinates from dot products, no square root).
  inline ClosestPoint closest_point_on_triangle(const Vec3 &p, const Vec3 &a, const Vec3 &b,
                                                const Vec3 &c)
  {
    const Vec3   ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0. && d2 <= 0.)
      return {a, TriangleRegion::vertex_a};
    const Vec3   bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0. && d4 <= d3)
      return {b, TriangleRegion::vertex_b};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0. && d1 >= 0. && d3 <= 0.)
      return {a + (d1 / (d1 - d3)) * ab, TriangleRegion::edge_ab};
    const Vec3   cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0. && d5 <= d6)
      return {c, TriangleRegion::vertex_c};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0. && d2 >= 0. && d6 <= 0.)
      return {a + (d2 / (d2 - d6)) * ac, TriangleRegion::edge_ca};
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0. && d4 - d3 >= 0. && d5 - d6 >= 0.)
      return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), TriangleRegion::edge_bc};
    const double denominator = 1. / (va + vb + vc);
    return {a + (vb * denominator) * ab + (vc * denominator) * ac, TriangleRegion::face};
  }
} // namespace sluice
