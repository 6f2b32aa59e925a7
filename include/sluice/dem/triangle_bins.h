#pragma once
// Triangles sorted into a uniform grid of cells, so that a particle finds the
// triangles within its reach by looking at its own cell only: each triangle
// is entered in every cell that its bounding box, grown by the reach, touches.
// Building costs O(T + the cells the boxes cover); a query costs the length
// of one cell's list. With cells about as large as the reach (the DEM's
// neighbour cells), a triangle much larger than a cell enters many cells: the
// price of not testing every triangle against every particle.

#include <sluice/core/vector3.h>
#include <sluice/dem/triangle_mesh.h>

#include <array>
#include <vector>

namespace sluice
{
  class TriangleBins
  {
  public:
    /// A grid of n cells per direction of size 'cell' from 'lower'; points
    /// outside it fall into the nearest boundary cell.
    TriangleBins(const Vec3 &lower, const Vec3 &cell, const std::array<unsigned int, 3> &n);

    /// Sorts the mesh's triangles in (again, after the mesh has moved): every
    /// triangle enters each cell its bounding box grown by 'reach' touches.
    void build(const TriangleMesh &mesh, double reach);

    /// The triangles that may lie within 'reach' (of build()) of x, each once.
    const unsigned int *begin(const Vec3 &x) const { return entries.data() + start[cell_of(x)]; }
    const unsigned int *end(const Vec3 &x) const { return entries.data() + start[cell_of(x) + 1]; }

    std::size_t n_entries() const { return entries.size(); }

  private:
    unsigned int cell_of(const Vec3 &x) const;
    int          index(double x, unsigned int d) const;

    Vec3                        lower, cell;
    std::array<unsigned int, 3> n;
    std::vector<unsigned int>   start, entries; // compressed rows per cell
  };
} // namespace sluice
