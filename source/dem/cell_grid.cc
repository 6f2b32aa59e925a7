// The cell grid of the neighbour searches (see the header).

#include <sluice/dem/cell_grid.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  void CellGrid::build(const std::vector<Vec3> &positions, const unsigned int n,
                       const PeriodicBox &box, const double range)
  {
    periodic = box.periodic;
    for (unsigned int d = 0; d < 3; ++d)
      n_cells[d] = std::max(1, static_cast<int>(std::floor(box.length[d] / range)));
    const unsigned int total_cells = n_cells[0] * n_cells[1] * n_cells[2];

    auto cell_coordinate = [&](const Vec3 &x, const unsigned int d) {
      const int c = static_cast<int>(std::floor((x[d] - box.lower[d]) / box.length[d] * n_cells[d]));
      return std::min(std::max(c, 0), n_cells[d] - 1);
    };

    // Counting sort of all particles (local and ghost) into cells.
    cell_of.resize(n);
    cell_start.assign(total_cells + 1, 0);
    for (unsigned int p = 0; p < n; ++p)
      {
        const Vec3 x = box.wrap(positions[p]);
        cell_of[p]   = cell_coordinate(x, 0) +
                     n_cells[0] * (cell_coordinate(x, 1) + n_cells[1] * cell_coordinate(x, 2));
        ++cell_start[cell_of[p] + 1];
      }
    for (unsigned int c = 0; c < total_cells; ++c)
      cell_start[c + 1] += cell_start[c];
    cell_particles.resize(n);
    std::vector<unsigned int> fill(cell_start.begin(), cell_start.end() - 1);
    for (unsigned int p = 0; p < n; ++p)
      cell_particles[fill[cell_of[p]]++] = p;
  }

  void CellGrid::stencil(const unsigned int p, std::vector<unsigned int> &cells) const
  {
    const unsigned int c     = cell_of[p];
    const int          ci[3] = {static_cast<int>(c % n_cells[0]),
                                static_cast<int>((c / n_cells[0]) % n_cells[1]),
                                static_cast<int>(c / (n_cells[0] * n_cells[1]))};
    cells.clear();
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          {
            int  cc[3] = {ci[0] + dx, ci[1] + dy, ci[2] + dz};
            bool valid = true;
            for (unsigned int d = 0; d < 3; ++d)
              if (cc[d] < 0 || cc[d] >= n_cells[d])
                {
                  if (periodic[d])
                    cc[d] = (cc[d] + n_cells[d]) % n_cells[d];
                  else
                    valid = false;
                }
            if (valid)
              cells.push_back(cc[0] + n_cells[0] * (cc[1] + n_cells[1] * cc[2]));
          }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  }
} // namespace sluice
