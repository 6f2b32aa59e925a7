// The SPH fluid on several MPI ranks (see the header).

#include <sluice/core/binary_io.h>
#include <sluice/dem/ghost_layer.h>
#include <sluice/sph/sph_exchange.h>

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    // A particle's record: id, position, velocity, acceleration, mass,
    // density, its rate, h, Omega, pressure, porosity, the wall flag and the
    // wall's velocity.
    constexpr unsigned int record_size = 21;

    void pack(const SphParticles &P, const unsigned int a, double *r)
    {
      r[0] = P.id[a];
      for (unsigned int d = 0; d < 3; ++d)
        {
          r[1 + d]  = P.position[a][d];
          r[4 + d]  = P.velocity[a][d];
          r[7 + d]  = P.acceleration[a][d];
          r[18 + d] = P.wall_velocity[a][d];
        }
      r[10] = P.mass[a];
      r[11] = P.density[a];
      r[12] = P.density_rate[a];
      r[13] = P.smoothing[a];
      r[14] = P.omega[a];
      r[15] = P.pressure[a];
      r[16] = P.porosity[a];
      r[17] = P.wall[a];
    }

    void append(SphParticles &P, const double *r)
    {
      P.id.push_back(static_cast<std::uint64_t>(r[0]));
      P.position.emplace_back(r[1], r[2], r[3]);
      P.velocity.emplace_back(r[4], r[5], r[6]);
      P.acceleration.emplace_back(r[7], r[8], r[9]);
      P.mass.push_back(r[10]);
      P.density.push_back(r[11]);
      P.density_rate.push_back(r[12]);
      P.smoothing.push_back(r[13]);
      P.omega.push_back(r[14]);
      P.pressure.push_back(r[15]);
      P.porosity.push_back(r[16]);
      P.wall.push_back(r[17] != 0.);
      P.wall_velocity.emplace_back(r[18], r[19], r[20]);
    }

    /// The first n entries of every array.
    void truncate(SphParticles &P, const unsigned int n)
    {
      P.id.resize(n);
      for (auto *v : {&P.position, &P.velocity, &P.acceleration, &P.wall_velocity})
        v->resize(n);
      for (auto *v : {&P.mass, &P.density, &P.density_rate, &P.smoothing, &P.omega, &P.pressure,
                      &P.porosity})
        v->resize(n);
      P.wall.resize(n);
    }

    void read(const double *x, Vec3 &v)
    {
      v = Vec3(x[0], x[1], x[2]);
    }
    void read(const double *x, double &v)
    {
      v = x[0];
    }

    /// An attached array after a move: its entries of the 'staying'
    /// particles, then those read at 'offset' in each arrived record.
    template <typename T>
    void move_attached(std::vector<T> &values, const std::vector<unsigned int> &staying,
                       const std::vector<double> &arrived, const unsigned int record,
                       const unsigned int offset)
    {
      std::vector<T> moved;
      for (const unsigned int a : staying)
        moved.push_back(values[a]);
      for (std::size_t k = 0; k < arrived.size(); k += record)
        read(arrived.data() + k + offset, moved.emplace_back());
      values = std::move(moved);
    }

  } // namespace

  struct SphExchange::Implementation
  {
    MPI_Comm    communicator;
    int         rank = 0, n_ranks = 1;
    PeriodicBox box;
    // The cells: how many along each axis, their size, and by lexicographic
    // index the rank that owns each (only on several ranks).
    std::array<int, 3>          n_cells{{1, 1, 1}};
    Vec3                        cell_size;
    std::vector<int>            owner;
    std::unique_ptr<GhostLayer> ghosts;
    // The balance's counters (a checkpoint's).
    unsigned int builds_since_repartition = 0, n_repartitions = 0;

    Implementation(MPI_Comm comm, const PeriodicBox &box)
      : communicator(comm), box(box)
    {
      int initialized = 0;
      MPI_Initialized(&initialized);
      if (!initialized)
        return;
      MPI_Comm_rank(comm, &rank);
      MPI_Comm_size(comm, &n_ranks);
    }

    unsigned int cell_of(const Vec3 &x) const
    {
      int c[3];
      for (unsigned int d = 0; d < 3; ++d)
        c[d] = std::min(
          std::max(static_cast<int>(std::floor((x[d] - box.lower[d]) / cell_size[d])), 0),
          n_cells[d] - 1);
      return c[0] + n_cells[0] * (c[1] + n_cells[1] * c[2]);
    }

    /// Cuts the box into cells at least 'reach' wide (fewer, wider ones
    /// where the box is narrower), owned by nobody yet.
    void cut(const double reach)
    {
      for (unsigned int d = 0; d < 3; ++d)
        {
          // Cells at least 'reach' wide. Two cells along a periodic
          // direction are each other's neighbour on both sides; the ghost
          // layer sends a particle to a rank once, and the pairs take the
          // nearest image, which is the only one within reach as the box is
          // at least twice as long.
          n_cells[d]   = std::max(1, static_cast<int>(std::floor(box.length[d] / reach)));
          cell_size[d] = box.length[d] / n_cells[d];
        }
      owner.assign(n_cells[0] * n_cells[1] * n_cells[2], -1);
    }

    /// Each cell's load, the same on every rank: the 'cost' of each owned
    /// particle, or without one, 4 for a fluid particle and 1 for a wall
    /// particle (it has no pairs with other wall particles: sph_pairs.h).
    /// 'everywhere': every rank holds all of 'P' (the start); otherwise each
    /// its owned particles, summed over the ranks.
    std::vector<unsigned int> loads_of_cells(const SphParticles &P, const bool everywhere,
                                             const std::vector<unsigned int> &cost = {}) const
    {
      std::vector<unsigned int> load(owner.size(), 0);
      for (unsigned int a = 0; a < P.n_local; ++a)
        load[cell_of(P.position[a])] += cost.empty() ? (P.wall[a] ? 1 : 4) : cost[a];
      if (!everywhere)
        Utilities::MPI::sum(ArrayView<const unsigned int>(load), communicator,
                            ArrayView<unsigned int>(load));
      return load;
    }

    /// The busiest rank's load over the mean, for the cells' 'load' owned
    /// as 'owners' says.
    double busiest_over_mean(const std::vector<unsigned int> &load,
                             const std::vector<int>          &owners) const
    {
      std::vector<double> of_rank(n_ranks, 0.);
      for (unsigned int c = 0; c < load.size(); ++c)
        of_rank[owners[c]] += load[c];
      const double total = std::accumulate(of_rank.begin(), of_rank.end(), 0.);
      return total > 0. ? *std::max_element(of_rank.begin(), of_rank.end()) * n_ranks / total :
                          1.;
    }

    /// Collective. The owners p4est gives the cells when it shares them out
    /// among the ranks by their loads; a cell without any weighs 1. On the
    /// dam break weighing a wall particle a quarter cut the 2-rank loop from
    /// 13.05 to 12.71 s (one run each; counting both alike).
    std::vector<int> shared_out(const std::vector<unsigned int> &load) const
    {
      parallel::distributed::Triangulation<3> triangulation(communicator);
      GridGenerator::subdivided_hyper_rectangle(
        triangulation,
        {static_cast<unsigned int>(n_cells[0]), static_cast<unsigned int>(n_cells[1]),
         static_cast<unsigned int>(n_cells[2])},
        Point<3>(box.lower.x, box.lower.y, box.lower.z),
        Point<3>(box.upper.x, box.upper.y, box.upper.z), /*colorize=*/true);
      std::vector<GridTools::PeriodicFacePair<Triangulation<3>::cell_iterator>> periodic_faces;
      for (unsigned int d = 0; d < 3; ++d)
        if (box.periodic[d])
          GridTools::collect_periodic_faces(triangulation, 2 * d, 2 * d + 1, d, periodic_faces);
      if (!periodic_faces.empty())
        triangulation.add_periodicity(periodic_faces);
      const auto lex_of = [this](const Triangulation<3>::cell_iterator &cell) {
        const Point<3> c = cell->center();
        return cell_of(Vec3(c[0], c[1], c[2]));
      };
      auto connection = triangulation.signals.weight.connect(
        [&](const Triangulation<3>::cell_iterator &cell,
            const Triangulation<3>::CellStatus) -> unsigned int {
          return cell->is_active() ? 1 + 25 * load[lex_of(cell)] : 0;
        });
      triangulation.repartition();
      connection.disconnect();

      std::vector<int> owners(load.size(), -1);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          owners[lex_of(cell)] = rank;
      Utilities::MPI::max(ArrayView<const int>(owners), communicator, ArrayView<int>(owners));
      return owners;
    }

    /// The cells' owners from now on, and the ghost layer that follows them.
    void adopt(std::vector<int> owners)
    {
      owner  = std::move(owners);
      ghosts = std::make_unique<GhostLayer>(communicator, n_cells, box.periodic);
      ghosts->set_owners(owner);
    }

    /// Collective. Appends to the owned particles of 'P' a copy of every
    /// particle that another rank owns in a cell next to this rank's.
    void append_ghosts(SphParticles &P) const
    {
      std::vector<GhostLayer::Send> sends;
      for (unsigned int a = 0; a < P.n_local; ++a)
        for (const int r : ghosts->partners_of(cell_of(P.position[a])))
          sends.push_back({a, r});
      const std::vector<double> records = ghosts->exchange(
        sends, record_size, [&](const unsigned int a, double *r) { pack(P, a, r); });
      for (std::size_t k = 0; k < records.size(); k += record_size)
        append(P, records.data() + k);
    }
  };

  SphExchange::SphExchange(MPI_Comm communicator, const PeriodicBox &box, const double reach,
                           const SphParticles &all)
    : impl(std::make_unique<Implementation>(communicator, box))
  {
    impl->cut(reach);
    if (impl->n_ranks > 1)
      impl->adopt(impl->shared_out(impl->loads_of_cells(all, /*everywhere=*/true)));
  }

  SphExchange::~SphExchange() = default;

  bool SphExchange::active() const
  {
    return impl->n_ranks > 1;
  }

  double SphExchange::reach() const
  {
    // Along an axis of one cell every pair lies within it.
    double reach = std::numeric_limits<double>::max();
    for (unsigned int d = 0; d < 3; ++d)
      if (impl->n_cells[d] > 1)
        reach = std::min(reach, impl->cell_size[d]);
    return reach;
  }

  bool SphExchange::fit(const SphParticles &P, const double needed_reach,
                        const std::vector<unsigned int> &cost)
  {
    Implementation &I = *impl;
    if (!active())
      return false;
    ++I.builds_since_repartition;
    if (needed_reach > reach())
      {
        // A smoothing length has grown past what the ghosts hold (the fluid
        // expanded): wider cells, with the start's headroom.
        I.cut(1.25 * needed_reach);
        I.adopt(I.shared_out(I.loads_of_cells(P, /*everywhere=*/false, cost)));
      }
    else
      {
        // The fluid flows away from where the cells were first shared out:
        // as the DEM's particles (particle_exchange.cc), when the busiest
        // rank carries 15% more than the mean, not within 20 rebuilds of the
        // last time, and only if sharing out again takes a tenth off it.
        if (I.builds_since_repartition < 20)
          return false;
        const std::vector<unsigned int> load = I.loads_of_cells(P, /*everywhere=*/false, cost);
        const double                    busiest = I.busiest_over_mean(load, I.owner);
        if (busiest <= 1.15)
          return false;
        std::vector<int> owners = I.shared_out(load);
        if (I.busiest_over_mean(load, owners) > 0.9 * busiest)
          {
            I.builds_since_repartition = 0;
            return false;
          }
        I.adopt(std::move(owners));
      }
    ++I.n_repartitions;
    I.builds_since_repartition = 0;
    return true;
  }

  unsigned int SphExchange::n_repartitions() const
  {
    return impl->n_repartitions;
  }

  std::vector<std::int64_t> SphExchange::cells() const
  {
    const Implementation &I = *impl;
    if (!active())
      return {};
    std::vector<std::int64_t> record = {I.n_ranks,    I.n_cells[0],
                                        I.n_cells[1], I.n_cells[2],
                                        I.builds_since_repartition, I.n_repartitions};
    record.insert(record.end(), I.owner.begin(), I.owner.end());
    return record;
  }

  void SphExchange::restore_cells(const std::vector<std::int64_t> &record, const SphParticles &all)
  {
    Implementation &I = *impl;
    if (!active() || record.empty())
      return;
    if (record.size() < 6 || std::min({record[1], record[2], record[3]}) < 1)
      throw BinaryFormatError("the SPH fluid's cells do not fit together");
    for (unsigned int d = 0; d < 3; ++d)
      {
        I.n_cells[d]   = static_cast<int>(record[1 + d]);
        I.cell_size[d] = I.box.length[d] / I.n_cells[d];
      }
    I.builds_since_repartition = record[4];
    I.n_repartitions           = record[5];
    std::vector<int> owners(record.begin() + 6, record.end());
    bool             fits =
      owners.size() == static_cast<std::size_t>(I.n_cells[0]) * I.n_cells[1] * I.n_cells[2];
    for (const int r : owners)
      fits = fits && r >= 0 && r < record[0];
    if (!fits)
      throw BinaryFormatError("the SPH fluid's cells do not fit together");
    I.owner.assign(owners.size(), -1); // the cells' count, for their loads
    // Written on another number of ranks: the same cells, shared out anew.
    I.adopt(record[0] == I.n_ranks ? std::move(owners) :
                                     I.shared_out(I.loads_of_cells(all, /*everywhere=*/true)));
  }

  void SphExchange::keep_own(SphParticles &P) const
  {
    if (!active())
      return;
    SphParticles        Q;
    std::vector<double> record(record_size);
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (impl->owner[impl->cell_of(P.position[a])] == impl->rank)
        {
          pack(P, a, record.data());
          append(Q, record.data());
        }
    Q.n_local = Q.size();
    P         = std::move(Q);
  }

  void SphExchange::redistribute(SphParticles &P, const Attachments &attached)
  {
    Implementation &I = *impl;
    if (!active())
      return;
    const unsigned int n_vectors = attached.vectors.size(), n_scalars = attached.scalars.size();
    const unsigned int size      = record_size + 3 * n_vectors + n_scalars;
    // The owned particles that stay, and the records of those that leave.
    truncate(P, P.n_local);
    std::map<unsigned int, std::vector<double>> leaving;
    std::vector<unsigned int>        staying;
    std::vector<double>              record(size);
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        const int to = I.owner[I.cell_of(P.position[a])];
        if (to == I.rank)
          {
            staying.push_back(a);
            continue;
          }
        pack(P, a, record.data());
        for (unsigned int v = 0; v < n_vectors; ++v)
          for (unsigned int d = 0; d < 3; ++d)
            record[record_size + 3 * v + d] = (*attached.vectors[v])[a][d];
        for (unsigned int s = 0; s < n_scalars; ++s)
          record[record_size + 3 * n_vectors + s] = (*attached.scalars[s])[a];
        leaving[to].insert(leaving[to].end(), record.begin(), record.end());
      }
    // deal.II's exchange returns the records by sending rank.
    std::vector<double> arrived;
    for (const auto &[rank, records] : Utilities::MPI::some_to_some(I.communicator, leaving))
      arrived.insert(arrived.end(), records.begin(), records.end());

    // The staying particles in their order, then the arrivals by rank.
    SphParticles Q;
    for (const unsigned int a : staying)
      {
        pack(P, a, record.data());
        append(Q, record.data());
      }
    for (std::size_t k = 0; k < arrived.size(); k += size)
      append(Q, arrived.data() + k);
    for (unsigned int v = 0; v < n_vectors; ++v)
      move_attached(*attached.vectors[v], staying, arrived, size, record_size + 3 * v);
    for (unsigned int s = 0; s < n_scalars; ++s)
      move_attached(*attached.scalars[s], staying, arrived, size,
                    record_size + 3 * n_vectors + s);
    Q.n_local = Q.size();
    I.append_ghosts(Q);
    P = std::move(Q);
  }

  void SphExchange::refresh_motion(SphParticles &P)
  {
    if (!active())
      return;
    const unsigned int n = P.n_local;
    impl->ghosts->refresh(
      8,
      [&](const unsigned int a, double *v) {
        for (unsigned int d = 0; d < 3; ++d)
          v[d] = P.position[a][d], v[3 + d] = P.velocity[a][d];
        v[6] = P.density[a];
        v[7] = P.porosity[a];
      },
      [&](const unsigned int k, const double *v) {
        P.position[n + k] = Vec3(v[0], v[1], v[2]);
        P.velocity[n + k] = Vec3(v[3], v[4], v[5]);
        P.density[n + k]  = v[6];
        P.porosity[n + k] = v[7];
      });
  }

  void SphExchange::refresh_density(SphParticles &P)
  {
    if (!active())
      return;
    const unsigned int n = P.n_local;
    impl->ghosts->refresh(
      1, [&](const unsigned int a, double *v) { v[0] = P.density[a]; },
      [&](const unsigned int k, const double *v) { P.density[n + k] = v[0]; });
  }

  void SphExchange::refresh_fluid_fractions(SphParticles &P)
  {
    if (!active())
      return;
    const unsigned int n = P.n_local;
    impl->ghosts->refresh(
      3,
      [&](const unsigned int a, double *v) {
        v[0] = P.mass[a], v[1] = P.density[a], v[2] = P.porosity[a];
      },
      [&](const unsigned int k, const double *v) {
        P.mass[n + k] = v[0], P.density[n + k] = v[1], P.porosity[n + k] = v[2];
      });
  }

  void SphExchange::refresh_rates_inputs(SphParticles &P, std::vector<Vec3> &no_slip)
  {
    if (!active())
      return;
    const unsigned int n = P.n_local;
    impl->ghosts->refresh(
      6,
      [&](const unsigned int a, double *v) {
        v[0] = P.omega[a];
        v[1] = P.pressure[a];
        v[2] = P.density[a];
        for (unsigned int d = 0; d < 3; ++d)
          v[3 + d] = no_slip[a][d];
      },
      [&](const unsigned int k, const double *v) {
        P.omega[n + k]    = v[0];
        P.pressure[n + k] = v[1];
        P.density[n + k]  = v[2];
        no_slip[n + k]    = Vec3(v[3], v[4], v[5]);
      });
  }

  void SphExchange::extend(const SphParticles &P, std::vector<Vec3> &values)
  {
    if (!active())
      return;
    const unsigned int n = P.n_local;
    values.resize(P.size());
    impl->ghosts->refresh(
      3,
      [&](const unsigned int a, double *v) {
        for (unsigned int d = 0; d < 3; ++d)
          v[d] = values[a][d];
      },
      [&](const unsigned int k, const double *v) { values[n + k] = Vec3(v[0], v[1], v[2]); });
  }

  SphParticles SphExchange::gather_all(const SphParticles &P, std::vector<Vec3> *attached) const
  {
    const unsigned int  size = record_size + (attached ? 3 : 0);
    std::vector<double> mine(P.n_local * size);
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        pack(P, a, mine.data() + a * size);
        if (attached)
          for (unsigned int d = 0; d < 3; ++d)
            mine[a * size + record_size + d] = (*attached)[a][d];
      }
    const std::vector<std::vector<double>> blocks =
      Utilities::MPI::all_gather(impl->communicator, mine);
    std::vector<const double *> records;
    for (const auto &block : blocks)
      for (std::size_t k = 0; k < block.size(); k += size)
        records.push_back(block.data() + k);
    std::sort(records.begin(), records.end(),
              [](const double *a, const double *b) { return a[0] < b[0]; });
    SphParticles all;
    if (attached)
      attached->clear();
    for (const double *r : records)
      {
        append(all, r);
        if (attached)
          attached->emplace_back(r[record_size], r[record_size + 1], r[record_size + 2]);
      }
    all.n_local = all.size();
    return all;
  }

  std::string SphExchange::describe(const SphParticles &P) const
  {
    const Implementation &I = *impl;
    int counts[2] = {-static_cast<int>(P.n_local), static_cast<int>(P.n_local)};
    MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT, MPI_MAX, I.communicator);
    std::ostringstream o;
    o << std::setprecision(4) << I.n_ranks << " MPI ranks own the " << I.n_cells[0] << " x "
      << I.n_cells[1] << " x " << I.n_cells[2] << " cells of " << I.cell_size.x << " x "
      << I.cell_size.y << " x " << I.cell_size.z << " m (p4est), " << -counts[0] << " to "
      << counts[1] << " particles each";
    return o.str();
  }

  std::string first_message_over_ranks(MPI_Comm communicator, const std::string &message)
  {
    int n_ranks = 1;
    MPI_Comm_size(communicator, &n_ranks);
    if (n_ranks == 1)
      return message;
    int rank = 0;
    MPI_Comm_rank(communicator, &rank);
    int first = message.empty() ? n_ranks : rank;
    MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, communicator);
    if (first == n_ranks)
      return {};
    return Utilities::MPI::broadcast(communicator, message, first);
  }
} // namespace sluice
