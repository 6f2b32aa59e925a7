#pragma once
// The particles' home between neighbour-list rebuilds and their MPI transport:
// a dealii::Particles::ParticleHandler on a parallel::distributed::Triangulation
// (p4est) that covers the domain with cells no smaller than the interaction
// range. At a rebuild the DEM hands its state back, the handler moves particles
// to the rank that owns their cell, and the ghost layer (ghost_layer.h) sends
// copies of the particles next to other ranks' cells; every step it refreshes
// the ghosts. The contact loop itself runs on the DEM's contiguous arrays
// (DESIGN.md §4).

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/neighbour_list.h>
#include <sluice/dem/particle_fields.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/periodic_box.h>

#include <mpi.h>

#include <memory>
#include <vector>

namespace sluice
{
  /// In a clump scene the handler's particles are the bodies (clump_system.h):
  /// ghosts then carry the scene's fields (a body's orientation among them,
  /// which the per-step refresh sends too), and a contact history, keyed by
  /// member ids (body id * member_stride + member), follows the body.
  struct BodyTransport
  {
    bool         clumps        = false;
    unsigned int member_stride = 1;
  };

  /// The per-particle fields of a clump body (ClumpSystem declares them; the
  /// exchange sets the last three at insertion from the ParticleRecord).
  namespace clump_fields
  {
    inline constexpr const char *momentum    = "clump_momentum";    // 3: L, body frame
    inline constexpr const char *orientation = "clump_orientation"; // 4: w, x, y, z
    inline constexpr const char *shape       = "clump_template";    // 1
    inline constexpr const char *scale       = "clump_scale";       // 1
  } // namespace clump_fields

  class ParticleExchange
  {
  public:
    /// carry_histories: a particle that changes rank finds the tangential
    /// histories of its contacts on its new rank (false when there is one
    /// rank or no friction). fields: the scene's per-particle fields
    /// (ParticleStorage::extra); those that migrate travel with a particle as
    /// handler properties, the others start at zero on its new rank (none in
    /// a pure-DEM scene).
    ParticleExchange(MPI_Comm communicator, const PeriodicBox &box, double interaction_range,
                     unsigned long long n_particles, bool carry_histories,
                     const ParticleFieldRegistry &fields, BodyTransport bodies = {});
    ~ParticleExchange();

    /// Keeps the records whose position lies in a locally owned cell; the id of a
    /// particle is its index in the list. Throws InputError for a particle outside
    /// the domain.
    void insert(const std::vector<ParticleRecord> &records, const SceneParameters &parameters);

    /// Writes the local particles' state into the handler, moves particles
    /// across ranks (repartitioning the cells when the particle load is out of
    /// balance), fetches the histories of the arrivals' contacts from their
    /// previous owners, exchanges ghosts. Returns the number of particles that
    /// left the domain (summed over ranks).
    unsigned long long migrate(const ParticleStorage &particles, const ContactHistoryMap &histories,
                               const PeriodicBox &box);

    /// Fills the arrays: owned particles first, then ghosts; adds the histories
    /// of the migrated particles' contacts to the map (where this rank has
    /// none of its own for the pair).
    void fill_storage(ParticleStorage &particles, ContactHistoryMap &histories,
                      const std::vector<double> &densities) const;

    /// Sends the owned particles' position and velocities to the ranks that hold
    /// ghost copies of them, and reads the ghosts back.
    void update_ghosts(ParticleStorage &particles);

    /// The particle with the lowest id among those the last migrate() lost,
    /// with its position outside the domain (the same on every rank).
    struct Loss
    {
      std::uint64_t id = 0;
      Vec3          position;
    };
    const Loss &first_loss() const { return first_loss_; }

    /// Collective. Writes the cells, their partition and the particles as the
    /// handler holds them (files 'path', 'path_fixed.data', ...), with the
    /// load-balance counters, for a checkpoint.
    void save(const std::string &path) const;
    /// Collective. Replaces the cells and particles by those save() wrote and
    /// exchanges ghosts. With the owner of each coarse cell at the save (from
    /// cell_owners()) and as many ranks, the partition is the saved one, so
    /// fill_storage() gives the arrays in the saved order.
    void load(const std::string &path, const std::vector<int> &owners);
    /// Replaces all particles by these (each rank passes all of them and keeps
    /// those in its cells), with the given ids: a restart on another number of
    /// ranks, whose handler layout differs from the saved one.
    void reinsert(const std::vector<ParticleRecord> &records,
                  const std::vector<std::uint64_t> &ids, const PeriodicBox &box);
    /// Collective, after migrate(): removes the particles with the given ids
    /// (every rank passes all of them) and inserts the records with their ids
    /// where their cells are owned (every rank passes all of them); then the
    /// ghosts. A stream's outlet and inlet (particle_stream.h).
    void replace(const std::vector<std::uint64_t> &remove_ids,
                 const std::vector<ParticleRecord> &records,
                 const std::vector<std::uint64_t> &ids, const PeriodicBox &box);
    /// Collective. The rank that owns each coarse cell, by cell index.
    std::vector<int> cell_owners() const;
    /// The load-balance counters, which decide when the next repartition
    /// happens: saved and restored with a checkpoint.
    std::vector<unsigned int> counters() const;
    void                      set_counters(const std::vector<unsigned int> &c);

    unsigned long long n_global_particles() const;
    /// How often the cells were repartitioned to balance the particle load.
    unsigned int       n_repartitions() const { return n_repartitions_; }
    unsigned int       n_cells_global() const;
    unsigned int       n_ranks() const;

  private:
    /// The busiest rank's particle count if the cells were repartitioned now.
    double predicted_busiest_after_repartition() const;

    unsigned int n_repartitions_ = 0;
    unsigned int builds_since_repartition_ = 1000; // the first build may balance
    Loss         first_loss_;
    struct Implementation;
    std::unique_ptr<Implementation> impl;
  };
} // namespace sluice
