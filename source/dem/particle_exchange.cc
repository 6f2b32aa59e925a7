#include <sluice/dem/particle_exchange.h>
#include <sluice/dem/periodic_edge_ghosts.h>

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/particles/particle_handler.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    // One history slot: partner id (or wall index), wall flag, three
    // components; in a clump scene also the member's own id (after the flag).
    unsigned int slot_size_of(const BodyTransport &bodies) { return bodies.clumps ? 6 : 5; }

    Point<3> to_point(const Vec3 &v) { return Point<3>(v.x, v.y, v.z); }

    /// The properties a particle carries in the handler, declared like the
    /// scene's fields (particle_fields.h): the DEM's own state, the history
    /// slots, then every scene field that migrates.
    struct HandlerLayout
    {
      HandlerLayout(const unsigned int history_slots, const ParticleFieldRegistry &scene,
                    const BodyTransport &bodies)
        : slot_size(slot_size_of(bodies))
      {
        const ParticleFieldRegistry::Use travels{true, false, false};
        velocity         = properties.declare("velocity", 3, travels);
        angular_velocity = properties.declare("angular_velocity", 3, travels);
        radius           = properties.declare("radius", 1, travels);
        type             = properties.declare("type", 1, travels);
        n_history        = properties.declare("history_count", 1, travels);
        first_slot       = properties.doubles_per_particle();
        if (history_slots > 0)
          properties.declare("histories", slot_size * history_slots, travels);
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

      unsigned int           slot_size;
      ParticleFieldRegistry  properties;
      unsigned int           velocity, angular_velocity, radius, type, n_history, first_slot;
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
    unsigned int                            history_slots;
    BodyTransport                           bodies;
    HandlerLayout                           layout;
    int                                     n_cells[3];
    Vec3                                    lower, cell_size;
    // Coarse cells in lexicographic order of their (i, j, k) position, so that
    // finding the cell of a point costs O(1) instead of a search.
    std::vector<Triangulation<3>::active_cell_iterator> cell_at;
    // Where a ghost with a given id sits in the arrays.
    std::unordered_map<types::particle_index, unsigned int> ghost_index;
    // The per-step ghost refresh sends every property of every ghost, and a
    // particle carries its contact histories and coupling data as properties.
    // So the refresh goes through a second handler on the same mesh that holds
    // only what changes every step (velocity and angular velocity), rebuilt
    // after every migration; 'light_owned' and 'light_ghost' give the array
    // index of its particles in its own iteration order.
    Particles::ParticleHandler<3> light;
    std::vector<unsigned int>     light_owned, light_ghost;
    // While a restart restores a saved partition: the weight of each coarse
    // cell (by index) that makes p4est cut exactly where it had cut.
    std::vector<unsigned int> forced_weight;
    // The ghosts across periodic edges and corners that the handler misses
    // (periodic_edge_ghosts.h): their records (id, location, properties),
    // appended after the handler's ghosts, and where the first one sits in the
    // arrays. The partners follow the partition ('owners_changed').
    std::unique_ptr<PeriodicEdgeGhosts> edges;
    std::vector<unsigned int>           lex_of_coarse;
    bool                                owners_changed = true;
    std::vector<double>                 edge_records;
    unsigned int                        first_edge_ghost = 0;

    Implementation(MPI_Comm comm, unsigned int slots, const ParticleFieldRegistry &fields,
                   const BodyTransport &bodies)
      : communicator(comm), triangulation(comm), history_slots(slots), bodies(bodies)
      , layout(slots, fields, bodies)
    {}

    /// Doubles per particle in the per-step ghost refresh: velocity and
    /// angular velocity, and a clump body's orientation.
    unsigned int n_light() const { return bodies.clumps ? 10 : 6; }
    /// The handler particle a contact history's member belongs to.
    types::particle_index owner_of(const std::uint64_t member) const
    {
      return member / bodies.member_stride;
    }

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
      properties[layout.radius] = r.radius;
      properties[layout.type]   = r.type;
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
          owner[cell->index()] = Utilities::MPI::this_mpi_process(communicator);
      MPI_Allreduce(MPI_IN_PLACE, owner.data(), owner.size(), MPI_INT, MPI_MAX, communicator);
      return owner;
    }

    /// Record size of a ghost across a periodic edge: id, location, properties.
    unsigned int edge_record_size() const { return 4 + handler.n_properties_per_particle(); }

    /// Collective: the handler's ghosts, then those it misses across periodic
    /// edges and corners.
    void exchange_ghosts()
    {
      handler.exchange_ghost_particles(false); // the refresh uses 'light'
      if (!edges->active())
        return;
      if (owners_changed)
        {
          const std::vector<int> by_index = owner_of_each_cell();
          std::vector<int>       by_lex(by_index.size());
          for (unsigned int c = 0; c < by_index.size(); ++c)
            by_lex[lex_of_coarse[c]] = by_index[c];
          edges->set_owners(by_lex);
          owners_changed = false;
        }
      // The handle of an owned particle is its index in the handler's order,
      // which is its index in the arrays fill_storage() builds.
      std::vector<Particles::ParticleHandler<3>::particle_iterator> owned;
      std::vector<PeriodicEdgeGhosts::Send>                         sends;
      for (auto particle = handler.begin(); particle != handler.end(); ++particle)
        {
          const auto lex = lex_of_coarse[particle->get_surrounding_cell()->index()];
          for (const int rank : edges->partners_of(lex))
            sends.push_back({static_cast<unsigned int>(owned.size()), rank});
          owned.push_back(particle);
        }
      std::unordered_set<types::particle_index> ghosts;
      for (auto particle = handler.begin_ghost(); particle != handler.end_ghost(); ++particle)
        ghosts.insert(particle->get_id());
      const unsigned int n = handler.n_properties_per_particle();
      edge_records         = edges->exchange(
        sends, edge_record_size(),
        [&](const unsigned int i, double *record) {
          const auto &particle = owned[i];
          record[0]            = particle->get_id();
          for (unsigned int d = 0; d < 3; ++d)
            record[1 + d] = particle->get_location()[d];
          const ArrayView<const double> prop = particle->get_properties();
          std::copy(prop.begin(), prop.begin() + n, record + 4);
        },
        [&](const std::uint64_t id) { return ghosts.count(id) > 0; });
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
                                     const unsigned long long n_particles,
                                     const unsigned int            history_slots,
                                     const ParticleFieldRegistry &fields,
                                     const BodyTransport          bodies)
    : impl(std::make_unique<Implementation>(communicator, history_slots, fields, bodies))
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
    impl->edges = std::make_unique<PeriodicEdgeGhosts>(
      communicator, std::array<int, 3>{{impl->n_cells[0], impl->n_cells[1], impl->n_cells[2]}},
      box.periodic);

    impl->handler.initialize(impl->triangulation, impl->mapping,
                             impl->layout.properties.doubles_per_particle());
    impl->light.initialize(impl->triangulation, impl->mapping, impl->n_light());

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
    // Histories of each owned particle's contacts, to travel with it.
    std::unordered_map<types::particle_index, std::vector<std::pair<ContactHistoryKey, Vec3>>>
      by_particle;
    if (impl->history_slots > 0)
      for (const auto &h : histories)
        {
          by_particle[impl->owner_of(h.first.first)].push_back(h);
          if (!h.first.wall)
            by_particle[impl->owner_of(h.first.second)].push_back(h);
        }

    unsigned int i = 0;
    Loss         local_loss{std::numeric_limits<std::uint64_t>::max(), Vec3()};
    double       too_many = 0.; // the most histories of a particle beyond the slots
    for (auto &particle : impl->handler)
      {
        Assert(particle.get_id() == particles.id[i], ExcInternalError());
        const Vec3 x = box.wrap(particles.position[i]);
        if (!box.contains(x) && particles.id[i] < local_loss.id)
          local_loss = {particles.id[i], x};
        particle.set_location(to_point(x));
        ArrayView<double> prop = particle.get_properties();
        const HandlerLayout &layout = impl->layout;
        for (unsigned int d = 0; d < 3; ++d)
          {
            prop[layout.velocity + d]         = particles.velocity[i][d];
            prop[layout.angular_velocity + d] = particles.angular_velocity[i][d];
          }
        for (const auto &f : layout.migrating)
          for (unsigned int e = 0; e < f.size; ++e)
            prop[f.property + e] = particles.extra_of(i)[f.block_offset + e];
        if (impl->history_slots > 0)
          {
            const auto it = by_particle.find(particle.get_id());
            const unsigned int n = it == by_particle.end() ? 0 : it->second.size();
            if (n > impl->history_slots)
              {
                too_many = std::max<double>(too_many, n);
                ++i;
                continue;
              }
            prop[layout.n_history] = n;
            for (unsigned int s = 0; s < n; ++s)
              {
                const auto &[key, h]          = it->second[s];
                const unsigned int base       = layout.first_slot + layout.slot_size * s;
                const bool this_is_first      = impl->owner_of(key.first) == particle.get_id();
                prop[base]     = key.wall ? key.second : (this_is_first ? key.second : key.first);
                prop[base + 1] = key.wall ? 1. : 0.;
                const unsigned int h_at = base + layout.slot_size - 3;
                if (impl->bodies.clumps) // the member's own id
                  prop[base + 2] = this_is_first ? key.first : key.second;
                for (unsigned int d = 0; d < 3; ++d)
                  prop[h_at + d] = h[d];
              }
          }
        ++i;
      }

    // Every rank must stop together, or the others would wait for this one.
    if (impl->history_slots > 0)
      {
        too_many = Utilities::MPI::max(too_many, impl->communicator);
        if (too_many > 0.)
          throw SimulationFailure(
            "entry 'parallel/maximum contacts per particle' = " +
            std::to_string(impl->history_slots) + " is too small: a particle has " +
            std::to_string(static_cast<unsigned int>(too_many)) +
            " contacts with tangential history; raise it (it costs memory and ghost traffic)");
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
            impl->light.clear();
            impl->handler.prepare_for_coarsening_and_refinement();
            impl->triangulation.repartition();
            impl->handler.unpack_after_coarsening_and_refinement();
            impl->owners_changed = true;
            ++n_repartitions_;
            builds_since_repartition_ = 0;
          }
      }
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
    impl->ghost_index.clear();
    auto append = [&](const std::uint64_t id, const Vec3 &x, const double *prop) {
      const unsigned int type = static_cast<unsigned int>(prop[layout.type]);
      const unsigned int v = layout.velocity, w = layout.angular_velocity;
      particles.push_back(id, x, Vec3(prop[v], prop[v + 1], prop[v + 2]),
                          Vec3(prop[w], prop[w + 1], prop[w + 2]), prop[layout.radius], type,
                          densities[type]);
    };
    auto append_handled = [&](const Particles::ParticleIterator<3> &particle) {
      const auto                    x    = particle->get_location();
      const ArrayView<const double> prop = particle->get_properties();
      append(particle->get_id(), Vec3(x[0], x[1], x[2]), prop.data());
      return prop;
    };
    // A ghost's block in a clump scene: its body's fields.
    auto append_ghost_block = [&](const double *prop) {
      if (!impl->bodies.clumps)
        return;
      const std::size_t block = particles.extra.size();
      particles.extra.resize(block + layout.n_doubles, 0.);
      for (const auto &f : layout.migrating)
        for (unsigned int e = 0; e < f.size; ++e)
          particles.extra[block + f.block_offset + e] = prop[f.property + e];
    };
    for (auto particle = impl->handler.begin(); particle != impl->handler.end(); ++particle)
      {
        const auto prop = append_handled(particle);
        const std::uint64_t id = particle->get_id();
        // The scene's block: what migrated, zero for what does not.
        const std::size_t block = particles.extra.size();
        particles.extra.resize(block + layout.n_doubles, 0.);
        for (const auto &f : layout.migrating)
          for (unsigned int e = 0; e < f.size; ++e)
            particles.extra[block + f.block_offset + e] = prop[f.property + e];
        if (impl->history_slots > 0)
          for (unsigned int s = 0; s < static_cast<unsigned int>(prop[layout.n_history]); ++s)
            {
              const unsigned int  base  = layout.first_slot + layout.slot_size * s;
              const std::uint64_t other = static_cast<std::uint64_t>(prop[base]);
              const bool          wall  = prop[base + 1] > 0.5;
              const std::uint64_t self =
                impl->bodies.clumps ? static_cast<std::uint64_t>(prop[base + 2]) : id;
              const unsigned int h_at = base + layout.slot_size - 3;
              const Vec3         h(prop[h_at], prop[h_at + 1], prop[h_at + 2]);
              if (wall)
                histories[{self, other, true}] = h;
              else
                histories[{std::min(self, other), std::max(self, other), false}] = h;
            }
      }
    particles.n_local = particles.size();
    for (auto particle = impl->handler.begin_ghost(); particle != impl->handler.end_ghost();
         ++particle)
      {
        impl->ghost_index[particle->get_id()] = particles.size();
        append_ghost_block(append_handled(particle).data());
      }
    impl->first_edge_ghost = particles.size();
    const unsigned int record_size = impl->edge_record_size();
    for (std::size_t at = 0; at < impl->edge_records.size(); at += record_size)
      {
        const double       *record = impl->edge_records.data() + at;
        const std::uint64_t id     = static_cast<std::uint64_t>(record[0]);
        impl->ghost_index[id]      = particles.size();
        append(id, Vec3(record[1], record[2], record[3]), record + 4);
        append_ghost_block(record + 4);
      }
    rebuild_light_handler(particles);
  }

  void ParticleExchange::rebuild_light_handler(const ParticleStorage &particles) const
  {
    if (n_ranks() == 1)
      return;
    auto &light = impl->light;
    light.clear();
    std::unordered_map<types::particle_index, unsigned int> owned_index;
    unsigned int                                            i = 0;
    for (auto particle = impl->handler.begin(); particle != impl->handler.end(); ++particle, ++i)
      {
        owned_index[particle->get_id()] = i;
        double v[10];
        for (unsigned int d = 0; d < 3; ++d)
          {
            v[d]     = particles.velocity[i][d];
            v[3 + d] = particles.angular_velocity[i][d];
          }
        if (impl->bodies.clumps)
          for (unsigned int k = 0; k < 4; ++k)
            v[6 + k] = particles.extra_of(i)[impl->layout.orientation_block + k];
        light.insert_particle(particle->get_location(), particle->get_reference_location(),
                              particle->get_id(), particle->get_surrounding_cell(),
                              ArrayView<const double>(v, impl->n_light()));
      }
    light.update_cached_numbers();
    light.exchange_ghost_particles(true);
    impl->light_owned.clear();
    for (auto particle = light.begin(); particle != light.end(); ++particle)
      impl->light_owned.push_back(owned_index.at(particle->get_id()));
    impl->light_ghost.clear();
    for (auto particle = light.begin_ghost(); particle != light.end_ghost(); ++particle)
      impl->light_ghost.push_back(impl->ghost_index.at(particle->get_id()));
  }

  void ParticleExchange::update_ghosts(ParticleStorage &particles)
  {
    auto        &light = impl->light;
    unsigned int k     = 0;
    for (auto &particle : light)
      {
        const unsigned int i = impl->light_owned[k++];
        particle.set_location(to_point(particles.position[i]));
        ArrayView<double> prop = particle.get_properties();
        for (unsigned int d = 0; d < 3; ++d)
          {
            prop[d]     = particles.velocity[i][d];
            prop[3 + d] = particles.angular_velocity[i][d];
          }
        if (impl->bodies.clumps)
          for (unsigned int k = 0; k < 4; ++k)
            prop[6 + k] = particles.extra_of(i)[impl->layout.orientation_block + k];
      }
    light.update_ghost_particles();
    k = 0;
    for (auto particle = light.begin_ghost(); particle != light.end_ghost(); ++particle)
      {
        const unsigned int j = impl->light_ghost[k++];
        const auto         x = particle->get_location();
        const ArrayView<const double> prop = particle->get_properties();
        particles.position[j]         = Vec3(x[0], x[1], x[2]);
        particles.velocity[j]         = Vec3(prop[0], prop[1], prop[2]);
        particles.angular_velocity[j] = Vec3(prop[3], prop[4], prop[5]);
        if (impl->bodies.clumps)
          for (unsigned int k = 0; k < 4; ++k)
            particles.extra_of(j)[impl->layout.orientation_block + k] = prop[6 + k];
      }
    // The ghosts across periodic edges: position, then what 'light' carries.
    const unsigned int orientation = impl->layout.orientation_block;
    impl->edges->refresh(
      3 + impl->n_light(),
      [&](const unsigned int i, double *values) {
        for (unsigned int d = 0; d < 3; ++d)
          {
            values[d]     = particles.position[i][d];
            values[3 + d] = particles.velocity[i][d];
            values[6 + d] = particles.angular_velocity[i][d];
          }
        if (impl->bodies.clumps)
          for (unsigned int k = 0; k < 4; ++k)
            values[9 + k] = particles.extra_of(i)[orientation + k];
      },
      [&](const unsigned int k, const double *values) {
        const unsigned int j          = impl->first_edge_ghost + k;
        particles.position[j]         = Vec3(values[0], values[1], values[2]);
        particles.velocity[j]         = Vec3(values[3], values[4], values[5]);
        particles.angular_velocity[j] = Vec3(values[6], values[7], values[8]);
        if (impl->bodies.clumps)
          for (unsigned int m = 0; m < 4; ++m)
            particles.extra_of(j)[orientation + m] = values[9 + m];
      });
  }

  void ParticleExchange::reinsert(const std::vector<ParticleRecord> &records,
                                  const std::vector<std::uint64_t> &ids, const PeriodicBox &box)
  {
    impl->light.clear();
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
    impl->light.clear();
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
