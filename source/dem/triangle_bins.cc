// Triangles in a uniform grid of cells (see the header).

#include <sluice/dem/triangle_bins.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  TriangleBins::TriangleBins(const Vec3 &lower_, const Vec3 &cell_,
                             const std::array<unsigned int, 3> &n_)
    : lower(lower_), cell(cell_), n(n_)
  {}

  int TriangleBins::index(const double x, const unsigned int d) const
  {
    const int i = static_cast<int>(std::floor((x - lower[d]) / cell[d]));
    return std::min(std::max(i, 0), static_cast<int>(n[d]) - 1);
  }

  unsigned int TriangleBins::cell_of(const Vec3 &x) const
  {
    return index(x.x, 0) + n[0] * (index(x.y, 1) + n[1] * index(x.z, 2));
  }

  void TriangleBins::build(const TriangleMesh &mesh, const double reach)
  {
    // Two passes over the boxes: count per cell, then fill (compressed rows).
    const std::size_t n_cells = static_cast<std::size_t>(n[0]) * n[1] * n[2];
    start.assign(n_cells + 1, 0);
    std::vector<std::array<int, 6>> boxes(mesh.size());
    for (unsigned int t = 0; t < mesh.size(); ++t)
      {
        Vec3 lo(1e300, 1e300, 1e300), hi = -lo;
        for (const unsigned int v : mesh.triangles[t])
          for (unsigned int d = 0; d < 3; ++d)
            {
              lo[d] = std::min(lo[d], mesh.vertices[v][d]);
              hi[d] = std::max(hi[d], mesh.vertices[v][d]);
            }
        for (unsigned int d = 0; d < 3; ++d)
          {
            boxes[t][d]     = index(lo[d] - reach, d);
            boxes[t][d + 3] = index(hi[d] + reach, d);
          }
      }
    const auto for_cells = [&](const std::array<int, 6> &b, auto &&f) {
      for (int k = b[2]; k <= b[5]; ++k)
        for (int j = b[1]; j <= b[4]; ++j)
          for (int i = b[0]; i <= b[3]; ++i)
            f(i + n[0] * (j + n[1] * k));
    };
    for (const auto &b : boxes)
      for_cells(b, [&](const unsigned int c) { ++start[c + 1]; });
    for (std::size_t c = 0; c < n_cells; ++c)
      start[c + 1] += start[c];
    entries.resize(start.back());
    std::vector<unsigned int> filled(start.begin(), start.end() - 1);
    for (unsigned int t = 0; t < mesh.size(); ++t)
      for_cells(boxes[t], [&](const unsigned int c) { entries[filled[c]++] = t; });
  }
} // namespace sluice
