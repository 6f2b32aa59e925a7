#include <sluice/dem/neighbour_list.h>
#include <sluice/dem/triangle_bins.h>
#include <sluice/dem/triangle_geometry.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace sluice
{
  namespace
  {
    /// Appends to partner[n ...] the partners of local particle i among the
    /// particles of 'cells', in the cells' order, and returns the new count.
    /// A candidate is listed if it is within reach, is not listed from its own
    /// side (a local pair goes with its lower index) and is not a member of
    /// i's rigid body. About half the candidates fail, a coin toss for a
    /// branch, so there is none per candidate: each is written and the count
    /// advances by the test's result (as the contact pass's touching test,
    /// contact_forces.cc). The list is the one a branch would give.
    template <bool periodic, bool bodies>
    unsigned int append_partners(const ParticleStorage &particles, const unsigned int i,
                                 const CellGrid &grid, const std::vector<unsigned int> &cells,
                                 const PeriodicBox &box, const double skin,
                                 const unsigned int member_stride,
                                 std::vector<unsigned int> &partner, unsigned int n)
    {
      unsigned int candidates = 0;
      for (const unsigned int cell : cells)
        candidates += grid.cell_start[cell + 1] - grid.cell_start[cell];
      if (partner.size() < n + candidates)
        partner.resize(std::max<std::size_t>(2 * partner.size(), n + candidates));

      const Vec3 *const         x       = particles.position.data();
      const double *const       r       = particles.radius.data();
      const unsigned int *const members = grid.cell_particles.data();
      unsigned int *const       out     = partner.data();
      const unsigned int        n_local = particles.n_local;
      const Vec3                xi      = x[i];
      const double              ri      = r[i];
      for (const unsigned int cell : cells)
        for (unsigned int k = grid.cell_start[cell]; k < grid.cell_start[cell + 1]; ++k)
          {
            const unsigned int j = members[k];
            Vec3               d = xi - x[j];
            if constexpr (periodic)
              d = box.minimum_image(d);
            const double reach = ri + r[j] + skin;
            bool         keep  = (j >= n_local) | (j > i);
            if constexpr (bodies)
              keep = keep & (particles.id[i] / member_stride != particles.id[j] / member_stride);
            keep   = keep & (norm_square(d) < reach * reach);
            out[n] = j;
            n += keep;
          }
      return n;
    }
  } // namespace

  void NeighbourList::build(const ParticleStorage &particles, const PeriodicBox &box,
                            const WallSet &walls, const double cutoff_radius,
                            const double skin, const bool keep_history,
                            const ContactHistoryMap &histories)
  {
    const unsigned int n_local = particles.n_local;
    const unsigned int n_all   = particles.size();
    ++n_builds;

    // Cells no smaller than the interaction range: every partner sits in one
    // of the 27 cells around a particle.
    grid.build(particles.position, n_all, box, 2. * cutoff_radius + skin);

    offset.assign(n_local + 1, 0);
    partner.clear();
    history.clear();
    history_may_be_nonzero.clear();
    wall_offset.assign(n_local + 1, 0);
    wall_partner.clear();
    wall_history.clear();

    const auto append = box.any_periodic ?
                          (member_stride > 0 ? &append_partners<true, true> :
                                               &append_partners<true, false>) :
                          (member_stride > 0 ? &append_partners<false, true> :
                                               &append_partners<false, false>);
    std::vector<unsigned int> stencil;
    stencil.reserve(27);
    unsigned int n_listed = 0;
    for (unsigned int i = 0; i < n_local; ++i)
      {
        // (Neighbours in storage often share a cell, and with it the stencil.)
        if (i == 0 || grid.cell_of[i] != grid.cell_of[i - 1])
          grid.stencil(i, stencil);
        n_listed = append(particles, i, grid, stencil, box, skin, member_stride, partner,
                          n_listed);
        offset[i + 1] = n_listed;

        const Vec3   xi = particles.position[i];
        const double ri = particles.radius[i];
        for (unsigned int w = 0; w < walls.n_planes(); ++w)
          if (dot(xi - walls[w].point, walls[w].normal) < ri + skin)
            wall_partner.push_back(w);
        wall_offset[i + 1] = wall_partner.size();
      }
    partner.resize(n_listed);

    // Tangential histories of contacts that existed before the rebuild. A
    // step builds its list at the positions of its contact pass, which zeroes
    // the history of every pair that does not touch there (contact_forces.cc,
    // with this same test), so only the touching pairs are looked up. (A
    // restart builds at the checkpoint's positions, where the pairs that did
    // not touch had no history to save.)
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
                  const unsigned int j = partner[k];
                  Vec3               d = particles.position[i] - particles.position[j];
                  if (box.any_periodic)
                    d = box.minimum_image(d);
                  const double r_sum = particles.radius[i] + particles.radius[j];
                  if (norm_square(d) >= r_sum * r_sum)
                    continue;
                  const std::uint64_t id_j = particles.id[j];
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

    mesh_offset.assign(n_local + 1, 0);
    mesh_candidate.clear();
    mesh_contact_offset.assign(n_local + 1, 0);
    mesh_contact.clear();
    n_planes = walls.n_planes();
    triangle_offset.clear();
    for (unsigned int m = 0; m < walls.n_meshes(); ++m)
      triangle_offset.push_back(walls.triangle_offset(m));
    if (walls.n_meshes() > 0)
      {
        build_mesh_candidates(particles, box, walls, grid.n_cells, cutoff_radius, skin);
        if (keep_history)
          restore_mesh_histories(particles, walls, histories);
      }

    position_at_build.assign(particles.position.begin(), particles.position.begin() + n_local);
  }

  void NeighbourList::build_mesh_candidates(const ParticleStorage &particles,
                                            const PeriodicBox &box, const WallSet &walls,
                                            const int n_cells[3], const double cutoff_radius,
                                            const double skin)
  {
    // The triangles are binned on the particles' cell grid (O(T) plus the
    // cells their boxes cover); each particle looks at its own cell's list and
    // keeps the triangles truly within its reach.
    const std::array<unsigned int, 3> n{{static_cast<unsigned int>(n_cells[0]),
                                         static_cast<unsigned int>(n_cells[1]),
                                         static_cast<unsigned int>(n_cells[2])}};
    const Vec3 cell(box.length.x / n[0], box.length.y / n[1], box.length.z / n[2]);
    std::vector<TriangleBins> bins;
    for (const MeshWall &wall : walls.meshes())
      {
        bins.emplace_back(box.lower, cell, n);
        bins.back().build(wall.mesh(), cutoff_radius + skin);
      }
    for (unsigned int i = 0; i < particles.n_local; ++i)
      {
        const Vec3   x     = particles.position[i];
        const double reach = particles.radius[i] + skin;
        for (unsigned int m = 0; m < walls.n_meshes(); ++m)
          {
            const TriangleMesh &mesh = walls.meshes()[m].mesh();
            for (const unsigned int *t = bins[m].begin(x); t != bins[m].end(x); ++t)
              {
                const auto &v = mesh.triangles[*t];
                const Vec3  c = closest_point_on_triangle(x, mesh.vertices[v[0]],
                                                          mesh.vertices[v[1]],
                                                          mesh.vertices[v[2]])
                                 .point;
                if (norm_square(x - c) < reach * reach)
                  mesh_candidate.push_back({m, *t});
              }
          }
        mesh_offset[i + 1] = mesh_candidate.size();
      }
  }

  void NeighbourList::restore_mesh_histories(const ParticleStorage &particles,
                                             const WallSet &walls,
                                             const ContactHistoryMap &histories)
  {
    std::unordered_map<std::uint64_t, unsigned int> local_index;
    for (unsigned int i = 0; i < particles.n_local; ++i)
      local_index[particles.id[i]] = i;
    std::vector<std::vector<MeshContactHistory>> of_particle(particles.n_local);
    for (const auto &[key, h] : histories)
      if (key.wall && key.second >= n_planes)
        {
          const auto it = local_index.find(key.first);
          if (it == local_index.end())
            continue;
          const unsigned int number = key.second - n_planes;
          // The mesh whose numbers hold it: the last offset not above it.
          const unsigned int m =
            std::upper_bound(triangle_offset.begin(), triangle_offset.end(), number) -
            triangle_offset.begin() - 1;
          if (number - triangle_offset[m] < walls.meshes()[m].mesh().size())
            of_particle[it->second].push_back({{m, number - triangle_offset[m]}, h});
        }
    // In triangle order, whatever the map's: the same on any number of ranks.
    for (unsigned int i = 0; i < particles.n_local; ++i)
      {
        auto &rows = of_particle[i];
        std::sort(rows.begin(), rows.end(), [](const auto &a, const auto &b) {
          return a.triangle.mesh < b.triangle.mesh ||
                 (a.triangle.mesh == b.triangle.mesh && a.triangle.triangle < b.triangle.triangle);
        });
        mesh_contact.insert(mesh_contact.end(), rows.begin(), rows.end());
        mesh_contact_offset[i + 1] = mesh_contact.size();
      }
  }

  void NeighbourList::collect_histories(const ParticleStorage &particles,
                                        ContactHistoryMap &    histories) const
  {
    for (unsigned int i = 0; i + 1 < mesh_contact_offset.size(); ++i)
      for (unsigned int k = mesh_contact_offset[i]; k < mesh_contact_offset[i + 1]; ++k)
        if (norm_square(mesh_contact[k].history) > 0.)
          {
            const MeshTriangle &t = mesh_contact[k].triangle;
            histories[{particles.id[i], n_planes + triangle_offset[t.mesh] + t.triangle, true}] =
              mesh_contact[k].history;
          }
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
