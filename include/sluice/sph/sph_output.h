#pragma once
// ParaView output of an SPH fluid's particles (dem/particle_output.h's
// .pvd/.pvtu/.vtu): velocity, force m a, density rho_hat, pressure,
// smoothing length h and fluid fraction eps per particle, walls as type 1,
// radius dx / 2 (for glyphs).

#include <sluice/dem/particle_output.h>
#include <sluice/sph/sph_particles.h>

#include <string>

namespace sluice
{
  class SphOutput
  {
  public:
    SphOutput(const std::string &directory, const std::string &base);

    /// Adds a snapshot at 'time' to the series.
    void write(const SphParticles &P, double dx, double time);
    /// Writes snapshot 'index' outside the series; returns its .pvtu's name.
    std::string write_files(const SphParticles &P, double dx, unsigned int index) const;

    ParticleOutput vtu;
  };
} // namespace sluice
