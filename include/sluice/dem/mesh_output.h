#pragma once
// A triangle mesh as a VTK unstructured grid (.vtu) that ParaView opens: its
// welded vertices as points, one triangle cell each, and per-triangle fields
// (the area, and what a scene adds: wear depth, impact and shear energy).

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
} // namespace sluice
