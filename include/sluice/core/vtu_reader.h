#pragma once
// Unstructured grids from VTK XML files, as ParaView writes them from
// OpenFOAM, Fluent or deal.II output (Sluice's own fluid snapshots included):
// a .vtu, a .pvtu (its pieces merged into one grid), or a .pvd time series of
// either (vtk_xml.h reads the encodings). Errors throw InputError naming the
// file and what is wrong.

#include <sluice/core/vector3.h>

#include <cstdint>
#include <string>
#include <vector>

namespace sluice
{
  /// One named point- or cell-data array: components values per point (cell).
  struct VtuArray
  {
    std::string         name;
    unsigned int        components = 1;
    std::vector<double> values;
  };

  /// A grid: points, cells as VTK writes them (connectivity, offsets past each
  /// cell's last point, VTK cell types), and its data arrays.
  struct VtuGrid
  {
    std::vector<Vec3>          points;
    std::vector<std::uint64_t> connectivity, offsets;
    std::vector<std::uint8_t>  types;
    std::vector<VtuArray>      point_data, cell_data;

    std::size_t n_cells() const { return types.size(); }
    /// The point- (or else cell-) data array of this name, or null.
    const VtuArray *find(const std::string &name, bool &on_points) const;
  };

  /// A .vtu or .pvtu file.
  VtuGrid read_unstructured_grid(const std::string &file_name);

  /// One snapshot of a .pvd: its time and files (several parts, merged).
  struct PvdSnapshot
  {
    double                   time = 0.;
    std::vector<std::string> files;
  };

  /// The snapshots of a .pvd in increasing time (file names resolved against
  /// its directory); throws InputError when times repeat or the list is empty.
  std::vector<PvdSnapshot> read_pvd(const std::string &file_name);

  /// Merges one more grid's cells, points and arrays into 'grid' (the arrays
  /// must match by name and components).
  void append_grid(VtuGrid &grid, const VtuGrid &piece, const std::string &piece_name);
} // namespace sluice
