#pragma once
// The DEM's state and its two per-step operations, shared by the pure-DEM
// scene and the coupled scenes: the particles (checked, inserted, distributed
// over ranks), the contact law chosen at set-up, the neighbour list with its
// Verlet skin, and the exchange that moves particles between ranks.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/contact_forces.h>
#include <sluice/dem/contact_properties.h>
#include <sluice/dem/neighbour_list.h>
#include <sluice/dem/particle_exchange.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/periodic_box.h>

#include <mpi.h>

#include <memory>
#include <vector>

namespace sluice
{
  class DemSystem
  {
  public:
    /// Checks the scene (particles, time step against the contact time,
    /// periodicity), inserts the particles and builds the lists. n_extra:
    /// per-particle doubles a coupled scene keeps (ParticleStorage::extra).
    /// Throws InputError before anything is written.
    DemSystem(const SceneParameters &parameters, MPI_Comm communicator, unsigned int n_extra = 0);

    /// After a drift: rebuilds the lists (moving particles between ranks) when
    /// a particle moved more than half the skin, else refreshes the ghosts.
    /// Stops the run (SimulationFailure, exit 5) when a position is not
    /// finite, a particle moved more than half the smallest radius in this step,
    /// or the last contact pass found an overlap above 'simulation/maximum
    /// overlap'.
    void update_neighbours();

    /// Contact forces and torques into particles.force/torque (overwritten).
    void compute_contacts();

    const SceneParameters &p;
    MPI_Comm               comm;
    int                    rank = 0, n_ranks = 1;

    ContactProperties        properties;
    double                   r_min = 0., r_max = 0., t_contact = 0., t_rayleigh = 0.;
    double                   t_damping = 0.; // the step that resolves the strongest dashpot
    double                   dt = 0., skin = 0.;
    // Half the smallest radius: a particle that moves further in one step can
    // pass through a contact unresolved.
    double                   max_step_displacement = 0.;
    bool                     friction = false;
    PeriodicBox              box;
    ContactForceKernel       contact_kernel;
    std::unique_ptr<ParticleExchange> exchange;
    ParticleStorage          particles;
    ContactHistoryMap        histories;
    NeighbourList            list;
    std::vector<Vec3>        wall_forces;
    ContactStatistics        stats;
    unsigned long long       n_inserted = 0, n_lost = 0;
    unsigned long long       step = 0; // calls of update_neighbours, one per DEM step

  private:
    [[noreturn]] void fail(double moved_2, double speed_2) const;
    void              report_lost(unsigned long long lost);
  };
} // namespace sluice
