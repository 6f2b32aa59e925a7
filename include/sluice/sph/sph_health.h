#pragma once
// The SPH fluid's health after a step: every fluid particle's state finite
// and inside the wall faces. A fault stops the run (SimulationFailure, exit
// 5) with a message naming the particle, the time and the entry to change.

#include <sluice/sph/sph_particles.h>
#include <sluice/sph/sph_setup.h>

namespace sluice
{
  void check_sph_health(const SphParticles &P, const SphSetup &setup, double time);

  /// Stops the run when a fluid particle has come within dx/4 of a solid
  /// wall ('sph/solid walls'): half-way to crossing it, where the contact no
  /// longer holds.
  void check_solid_wall_overlap(const SphSolidWalls &walls, double spacing, double time);
} // namespace sluice
