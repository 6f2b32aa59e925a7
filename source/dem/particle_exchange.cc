#include <sluice/dem/particle_exchange.h>
#include <sluice/dem/ghost_layer.h>

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/particles/particle_handler.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    Point<3> to_point(const Vec3 &v) { return Point<3>(v.x, v.y, v.z); }

    /// The properties a particle carries in the handler, declared like the
    /// scene's fields (particle_fields.h): the DEM's own state, the rank that
    /// owned it before the last migration (which the contact histories of
    /// the particles that changed rank are asked from), then every scene
    /// field that migrates.
    struct HandlerLayout
    {
      explicit HandlerLayout(const ParticleFieldRegistry &scene)
      {
        const ParticleFieldRegistry::Use travels{true, false, false};
        velocity         = properties.declare("velocity", 3, travels);
        angular_velocity = properties.declare("angular_velocity", 3, travels);
        radius           = properties.declare("radius", 1, travels);
        type             = properties.declare("type", 1, travels);
        previous_owner   = properties.declare("previous_owner", 1, travels);
        for (const ParticleField &f : scene.fields())
          if (f.migrates)
            {
              const unsigned int at = properties.declare(f.name, f.size, travels);
              migrating.push_back({f.offset, at, f.size});
              if (f.name == clump_fields::orientation)
                {
                  orientation = at;
                  orientation_block = f.offset;
                }
              if (f.name == clump_fields::shape)
                shape = at;
              if (f.name == clump_fields::scale)
                scale = at;
            }
        n_doubles = scene.doubles_per_particle();
      }

      /// A scene field's place in the particle's block and among the properties.
      struct Migrating
      {
        unsigned int block_offset, property, size;
      };

      ParticleFieldRegistry  properties;
      unsigned int           velocity, angular_velocity, radius, type, previous_owner;
      std::vector<Migrating> migrating;
      unsigned int           n_doubles; // the scene's block per particle
      // A clump body's fields among the properties (none: not a clump scene),
      // and the orientation's offset in the block.
      static constexpr unsigned int none = ~0u;
      unsigned int orientation = none, shape = none, scale = none, orientation_block = 0;
    };
  } // namespace

  struct ParticleExchange::Implementation
  {
    MPI_Comm                                communicator;
    parallel::distributed::Triangulation<3> triangulation;
    MappingQ1<3>                            mapping;
    Particles::ParticleHandler<3>           handler;
    bool                                    carry_histories;
    BodyTransport                           bodies;
    HandlerLayout                           layout;
    int                                     n_cells[3];
    Vec3                                    lower, cell_size;
    // Coarse cells in lexicographic order of their (i, j, k) position, so that
    // finding the cell of a point costs O(1) instead of a search.
    std::vector<Triangulation<3>::active_cell_iterator> cell_at;
    // While a restart restores a saved partition: the weight of each coarse
    // cell (by index) that makes p4est cut exactly where it had cut.
    std::vector<unsigned int> forced_weight;
    // The ghosts (ghost_layer.h): their records (id, location, properties)
    // from the last exchange, appended after the owned particles. The
    // partners follow the partition ('owners_changed').
    std::unique_ptr<GhostLayer> ghosts;
    std::vector<unsigned int>   lex_of_coarse;
    bool                        owners_changed = true;
    std::vector<double>         ghost_records;
    // The contact histories of the particles that arrived in the last
    // migration, from their previous owners: first id, second id, wall flag
    // and three components each.
    std::vector<double> arrived_histories;

    Implementation(MPI_Comm comm, const bool carry_histories, const ParticleFieldRegistry &fields,
                   const BodyTransport &bodies)
      : communicator(comm), triangulation(comm), carry_histories(carry_histories), bodies(bodies)
      , layout(fields)
    {}

    /// Doubles per particle in the per-step ghost refresh: position,
    /// velocity and angular velocity, and a clump body's orientation.
    unsigned int n_refreshed() const { return bodies.clumps ? 13 : 9; }
    /// The handler particle a contact history's member belongs to.
    types::particle_index owner_of(const std::uint64_t member) const
    {
      return member / bodies.member_stride;
    }
    unsigned int this_rank() const { return Utilities::MPI::this_mpi_process(communicator); }

    Triangulation<3>::active_cell_iterator cell_around(const Vec3 &x) const
    {
      int c[3];
      for (unsigned int d = 0; d < 3; ++d)
        c[d] = std::min(std::max(static_cast<int>(std::floor((x[d] - lower[d]) / cell_size[d])), 0),
                        n_cells[d] - 1);
      return cell_at[c[0] + n_cells[0] * (c[1] + n_cells[1] * c[2])];
    }

    /// Inserts one particle at x (inside the box) with the record's state,
    /// if its cell is this rank's. 'properties' is scratch space.
    void insert_if_owned(const ParticleRecord &r, const Vec3 &x, const types::particle_index id,
                         std::vector<double> &properties)
    {
      const auto cell = cell_around(x);
      if (!cell->is_locally_owned())
        return;
      for (unsigned int d = 0; d < 3; ++d)
        {
          properties[layout.velocity + d]         = r.velocity[d];
          properties[layout.angular_velocity + d] = r.angular_velocity[d];
        }
      properties[layout.radius]         = r.radius;
      properties[layout.type]           = r.type;
      properties[layout.previous_owner] = this_rank();
      if (layout.orientation != HandlerLayout::none)
        {
          for (unsigned int k = 0; k < 4; ++k)
            properties[layout.orientation + k] = r.orientation[k];
          properties[layout.shape] = r.clump_template;
          properties[layout.scale] = r.clump_scale;
        }
      handler.insert_particle(to_point(x), reference_location(cell, x), id, cell,
                              ArrayView<const double>(properties));
    }

    /// Collective. The rank that owns each coarse cell, by cell index.
    std::vector<int> owner_of_each_cell() const
    {
      std::vector<int> owner(triangulation.n_cells(0), -1);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          owner[cell->index()] = this_rank();
      MPI_Allreduce(MPI_IN_PLACE, owner.data(), owner.size(), MPI_INT, MPI_MAX, communicator);
      return owner;
    }

    /// Record size of a ghost: id, location, properties.
    unsigned int ghost_record_size() const { return 4 + handler.n_properties_per_particle(); }

    /// Collective: sends a record of every owned particle to the ranks that
    /// own a neighbour of its cell.
    void exchange_ghosts()
    {
      if (!ghosts->active())
        return;
      if (owners_changed)
        {
          const std::vector<int> by_index = owner_of_each_cell();
          std::vector<int>       by_lex(by_index.size());
          for (unsigned int c = 0; c < by_index.size(); ++c)
            by_lex[lex_of_coarse[c]] = by_index[c];
          ghosts->set_owners(by_lex);
          owners_changed = false;
        }
      // The handle of an owned particle is its index in the handler's order,
      // which is its index in the arrays fill_storage() builds.
      std::vector<Particles::ParticleHandler<3>::particle_iterator> owned;
      std::vector<GhostLayer::Send>                                 sends;
      for (auto particle = handler.begin(); particle != handler.end(); ++particle)
        {
          const auto lex = lex_of_coarse[particle->get_surrounding_cell()->index()];
          for (const int rank : ghosts->partners_of(lex))
            sends.push_back({static_cast<unsigned int>(owned.size()), rank});
          owned.push_back(particle);
        }
      const unsigned int n           = handler.n_properties_per_particle();
      auto               pack_record = [&](const unsigned int i, double *record) {
        const auto &particle = owned[i];
        record[0]            = particle->get_id();
        for (unsigned int d = 0; d < 3; ++d)
          record[1 + d] = particle->get_location()[d];
        const ArrayView<const double> prop = particle->get_properties();
        std::copy(prop.begin(), prop.begin() + n, record + 4);
      };
      ghost_records = ghosts->exchange(sends, ghost_record_size(), pack_record);
    }

    /// Collective, after the particles moved: asks the previous owner of every
    /// particle that arrived here for its contact histories, and keeps them
    /// in 'arrived_histories'.
    void fetch_histories(const ContactHistoryMap &histories)
    {
      arrived_histories.clear();
      if (!carry_histories)
        return;
      std::map<unsigned int, std::vector<std::uint64_t>> wanted;
      for (const auto &particle : handler)
        {
          const unsigned int from = particle.get_properties()[layout.previous_owner];
          if (from != this_rank())
            wanted[from].push_back(particle.get_id());
        }
      const auto asked = Utilities::MPI::some_to_some(communicator, wanted);
      // Each history goes to the new owner of each of its two particles.
      std::unordered_map<std::uint64_t, unsigned int> new_owner;
      for (const auto &[rank, ids] : asked)
        for (const auto id : ids)
          new_owner[id] = rank;
      std::map<unsigned int, std::vector<double>> answers;
      const auto                                  none = new_owner.end();
      if (!new_owner.empty())
        for (const auto &[key, h] : histories)
          {
            auto send_to = [&, &key = key, &h = h](const unsigned int rank) {
              answers[rank].insert(answers[rank].end(),
                                   {static_cast<double>(key.first), static_cast<double>(key.second),
                                    key.wall ? 1. : 0., h.x, h.y, h.z});
            };
            const auto first  = new_owner.find(owner_of(key.first));
            const auto second = key.wall ? none : new_owner.find(owner_of(key.second));
            if (first != none)
              send_to(first->second);
            if (second != none && (first == none || second->second != first->second))
              send_to(second->second);
          }
      for (const auto &[rank, records] : Utilities::MPI::some_to_some(communicator, answers))
        arrived_histories.insert(arrived_histories.end(), records.begin(), records.end());
    }

    Point<3> reference_location(const Triangulation<3>::active_cell_iterator &cell,
                                const Vec3 &x) const
    {
      const Point<3> v0 = cell->vertex(0);
      return Point<3>((x.x - v0[0]) / cell_size.x, (x.y - v0[1]) / cell_size.y,
                      (x.z - v0[2]) / cell_size.z);
    }
  };

  ParticleExchange::ParticleExchange(MPI_Comm communicator, const PeriodicBox &box,
                                     const double interaction_range,
                                     const unsigned long long     n_particles,
                                     const bool                   carry_histories,
                                     const ParticleFieldRegistry &fields,
                                     const BodyTransport          bodies)
    : impl(std::make_unique<Implementation>(communicator, carry_histories, fields, bodies))
  {
    // Cells at least one interaction range wide, so that ghosts from the cells
    // next to a rank's own cells include every possible partner. Not many more
    // cells than particles/8, which keeps the coarse mesh cheap for dilute scenes.
    double n_total = 1.;
    for (unsigned int d = 0; d < 3; ++d)
      {
        impl->n_cells[d] =
          std::max(1, static_cast<int>(std::floor(box.length[d] / interaction_range)));
        n_total *= impl->n_cells[d];
      }
    const double target = std::max(8., n_particles / 8.);
    if (n_total > target)
      {
        const double shrink = std::cbrt(n_total / target);
        for (unsigned int d = 0; d < 3; ++d)
          impl->n_cells[d] = std::max(1, static_cast<int>(impl->n_cells[d] / shrink));
      }
    for (unsigned int d = 0; d < 3; ++d)
      {
        // A periodic direction needs three cells, or the two neighbours of a cell
        // would be the same cell seen from both sides.
        if (box.periodic[d] && impl->n_cells[d] < 3 &&
            box.length[d] >= 3. * interaction_range)
          impl->n_cells[d] = 3;
        impl->cell_size[d] = box.length[d] / impl->n_cells[d];
      }
    impl->lower = box.lower;

    GridGenerator::subdivided_hyper_rectangle(
      impl->triangulation,
      {static_cast<unsigned int>(impl->n_cells[0]), static_cast<unsigned int>(impl->n_cells[1]),
       static_cast<unsigned int>(impl->n_cells[2])},
      to_point(box.lower), to_point(box.upper), /*colorize=*/true);
    std::vector<GridTools::PeriodicFacePair<Triangulation<3>::cell_iterator>> periodic_faces;
    for (unsigned int d = 0; d < 3; ++d)
      if (box.periodic[d])
        GridTools::collect_periodic_faces(impl->triangulation, 2 * d, 2 * d + 1, d, periodic_faces);
    if (!periodic_faces.empty())
      impl->triangulation.add_periodicity(periodic_faces);

    impl->cell_at.resize(impl->n_cells[0] * impl->n_cells[1] * impl->n_cells[2]);
    impl->lex_of_coarse.resize(impl->cell_at.size());
    for (const auto &cell : impl->triangulation.active_cell_iterators())
      {
        const Point<3> c = cell->center();
        int            idx[3];
        for (unsigned int d = 0; d < 3; ++d)
          idx[d] = static_cast<int>(std::floor((c[d] - box.lower[d]) / impl->cell_size[d]));
        const unsigned int lex = idx[0] + impl->n_cells[0] * (idx[1] + impl->n_cells[1] * idx[2]);
        impl->cell_at[lex] = cell;
        impl->lex_of_coarse[cell->index()] = lex;
      }
    impl->ghosts = std::make_unique<GhostLayer>(
      communicator, std::array<int, 3>{{impl->n_cells[0], impl->n_cells[1], impl->n_cells[2]}},
      box.periodic);

    impl->handler.initialize(impl->triangulation, impl->mapping,
                             impl->layout.properties.doubles_per_particle());

    // Load balance: the cost of a cell is its particles (their contacts); the
    // cells themselves cost almost nothing. p4est partitions by these weights
    // when repartition() is called (as in deal.II's step-68).
    impl->triangulation.signals.weight.connect(
      [this](const Triangulation<3>::cell_iterator &cell,
             const Triangulation<3>::CellStatus) -> unsigned int {
        if (!cell->is_active())
          return 0;
        if (!impl->forced_weight.empty())
          return impl->forced_weight[cell->index()];
        return 1 + 100 * impl->handler.n_particles_in_cell(
                           Triangulation<3>::active_cell_iterator(cell));
      });
  }

  ParticleExchange::~ParticleExchange() = default;

  void ParticleExchange::insert(const std::vector<ParticleRecord> &records,
                                const SceneParameters &           p)
  {
    std::vector<double> properties(impl->handler.n_properties_per_particle(), 0.);
    for (std::size_t id = 0; id < records.size(); ++id)
      {
        const ParticleRecord &r = records[id];
        for (unsigned int d = 0; d < 3; ++d)
          if (r.position[d] < p.lower_corner[d] || r.position[d] > p.upper_corner[d])
            throw InputError("error in '" + p.file_name + "': particle " + std::to_string(id) +
                             " at (" + to_text(r.position.x) + ", " + to_text(r.position.y) + ", " +
                             to_text(r.position.z) +
                             ") lies outside the domain [" + to_text(p.lower_corner[d]) + ", " +
                             to_text(p.upper_corner[d]) + "] in " + "xyz"[d] + " (" +
                             (p.insertion_method == InsertionMethod::lattice ||
                                  p.insertion_method == InsertionMethod::random ?
                                "entries 'insertion/region lower corner' and 'region upper "
                                "corner' reach beyond 'domain/lower corner' .. 'upper corner'" :
                                std::string(p.insertion_method == InsertionMethod::file ?
                                              "row of 'insertion/file'" :
                                              "row of 'insertion/list'")) +
                             ")");
        impl->insert_if_owned(r, r.position, id, properties);
      }
    impl->handler.update_cached_numbers();
    impl->exchange_ghosts();
  }

  unsigned long long ParticleExchange::migrate(const ParticleStorage &  particles,
                                               const ContactHistoryMap &histories,
                                               const PeriodicBox &      box)
  {
    unsigned int i = 0;
    Loss         local_loss{std::numeric_limits<std::uint64_t>::max(), Vec3()};
    const HandlerLayout &layout = impl->layout;
    for (auto &particle : impl->handler)
      {
        Assert(particle.get_id() == particles.id[i], ExcInternalError());
        const Vec3 x = box.wrap(particles.position[i]);
        if (!box.contains(x) && particles.id[i] < local_loss.id)
          local_loss = {particles.id[i], x};
        particle.set_location(to_point(x));
        ArrayView<double> prop = particle.get_properties();
        for (unsigned int d = 0; d < 3; ++d)
          {
            prop[layout.velocity + d]         = particles.velocity[i][d];
            prop[layout.angular_velocity + d] = particles.angular_velocity[i][d];
          }
        prop[layout.previous_owner] = impl->this_rank();
        for (const auto &f : layout.migrating)
          for (unsigned int e = 0; e < f.size; ++e)
            prop[f.property + e] = particles.extra_of(i)[f.block_offset + e];
        ++i;
      }

    const auto before = impl->handler.n_global_particles();
    impl->handler.sort_particles_into_subdomains_and_cells();
    const auto after = impl->handler.n_global_particles();
    if (after < before)
      {
        // Which rank lost the lowest id tells where it went.
        MPI_Allreduce(&local_loss.id, &first_loss_.id, 1, MPI_UINT64_T, MPI_MIN,
                      impl->communicator);
        const int owner =
          Utilities::MPI::min(first_loss_.id == local_loss.id ?
                                Utilities::MPI::this_mpi_process(impl->communicator) :
                                std::numeric_limits<unsigned int>::max(),
                              impl->communicator);
        first_loss_.position = local_loss.position;
        MPI_Bcast(&first_loss_.position, 3, MPI_DOUBLE, owner, impl->communicator);
      }

    // Particles gather where gravity takes them, not where p4est first put the
    // cells: when the busiest rank has 15% more particles than the mean, the
    // cells are repartitioned by particle count and the particles move with them,
    // but only if that would take at least a tenth of the load off the busiest
    // rank (with few cells the target may be out of reach, and every attempt
    // costs a full migration), and not within 20 list builds of the last one.
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(impl->communicator);
    ++builds_since_repartition_;
    if (n_ranks > 1 && builds_since_repartition_ >= 20)
      {
        const double busiest = Utilities::MPI::max(
          static_cast<double>(impl->handler.n_locally_owned_particles()), impl->communicator);
        if (busiest > 1.15 * static_cast<double>(after) / n_ranks &&
            predicted_busiest_after_repartition() < 0.9 * busiest)
          {
            impl->handler.prepare_for_coarsening_and_refinement();
            impl->triangulation.repartition();
            impl->handler.unpack_after_coarsening_and_refinement();
            impl->owners_changed = true;
            ++n_repartitions_;
            builds_since_repartition_ = 0;
          }
      }
    impl->fetch_histories(histories);
    impl->exchange_ghosts();
    return before - after;
  }

  double ParticleExchange::predicted_busiest_after_repartition() const
  {
    // The particles of every coarse cell (a p4est tree), known on every rank.
    const auto         &tria = impl->triangulation;
    std::vector<double> particles_in(tria.n_cells(0), 0.);
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        particles_in[cell->index()] = impl->handler.n_particles_in_cell(cell);
    MPI_Allreduce(MPI_IN_PLACE, particles_in.data(), particles_in.size(), MPI_DOUBLE, MPI_SUM,
                  impl->communicator);
    // p4est cuts the trees, in its order, where the running sum of the weights
    // (those of signals.weight) crosses k / n_ranks of the total.
    const std::vector<types::global_dof_index> &tree_to_cell =
      tria.get_p4est_tree_to_coarse_cell_permutation();
    double total = 0.;
    for (const double n : particles_in)
      total += 1. + 100. * n;
    const unsigned int  n_ranks = Utilities::MPI::n_mpi_processes(impl->communicator);
    std::vector<double> load(n_ranks, 0.);
    double              running = 0.;
    for (const auto cell : tree_to_cell)
      {
        const double       weight = 1. + 100. * particles_in[cell];
        const unsigned int rank =
          std::min<unsigned int>(n_ranks - 1, (running + 0.5 * weight) * n_ranks / total);
        load[rank] += particles_in[cell];
        running += weight;
      }
    return *std::max_element(load.begin(), load.end());
  }

  void ParticleExchange::fill_storage(ParticleStorage &particles, ContactHistoryMap &histories,
                                      const std::vector<double> &densities) const
  {
    const HandlerLayout &layout = impl->layout;
    particles.clear();
    particles.n_extra = layout.n_doubles;
    // One particle's state and its block of scene fields: what migrates (a
    // ghost's, in a clump scene only: its body's fields), zero for the rest.
    auto append = [&](const std::uint64_t id, const Vec3 &x, const double *prop,
                      const bool with_block) {
      const unsigned int type = static_cast<unsigned int>(prop[layout.type]);
      const unsigned int v = layout.velocity, w = layout.angular_velocity;
      particles.push_back(id, x, Vec3(prop[v], prop[v + 1], prop[v + 2]),
                          Vec3(prop[w], prop[w + 1], prop[w + 2]), prop[layout.radius], type,
                          densities[type]);
      if (!with_block)
        return;
      const std::size_t block = particles.extra.size();
      particles.extra.resize(block + layout.n_doubles, 0.);
      for (const auto &f : layout.migrating)
        for (unsigned int e = 0; e < f.size; ++e)
          particles.extra[block + f.block_offset + e] = prop[f.property + e];
    };
    for (auto particle = impl->handler.begin(); particle != impl->handler.end(); ++particle)
      {
        const auto x = particle->get_location();
        append(particle->get_id(), Vec3(x[0], x[1], x[2]), particle->get_properties().data(),
               true);
      }
    particles.n_local = particles.size();
    const unsigned int record_size = impl->ghost_record_size();
    for (std::size_t at = 0; at < impl->ghost_records.size(); at += record_size)
      {
        const double *record = impl->ghost_records.data() + at;
        append(static_cast<std::uint64_t>(record[0]), Vec3(record[1], record[2], record[3]),
               record + 4, impl->bodies.clumps);
      }
    // A pair's history that this rank computed itself stays.
    const std::vector<double> &h = impl->arrived_histories;
    for (std::size_t at = 0; at < h.size(); at += 6)
      {
        const ContactHistoryKey key{static_cast<std::uint64_t>(h[at]),
                                    static_cast<std::uint64_t>(h[at + 1]), h[at + 2] > 0.5};
        if (histories.find(key) == histories.end())
          histories[key] = Vec3(h[at + 3], h[at + 4], h[at + 5]);
      }
  }

  void ParticleExchange::update_ghosts(ParticleStorage &particles)
  {
    const unsigned int orientation = impl->layout.orientation_block;
    const bool         clumps      = impl->bodies.clumps;
    const unsigned int first_ghost = particles.n_local;
    impl->ghosts->refresh(
      impl->n_refreshed(),
      [&](const unsigned int i, double *values) {
        for (unsigned int d = 0; d < 3; ++d)
          {
            values[d]     = particles.position[i][d];
            values[3 + d] = particles.velocity[i][d];
            values[6 + d] = particles.angular_velocity[i][d];
          }
        if (clumps)
          for (unsigned int k = 0; k < 4; ++k)
            values[9 + k] = particles.extra_of(i)[orientation + k];
      },
      [&](const unsigned int k, const double *values) {
        const unsigned int j          = first_ghost + k;
        particles.position[j]         = Vec3(values[0], values[1], values[2]);
        particles.velocity[j]         = Vec3(values[3], values[4], values[5]);
        particles.angular_velocity[j] = Vec3(values[6], values[7], values[8]);
        if (clumps)
          for (unsigned int m = 0; m < 4; ++m)
            particles.extra_of(j)[orientation + m] = values[9 + m];
      });
  }

  void ParticleExchange::reinsert(const std::vector<ParticleRecord> &records,
                                  const std::vector<std::uint64_t> &ids, const PeriodicBox &box)
  {
    impl->handler.clear();
    std::vector<double> properties(impl->handler.n_properties_per_particle(), 0.);
    for (std::size_t k = 0; k < records.size(); ++k)
      impl->insert_if_owned(records[k], box.wrap(records[k].position), ids[k], properties);
    impl->handler.update_cached_numbers();
    impl->exchange_ghosts();
  }

  void ParticleExchange::replace(const std::vector<std::uint64_t> &remove_ids,
                                 const std::vector<ParticleRecord> &records,
                                 const std::vector<std::uint64_t> &ids, const PeriodicBox &box)
  {
    std::vector<std::uint64_t> sorted(remove_ids);
    std::sort(sorted.begin(), sorted.end());
    std::vector<Particles::ParticleHandler<3>::particle_iterator> gone;
    for (auto particle = impl->handler.begin(); particle != impl->handler.end(); ++particle)
      if (std::binary_search(sorted.begin(), sorted.end(), particle->get_id()))
        gone.push_back(particle);
    impl->handler.remove_particles(gone);
    std::vector<double> properties(impl->handler.n_properties_per_particle(), 0.);
    for (std::size_t k = 0; k < records.size(); ++k)
      impl->insert_if_owned(records[k], box.wrap(records[k].position), ids[k], properties);
    impl->handler.update_cached_numbers();
    impl->exchange_ghosts();
  }

  std::vector<int> ParticleExchange::cell_owners() const
  {
    return impl->owner_of_each_cell();
  }

  void ParticleExchange::save(const std::string &path) const
  {
    impl->handler.prepare_for_serialization();
    impl->triangulation.save(path);
  }

  void ParticleExchange::load(const std::string &path, const std::vector<int> &owners)
  {
    impl->handler.clear();
    impl->triangulation.load(path);
    impl->handler.deserialize();
    impl->owners_changed = true;
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(impl->communicator);
    if (n_ranks > 1 && owners.size() == impl->triangulation.n_cells(0))
      {
        // p4est loads with the cells spread evenly; the saved partition (a
        // range of trees per rank, in p4est's order) comes back through
        // weights: the first cell of rank r's range weighs S - n_r + 1, the
        // others 1, so every range weighs S and p4est's cuts at multiples of
        // S fall exactly on the saved range boundaries.
        const std::vector<types::global_dof_index> &order =
          impl->triangulation.get_p4est_tree_to_coarse_cell_permutation();
        std::vector<unsigned int> range_size(n_ranks, 0);
        bool                      contiguous = true;
        int                       previous   = 0;
        for (const auto cell : order)
          {
            const int o = owners[cell];
            contiguous  = contiguous && o >= previous && o < static_cast<int>(n_ranks);
            previous    = o;
            if (contiguous)
              ++range_size[o];
          }
        const unsigned int S = *std::max_element(range_size.begin(), range_size.end());
        if (contiguous && *std::min_element(range_size.begin(), range_size.end()) > 0)
          {
            impl->forced_weight.assign(owners.size(), 1);
            int last = -1;
            for (const auto cell : order)
              if (owners[cell] != last)
                {
                  last                      = owners[cell];
                  impl->forced_weight[cell] = S - range_size[last] + 1;
                }
            impl->handler.prepare_for_coarsening_and_refinement();
            impl->triangulation.repartition();
            impl->handler.unpack_after_coarsening_and_refinement();
            impl->forced_weight.clear();
          }
      }
    impl->handler.update_cached_numbers();
    impl->exchange_ghosts();
  }

  std::vector<unsigned int> ParticleExchange::counters() const
  {
    return {n_repartitions_, builds_since_repartition_};
  }

  void ParticleExchange::set_counters(const std::vector<unsigned int> &c)
  {
    n_repartitions_           = c.at(0);
    builds_since_repartition_ = c.at(1);
  }

  unsigned long long ParticleExchange::n_global_particles() const
  {
    return impl->handler.n_global_particles();
  }

  unsigned int ParticleExchange::n_cells_global() const
  {
    return impl->triangulation.n_global_active_cells();
  }

  unsigned int ParticleExchange::n_ranks() const
  {
    return Utilities::MPI::n_mpi_processes(impl->communicator);
  }
} // namespace sluice
