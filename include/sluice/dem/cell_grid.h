#pragma once
// The cell grid of the neighbour searches: the box cut into cells no smaller
// than the interaction range, the particles (owned and ghost) sorted into
// them by a counting sort in O(N), and each cell's stencil of the 27 cells
// around it, wrapped across periodic faces, so that every partner within
// the range of a particle lies in its cell's stencil. The DEM's contact list
// (neighbour_list.h) and the SPH pair list (sph/sph_pairs.h) both search it.

#include <sluice/core/vector3.h>
#include <sluice/dem/periodic_box.h>

#include <array>
#include <vector>

namespace sluice
{
  class CellGrid
  {
  public:
    /// Sorts positions[0, n) into cells of at least 'range' (at least one
    /// cell per direction).
    void build(const std::vector<Vec3> &positions, unsigned int n, const PeriodicBox &box,
               double range);

    /// The cells around particle p's cell, its own included, each once and in
    /// ascending order (with fewer than three cells along a periodic
    /// direction the stencil wraps onto itself).
    void stencil(unsigned int p, std::vector<unsigned int> &cells) const;

    /// The particles of a cell: cell_particles[cell_start[c] ... cell_start[c+1] - 1].
    std::vector<unsigned int> cell_start, cell_particles;
    std::vector<unsigned int> cell_of; // per particle
    int                       n_cells[3] = {1, 1, 1};

  private:
    std::array<bool, 3> periodic{{false, false, false}};
  };
} // namespace sluice
