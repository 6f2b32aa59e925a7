#pragma once
// The linear VTK cells an imported flow field may come on, with their shape
// functions in VTK's own parametric coordinates (VTK User's Guide, "Cell
// types"; the node orders are VTK's):
//   tetra (10)       N = 1 - r - s - t, r, s, t
//   voxel (11)       trilinear, nodes in lexicographic order
//   hexahedron (12)  trilinear, nodes 0-3 counter-clockwise at t = 0, 4-7 at t = 1
//   wedge (13)       the triangle's (1 - r - s, r, s) times (1 - t, t)
//   pyramid (14)     bilinear on the base times (1 - t), and t at the apex
// The point of a cell holding x is found by Newton's method on x(r) = x
// (exact in one step for a tetrahedron), and the gradient of a nodal field is
// sum_a f_a J^-T grad_r N_a.

#include <sluice/core/vector3.h>

#include <array>
#include <cstdint>

namespace sluice
{
  namespace vtk_cell
  {
    constexpr unsigned int max_nodes = 8;

    /// The number of nodes of a supported VTK cell type, or 0.
    unsigned int n_nodes(std::uint8_t type);

    /// Shape functions and their parametric derivatives at r.
    void shape(std::uint8_t type, const Vec3 &r, double *N, Vec3 *dN);

    /// The parametric centre (Newton's start).
    Vec3 centre(std::uint8_t type);

    /// Whether r lies in the reference cell, to 'tolerance'.
    bool contains(std::uint8_t type, const Vec3 &r, double tolerance);
  } // namespace vtk_cell

  /// Where a point lies in one cell, and what a nodal field needs there: the
  /// shape functions and their physical gradients.
  struct CellPoint
  {
    long                                          cell = -1; // -1: in no cell
    unsigned int                                  n_nodes = 0;
    std::array<std::uint64_t, vtk_cell::max_nodes> nodes{};
    std::array<double, vtk_cell::max_nodes>       N{};
    std::array<Vec3, vtk_cell::max_nodes>         gradient{};
  };

  /// Finds r with x(r) = x in the cell of these node positions and fills the
  /// weights; false when x lies outside the cell (or the map is singular).
  bool locate_in_cell(std::uint8_t type, const Vec3 *node_positions, const Vec3 &x,
                      CellPoint &point);
} // namespace sluice
