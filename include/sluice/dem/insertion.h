#pragma once
// Creating the initial particles. Every rank generates the same list from the
// seed, so insertion is reproducible and independent of the number of ranks; the
// particle handler then keeps the ones in each rank's cells.

#include <sluice/core/scene_parameters.h>

#include <vector>

namespace sluice
{
  /// All particles of the scene, in id order. Throws InputError when the region
  /// cannot hold the requested number of particles.
  std::vector<ParticleRecord> create_particles(const SceneParameters &parameters);
} // namespace sluice
