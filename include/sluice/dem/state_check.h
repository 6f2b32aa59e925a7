#pragma once
// Input that cannot be simulated, and a run that has gone wrong, found and named.
//
// Before the first step: coincident particles, overlaps deeper than the stated
// fraction of the smaller radius, centres inside or behind a wall. Each is an
// InputError (exit 2) naming the particles. During the run the DEM tests three
// numbers it already has at every list update (largest displacement since the
// build, deepest overlap of the last contact pass, and whether any position is
// not finite); only when one is out of bounds are the functions below called
// to find the particle and say what probably went wrong (SimulationFailure,
// exit 5). All functions here are collective over the communicator and give
// every rank the same message.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/neighbour_list.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/dem/wall_set.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace sluice
{
  /// Throws InputError (on every rank) for coincident particles, a pair or wall
  /// overlap above 'max_overlap' times the smaller radius, or a centre on or
  /// behind a wall. The lists must have been built.
  void check_initial_state(const ParticleStorage &particles, const NeighbourList &list,
                           const WallSet &walls, const PeriodicBox &box,
                           double max_overlap, const std::string &file_name, MPI_Comm comm,
                           unsigned int member_stride = 0);

  /// Where the run stopped, for the messages.
  struct StepInfo
  {
    unsigned long long step = 0;
    double             time = 0., dt = 0., max_step_displacement = 0.;
    double             characteristic_velocity = 0.;
    unsigned int       member_stride = 0; // a clump scene's (clump_system.h), else 0
  };

  /// A position, velocity or force that is not finite: names the particle.
  [[noreturn]] void fail_non_finite(const ParticleStorage &particles, const StepInfo &where,
                                    MPI_Comm comm);

  /// A particle that moved further in one step than contacts can resolve.
  [[noreturn]] void fail_fast_particle(const ParticleStorage &particles, const StepInfo &where,
                                       MPI_Comm comm);

  /// An overlap above 'max_overlap' times the smaller radius.
  [[noreturn]] void fail_deep_overlap(const ParticleStorage &particles, const NeighbourList &list,
                                      const WallSet &walls, const PeriodicBox &box,
                                      double max_overlap, const StepInfo &where, MPI_Comm comm);
} // namespace sluice
