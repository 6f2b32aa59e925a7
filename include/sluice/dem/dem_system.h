#pragma once
// The DEM's state and its time step, shared by the pure-DEM scene and the
// coupled scenes: the particles (checked, inserted, distributed over ranks),
// the walls, the contact law chosen at set-up, the neighbour list with its
// Verlet skin, and the exchange that moves particles between ranks.
//
// One step (advance) is velocity Verlet (Allen & Tildesley): half kick with
// the forces of the previous step, drift, walls moved, new contact forces,
// second half kick. Velocity-dependent forces (dashpots, tangential slip) see
// the half-step velocities, as in LIGGGHTS' nve/sphere. What a scene adds to
// the particles' motion comes in as a template argument, so a scene pays for
// nothing it does not use:
//   - the kick: gravity alone (GravityKick), or a coupled scene's fluid forces
//     with the drag integrated exactly (coupling/fluid_kick.h);
//   - a constraint applied after each kick (NoConstraint by default).
// Wall motion is the wall set's (walls.move, every step), and contact
// observers (impact energy at a contact's start, shear work at wall contacts)
// attach with observe(): the kernel chosen then records, others do not.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/stage_clock.h>
#include <sluice/dem/clump_system.h>
#include <sluice/dem/contact_forces.h>
#include <sluice/dem/contact_properties.h>
#include <sluice/dem/mesh_contact_forces.h>
#include <sluice/dem/neighbour_list.h>
#include <sluice/dem/particle_exchange.h>
#include <sluice/dem/particle_fields.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/dem/velocity_verlet.h>
#include <sluice/dem/wall_set.h>

