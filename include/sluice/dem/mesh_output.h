#pragma once
// A triangle mesh as a VTK unstructured grid (.vtu) that ParaView opens: its
// welded vertices as points, one triangle cell each, and per-triangle fields
// (the area, and what a scene adds: wear depth, impact and shear energy).

#include <sluice/core/series_files.h>
#include <sluice/dem/triangle_mesh.h>

#include <string>
#include <utility>
#include <vector>

namespace sluice
{
  /// A per-triangle field: its name and one value per triangle.
  using TriangleField = std::pair<std::string, std::vector<double>>;

  /// Writes 'path' whole (a temporary file renamed over it), with the cell
  /// fields 'area' and each of 'fields'. Throws OutputError.
  void write_mesh_vtu(const std::string &path, const TriangleMesh &mesh,
                      const std::vector<TriangleField> &fields = {});

  /// A mesh wall's surface as a time series: '<base>_<wall>_NNNNN.vtu' files
  /// listed in '<base>_<wall>.pvd', written by one rank (the mesh is the same
  /// on every rank).
  class MeshSeries
  {
  public:
    MeshSeries(const std::string &directory, const std::string &base_name,
               const std::string &wall_name, bool writes);

    /// Writes the next snapshot at 'time'. Throws OutputError.
    void write(const TriangleMesh &mesh, double time,
               const std::vector<TriangleField> &fields = {});

    /// The series index, for a checkpoint to save and a restart to restore.
    PvdSeries       &index() { return series; }
    const PvdSeries &index() const { return series; }

  private:
    std::string directory, prefix;
    bool        writes;
    PvdSeries   series;
  };
} // namespace sluice
