#pragma once
// The SPH fluid on several MPI ranks (doc/sph.md, "Several ranks").
//
// The box is cut into coarse cells at least one reach (2 h_max + skin) wide,
// a parallel::distributed::Triangulation whose cells p4est partitions among
// the ranks by their particles at the start, and again when the fluid has
// flowed away from that share or a smoothing length has grown past the
// cells (fit()). A rank owns the particles in its cells. At each rebuild of
// the pairs the owned particles move to the rank that owns their cell, and
// the ghost layer
// (dem/ghost_layer.h, the DEM's) sends a copy of every particle to the ranks
// that own a neighbour of its cell, across periodic edges and corners too.
// Between rebuilds the ghosts are refreshed field by field, at the points
// of the step where their owners have computed them (sph_solver.h).
//
// With one rank nothing is sent and the arrays are left as they are.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_particles.h>

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sluice
{
  class SphExchange
  {
  public:
    /// Partitions the box's cells (at least 'reach' wide) by the counts of
    /// 'all' particles in them.
    SphExchange(MPI_Comm communicator, const PeriodicBox &box, double reach,
                const SphParticles &all);
    ~SphExchange();

    /// More than one rank.
    bool active() const;
    /// The smallest width of the cells along an axis cut into several: the
    /// farthest a pair's partners may be apart.
    double reach() const;

    /// Collective, at a rebuild of the pairs, before redistribute(), with
    /// the owned particles of 'P' and what each costs a step ('cost'; empty:
    /// 4 for a fluid particle, 1 for a wall particle). Cuts the box into
    /// wider cells if the pairs now reach 'needed_reach' beyond reach(); or,
    /// when the busiest rank's load is more than 1.15 times the mean (not
    /// within 20 calls of the last time), shares the cells out again if that
    /// takes a tenth off it. Returns whether the cells' owners changed; the
    /// particles move at the next redistribute().
    bool fit(const SphParticles &P, double needed_reach,
             const std::vector<unsigned int> &cost = {});
    /// How often fit() changed the owners.
    unsigned int n_repartitions() const;
    /// The cells and their owners with fit()'s counters, for a checkpoint
    /// (empty on one rank).
    std::vector<std::int64_t> cells() const;
    /// Collective. Takes the cells of a checkpoint's cells() (nothing for an
    /// empty record); written on another number of ranks, shares them out
    /// again by the loads of 'all' (every rank's copy of all particles).
    /// Throws BinaryFormatError for a record that does not fit.
    void restore_cells(const std::vector<std::int64_t> &record, const SphParticles &all);

    /// Per-particle arrays of the owned particles (a step's temporaries)
    /// that move with them.
    struct Attachments
    {
      std::vector<std::vector<Vec3> *>   vectors;
      std::vector<std::vector<double> *> scalars;
    };

    /// Keeps the particles of 'P' (every rank's copy of all of them) that
    /// lie in this rank's cells, in their order, and no ghosts.
    void keep_own(SphParticles &P) const;

    /// Collective. Keeps the owned particles of 'P' that lie in this rank's
    /// cells and receives those of other ranks that lie in them, with their
    /// attachments; then appends the ghosts.
    void redistribute(SphParticles &P, const Attachments &attached = {});

    /// Collective. The ghosts' position, velocity, density and porosity.
    void refresh_motion(SphParticles &P);
    /// Collective. The ghosts' density.
    void refresh_density(SphParticles &P);
    /// Collective. The ghosts' mass, density and porosity (a coupled scene's
    /// solids taken in: sph_backend.h).
    void refresh_fluid_fractions(SphParticles &P);
    /// Collective. The ghosts' Omega, pressure, density and the viscous
    /// velocity 'no_slip' (per particle, owned and ghost).
    void refresh_rates_inputs(SphParticles &P, std::vector<Vec3> &no_slip);
    /// Collective. Extends an owned-sized array to the ghosts' values.
    void extend(const SphParticles &P, std::vector<Vec3> &values);

    /// Collective. The ranks, their cells and the fewest and most particles
    /// a rank owns, for the scene's header.
    std::string describe(const SphParticles &P) const;

    /// Collective. Every rank's owned particles, on every rank, by id.
    SphParticles gather_all(const SphParticles &P, std::vector<Vec3> *attached = nullptr) const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> impl;
  };

  /// The lowest rank's message among those that have one ("" for none), on
  /// every rank.
  std::string first_message_over_ranks(MPI_Comm communicator, const std::string &message);

  /// Collective: 'check' on every rank; if it throws SimulationFailure on
  /// any, every rank throws the lowest such rank's message.
  template <typename Check>
  void check_on_all_ranks(MPI_Comm communicator, const Check &check)
  {
    std::string message;
    try
      {
        check();
      }
    catch (const SimulationFailure &e)
      {
        message = e.what();
        if (message.empty())
          message = "a simulation failure";
      }
    const std::string first = first_message_over_ranks(communicator, message);
    if (!first.empty())
      throw SimulationFailure(first);
  }
} // namespace sluice