#include <mpi.h>

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace sluice
{
  /// The kick of a pure-DEM scene: contact forces and gravity.
  struct GravityKick
  {
    Vec3 gravity;
    void kick(ParticleStorage &P, const double h) const { half_kick(P, h, gravity); }
  };

  /// Whether a kick's forces depend on the positions and are refreshed after
  /// the drift, as the contact forces are (refresh(P, t); an imported flow
  /// field's, coupling/imported_field_scene.cc): the second half kick then
  /// sees the forces at the new positions, which keeps Verlet second order.
  template <typename Kick, typename = void>
  struct RefreshesAfterDrift : std::false_type
  {};
  template <typename Kick>
  struct RefreshesAfterDrift<Kick, std::void_t<decltype(std::declval<const Kick &>().refresh(
                                     std::declval<ParticleStorage &>(), 0.))>> : std::true_type
  {};

  /// No constraint: every particle moves freely.
  struct NoConstraint
  {
    void apply(ParticleStorage &) const {}
  };

  class DemSystem
  {
  public:
    /// Checks the scene (particles, time step against the contact time,
    /// periodicity), inserts the particles and builds the lists. fields: the
    /// per-particle fields a scene adds (particle_fields.h; a coupled scene's
    /// coupling data), kept in ParticleStorage::extra. Throws InputError
    /// before anything is written.
    DemSystem(const SceneParameters &parameters, MPI_Comm communicator,
              const ParticleFieldRegistry &fields = ParticleFieldRegistry());

    /// One velocity-Verlet step of dt.
    template <typename Kick, typename Constraint = NoConstraint>
    void advance(const Kick &kick, const Constraint &constraint = Constraint());

    /// One step of a clump scene (clump_system.h): the bodies' half kick and
    /// drift, their members moved with them, the contact passes on the
    /// members, their loads summed onto the bodies, the second half kick.
    /// The kick moves the bodies' centroids as it moves spheres (its change
    /// of their angular velocity is replaced by the rotation's kick).
    template <typename Kick, typename Constraint = NoConstraint>
    void advance_clumps(const Kick &kick, const Constraint &constraint = Constraint());

    /// What the particle handler carries: the bodies in a clump scene, else
    /// the particles themselves.
    ParticleStorage       &handler_particles() { return clumps ? clumps->bodies : particles; }
    const ParticleStorage &handler_particles() const
    {
      return clumps ? clumps->bodies : particles;
    }
    /// After the exchange refilled handler_particles(): in a clump scene the
    /// bodies' mass properties and their members in 'particles'.
    void refresh_members();

    /// After a drift: rebuilds the lists (moving particles between ranks) when
    /// a particle moved more than half the skin, else refreshes the ghosts.
    /// Stops the run (SimulationFailure, exit 5) when a position is not
    /// finite, a particle moved more than half the smallest radius in this step,
    /// or the last contact pass found an overlap above 'simulation/maximum
    /// overlap'. A wall that moved more than half the skin also rebuilds.
    void update_neighbours();

    /// Contact forces and torques into particles.force/torque (overwritten).
    void compute_contacts();

    /// At the next step's list update (a rebuild, after the drift): removes
    /// the particles with these ids and inserts these records with theirs
    /// (every rank passes all of them; particle_stream.h). Collective.
    void schedule_replacement(std::vector<std::uint64_t> remove_ids,
                              std::vector<ParticleRecord> records,
                              std::vector<std::uint64_t>  ids);

    /// Builds the neighbour list from the current positions (histories from
    /// the map) and marks the walls' positions.
    void build_list();

    /// Attaches a contact observer (contact_observer.h: impact energies, wall
    /// shear work), or detaches it with null. From the next contact pass on
    /// the kernel is the one that records; without one nothing is recorded
    /// and nothing is paid. The observer's sums are part of a checkpoint.
    void             observe(ContactObserver *observer);
    ContactObserver *observer() const { return contact_observer; }

    const SceneParameters      &p;
    MPI_Comm                    comm;
    const ParticleFieldRegistry fields;
    int                    rank = 0, n_ranks = 1;

    ContactProperties        properties;
    double                   r_min = 0., r_max = 0., t_contact = 0., t_rayleigh = 0.;
    double                   body_radius_max = 0.; // a clump's largest bounding radius
    double                   t_damping = 0.; // the step that resolves the strongest dashpot
    double                   dt = 0., skin = 0.;
    // Half the smallest radius: a particle that moves further in one step can
    // pass through a contact unresolved.
    double                   max_step_displacement = 0.;
    bool                     friction = false;
    PeriodicBox              box;
    WallSet                  walls;
    ContactForceKernel       contact_kernel;
    MeshContactKernel        mesh_kernel = nullptr; // a scene with mesh walls only
    std::unique_ptr<ParticleExchange> exchange;
    // A clump scene's bodies (null for spheres); 'particles' then holds their
    // members, on which the contact passes run.
    std::unique_ptr<ClumpSystem> clumps;
    ParticleStorage          particles;
    ContactHistoryMap        histories;
    NeighbourList            list;
    std::vector<Vec3>        wall_forces; // planes, then meshes (wall_set.h)
    MeshWallLoads            mesh_loads;  // the meshes' torques and powers
    ContactStatistics        stats;
    unsigned long long       n_inserted = 0, n_lost = 0;
    // By a stream since the start (schedule_replacement()), over all ranks.
    unsigned long long       n_added = 0, n_removed = 0;
    unsigned long long       step = 0; // steps taken
    /// Where the steps' time goes (the 'cost:' line of a DEM scene); the
    /// scene starts it when its time loop starts.
    struct Stage
    {
      enum : unsigned int { contacts, histories, migrate, fill, list, ghosts, rest };
    };
    StageClock clock{{"contacts", "histories", "migrate", "fill", "list", "ghosts", "other"}};
    double                   time() const { return step * dt; }

  private:
    ContactObserver  *contact_observer = nullptr;
    // A scheduled replacement (schedule_replacement()).
    std::vector<std::uint64_t>  remove_ids, add_ids;
    std::vector<ParticleRecord> add_records;
    bool                        replacement_due = false;
    /// The contact passes for the scene's law, walls and observer.
    void              select_kernels();
    [[noreturn]] void fail(double moved_2, double speed_2) const;
    void              report_lost(unsigned long long lost);
  };

  template <typename Kick, typename Constraint>
  void DemSystem::advance(const Kick &kick, const Constraint &constraint)
  {
    const double h = 0.5 * dt;
    kick.kick(particles, h);
    constraint.apply(particles);
    drift(particles, dt);
    walls.move(time(), dt);
    ++step;
    update_neighbours();
    compute_contacts();
    if constexpr (RefreshesAfterDrift<Kick>::value)
      kick.refresh(particles, time());
    kick.kick(particles, h);
    constraint.apply(particles);
    // The step's contact work with the velocities at its end (contact_observer.h).
    if (contact_observer)
      contact_observer->settle(particles.velocity.data(), particles.angular_velocity.data(),
                               particles.type.data(), dt);
    clock.lap(Stage::rest);
  }
  template <typename Kick, typename Constraint>
  void DemSystem::advance_clumps(const Kick &kick, const Constraint &constraint)
  {
    ParticleStorage &bodies = clumps->bodies;
    const double     h      = 0.5 * dt;
    kick.kick(bodies, h);
    clumps->kick_rotation(h);
    constraint.apply(bodies);
    clumps->drift(dt);
    clumps->move_members(particles);
    walls.move(time(), dt);
    ++step;
    update_neighbours();
    compute_contacts();
    clumps->gather(particles);
    if constexpr (RefreshesAfterDrift<Kick>::value)
      kick.refresh(bodies, time());
    kick.kick(bodies, h);
    clumps->kick_rotation(h);
    constraint.apply(bodies);
    // The members' velocities at the step's end, for the observer and output.
    clumps->update_member_velocities(particles);
    if (contact_observer)
      contact_observer->settle(particles.velocity.data(), particles.angular_velocity.data(),
                               particles.type.data(), dt);
    clock.lap(Stage::rest);
  }
} // namespace sluice
