#pragma once
// One snapshot of an imported flow field (Gao & Sun 2021 §5.1: a pump's
// slurry flow computed elsewhere drives the particles, one way): the grid of
// a .vtu or .pvtu (vtu_reader.h) with a search tree over its cells' bounding
// boxes, and the fluid velocity, pressure and (optionally) porosity at its
// points. A particle finds its cell by its last cell first, then the tree;
// the fields are interpolated with the cell's shape functions
// (vtk_cell_shapes.h), the velocity and pressure gradients with theirs.
// Cell data are turned into point data by averaging over the cells that share
// a point (ParaView's Cell Data to Point Data). Every rank holds the whole
// field: its memory is the file's, once per rank.

#include <sluice/core/vtu_reader.h>
#include <sluice/coupling/fluid_backend.h>
#include <sluice/coupling/vtk_cell_shapes.h>

#include <memory>
#include <string>
#include <vector>

namespace sluice
{
  /// Which arrays of the file hold what, and in which units.
  struct ImportedFieldArrays
  {
    std::string velocity = "velocity", pressure = "pressure";
    std::string porosity; // empty: the fluid fills the space (eps = 1)
    double      length_scale = 1.;   // file coordinates times this are metres
    double      pressure_scale = 1.; // file pressure times this is Pa (rho for p/rho)
    bool        need_pressure = true;
  };

  /// The grid and its search tree: shared by snapshots on the same grid.
  class FieldGeometry
  {
  public:
    FieldGeometry(std::vector<Vec3> points, std::vector<std::uint64_t> connectivity,
                  std::vector<std::uint64_t> offsets, std::vector<std::uint8_t> types,
                  const std::string &file_name);
    ~FieldGeometry();

    /// The cell holding x: 'hint' first (a particle's last cell, or -1).
    CellPoint locate(const Vec3 &x, long hint) const;
    bool      same_grid(const VtuGrid &grid, double length_scale) const;
    std::size_t n_points() const { return points.size(); }
    std::size_t n_cells() const { return types.size(); }
    Vec3        lower, upper; // the bounding box

    std::vector<Vec3>          points;
    std::vector<std::uint64_t> connectivity, offsets;
    std::vector<std::uint8_t>  types;

  private:
    struct Tree;
    std::unique_ptr<Tree> tree;
    bool in_cell(std::size_t cell, const Vec3 &x, CellPoint &point) const;
  };

  class ImportedField
  {
  public:
    /// Reads the parts of one snapshot (.vtu or .pvtu files, merged); the
    /// geometry of an earlier snapshot is reused when the grid is the same.
    /// Throws InputError naming the file, the array or the cell.
    ImportedField(const std::vector<std::string> &files, const ImportedFieldArrays &arrays,
                  std::shared_ptr<const FieldGeometry> earlier = nullptr);

    const std::shared_ptr<const FieldGeometry> &geometry() const { return grid; }

    /// The fluid at a located point (velocity, its gradient, the pressure
    /// gradient, the porosity).
    void evaluate(const CellPoint &point, ParticleFluidSample &sample) const;

  private:
    std::shared_ptr<const FieldGeometry> grid;
    std::vector<Vec3>                    velocity;
    std::vector<double>                  pressure, porosity;
  };
} // namespace sluice
