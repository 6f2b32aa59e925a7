#include <sluice/dem/neighbour_list.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sluice
{
  void NeighbourList::build(const ParticleStorage &particles, const PeriodicBox &box,
                            const WallSet &walls, const double cutoff_radius,
                            const double skin, const bool keep_history,
                            const ContactHistoryMap &histories)
  {
    const unsigned int n_local = particles.n_local;
    const unsigned int n_all   = particles.size();
    ++n_builds;

    // Cell grid over the box with cells no smaller than the interaction range, so
    // that every partner sits in one of the 27 cells around a particle.
    const double range = 2. * cutoff_radius + skin;
    int          n_cells[3];
    for (unsigned int d = 0; d < 3; ++d)
      n_cells[d] = std::max(1, static_cast<int>(std::floor(box.length[d] / range)));
    const unsigned int total_cells = n_cells[0] * n_cells[1] * n_cells[2];

    auto cell_coordinate = [&](const Vec3 &x, const unsigned int d) {
      const int c = static_cast<int>(std::floor((x[d] - box.lower[d]) / box.length[d] * n_cells[d]));
      return std::min(std::max(c, 0), n_cells[d] - 1);
    };

    // Counting sort of all particles (local and ghost) into cells.
    cell_of.resize(n_all);
    cell_start.assign(total_cells + 1, 0);
    for (unsigned int p = 0; p < n_all; ++p)
      {
        const Vec3 x = box.wrap(particles.position[p]);
        cell_of[p]   = cell_coordinate(x, 0) +
                     n_cells[0] * (cell_coordinate(x, 1) + n_cells[1] * cell_coordinate(x, 2));
        ++cell_start[cell_of[p] + 1];
      }
    for (unsigned int c = 0; c < total_cells; ++c)
      cell_start[c + 1] += cell_start[c];
    cell_particles.resize(n_all);
    {
      std::vector<unsigned int> fill(cell_start.begin(), cell_start.end() - 1);
      for (unsigned int p = 0; p < n_all; ++p)
        cell_particles[fill[cell_of[p]]++] = p;
    }

    offset.assign(n_local + 1, 0);
    partner.clear();
    history.clear();
    wall_offset.assign(n_local + 1, 0);
    wall_partner.clear();
    wall_history.clear();

    std::vector<unsigned int> stencil;
    stencil.reserve(27);
    for (unsigned int i = 0; i < n_local; ++i)
      {
        const unsigned int c  = cell_of[i];
        const int          ci[3] = {static_cast<int>(c % n_cells[0]),
                                    static_cast<int>((c / n_cells[0]) % n_cells[1]),
                                    static_cast<int>(c / (n_cells[0] * n_cells[1]))};
        stencil.clear();
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              {
                int  cc[3] = {ci[0] + dx, ci[1] + dy, ci[2] + dz};
                bool valid = true;
                for (unsigned int d = 0; d < 3; ++d)
                  if (cc[d] < 0 || cc[d] >= n_cells[d])
                    {
                      if (box.periodic[d])
                        cc[d] = (cc[d] + n_cells[d]) % n_cells[d];
                      else
                        valid = false;
                    }
                if (valid)
                  stencil.push_back(cc[0] + n_cells[0] * (cc[1] + n_cells[1] * cc[2]));
              }
        // With fewer than three cells along a periodic direction the stencil wraps
        // onto itself; list each cell once.
        std::sort(stencil.begin(), stencil.end());
        stencil.erase(std::unique(stencil.begin(), stencil.end()), stencil.end());

        const Vec3   xi = particles.position[i];
        const double ri = particles.radius[i];
        for (const unsigned int cell : stencil)
          for (unsigned int k = cell_start[cell]; k < cell_start[cell + 1]; ++k)
            {
              const unsigned int j = cell_particles[k];
              if (j < n_local && j <= i)
                continue; // a local pair is listed from its lower index only
              Vec3 d = xi - particles.position[j];
              if (box.any_periodic)
                d = box.minimum_image(d);
              const double reach = ri + particles.radius[j] + skin;
              if (norm_square(d) < reach * reach)
                partner.push_back(j);
            }
        offset[i + 1] = partner.size();

        for (unsigned int w = 0; w < walls.size(); ++w)
          if (dot(xi - walls[w].point, walls[w].normal) < ri + skin)
            wall_partner.push_back(w);
        wall_offset[i + 1] = wall_partner.size();
      }

    // Tangential histories of contacts that existed before the rebuild.
    if (keep_history)
      {
        history.assign(partner.size(), Vec3());
        wall_history.assign(wall_partner.size(), Vec3());
        if (!histories.empty())
          for (unsigned int i = 0; i < n_local; ++i)
            {
              const std::uint64_t id_i = particles.id[i];
              for (unsigned int k = offset[i]; k < offset[i + 1]; ++k)
                {
                  const std::uint64_t id_j = particles.id[partner[k]];
                  const auto it = histories.find({std::min(id_i, id_j), std::max(id_i, id_j), false});
                  if (it != histories.end())
                    history[k] = id_i < id_j ? it->second : -it->second;
                }
              for (unsigned int k = wall_offset[i]; k < wall_offset[i + 1]; ++k)
                {
                  const auto it = histories.find({id_i, wall_partner[k], true});
                  if (it != histories.end())
                    wall_history[k] = it->second;
                }
            }
      }

    position_at_build.assign(particles.position.begin(), particles.position.begin() + n_local);
  }

  void NeighbourList::collect_histories(const ParticleStorage &particles,
                                        ContactHistoryMap &    histories) const
  {
    if (history.empty() && wall_history.empty())
      return;
    for (unsigned int i = 0; i + 1 < offset.size(); ++i)
      {
        const std::uint64_t id_i = particles.id[i];
        for (unsigned int k = offset[i]; k < offset[i + 1]; ++k)
          if (norm_square(history[k]) > 0.)
            {
              const std::uint64_t id_j = particles.id[partner[k]];
              histories[{std::min(id_i, id_j), std::max(id_i, id_j), false}] =
                id_i < id_j ? history[k] : -history[k];
            }
        for (unsigned int k = wall_offset[i]; k < wall_offset[i + 1]; ++k)
          if (norm_square(wall_history[k]) > 0.)
            histories[{id_i, wall_partner[k], true}] = wall_history[k];
      }
  }

  double NeighbourList::max_displacement_square(const ParticleStorage &particles) const
  {
    double m      = 0.;
    bool   finite = true;
    for (unsigned int i = 0; i < particles.n_local; ++i)
      {
        const double d2 = norm_square(particles.position[i] - position_at_build[i]);
        m               = std::max(m, d2);
        finite &= d2 < std::numeric_limits<double>::max();
      }
    return finite ? m : std::numeric_limits<double>::infinity();
  }
} // namespace sluice
