#pragma once
// Measurements that compare a scene with its analytical reference: the Hertz
// impact, restitution, a sphere sliding into rolling, and a settled bed. Each ends
// in one line 'result: <case> value=.. reference=.. error=.. wall_s=..'.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/contact_properties.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/wall_set.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace sluice
{
  struct ValidationResult
  {
    std::string              name;
    double                   value = 0., reference = 0., error = 0.;
    std::vector<std::string> checks; // further 'check:' lines
    std::string              failure; // a further bound missed: exit 3 with this message
  };

  class ValidationProbe
  {
  public:
    /// The walls are read as they are at each observation (they may move).
    ValidationProbe(const SceneParameters &parameters, const ContactProperties &properties,
                    const WallSet &walls, MPI_Comm communicator);

    /// Called after every step (and once at the start) with the current state.
    void observe(double time, double dt, const ParticleStorage &particles);

    /// Called at the end; collective over the ranks.
    ValidationResult finish(const ParticleStorage &particles, unsigned long long n_lost,
                            unsigned long long n_inserted);

    bool active() const { return parameters.validation != ValidationCase::none; }

    /// What the probe has measured so far, for a checkpoint, and back (an
    /// empty list leaves the probe as constructed).
    std::vector<double> state() const;
    void                set_state(const std::vector<double> &numbers);

  private:
    struct TrackedState
    {
      Vec3   x[2], v[2], w[2];
      double r[2]    = {0., 0.};
      double mass[2] = {0., 0.};
      int    type[2] = {0, 0};
    };
    TrackedState gather_tracked(const ParticleStorage &particles) const;
    /// Overlap and unit normal (from partner to particle 0) of the tracked
    /// contact; the nearest wall when particle 0 is alone.
    double overlap(const TrackedState &s, Vec3 &normal, unsigned int &wall) const;
    /// The material type of particle 0's partner.
    unsigned int partner_type(const TrackedState &s) const;

    const SceneParameters   &parameters;
    const ContactProperties &properties;
    const WallSet           &walls;
    MPI_Comm                 communicator;
    unsigned int             last_wall = 0;
    bool                     two_particles = false;

    // Contact event of the tracked pair (or particle 0 and its wall).
    bool   started = false, ended = false, have_previous = false;
    double previous_overlap = 0., previous_time = 0., previous_normal_speed = 0.;
    double t_start = 0., t_end = 0., max_overlap = 0.;
    double impact_speed = 0., rebound_speed = 0.;
    double initial_tangential_speed = -1.;
    Vec3   last_velocity, last_angular_velocity, contact_normal;
    double last_radius = 0., last_overlap = 0.;
  };
} // namespace sluice
