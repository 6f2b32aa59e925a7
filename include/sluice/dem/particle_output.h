#pragma once
// ParaView output of the particles: one .vtu piece per rank, a .pvtu that joins
// them, and a .pvd that lists every snapshot with its time. Binary (base64) data
// keeps the files small; fields: velocity, angular velocity, radius, type, force,
// coordination number, id, and the scene's per-particle fields marked for
// output (particle_fields.h; a coupled scene's fluid velocity and drag
// coefficient).

#include <sluice/core/series_files.h>
#include <sluice/dem/particle_fields.h>
#include <sluice/dem/particle_storage.h>

#include <string>
#include <utility>
#include <vector>

namespace sluice
{
  class ParticleOutput
  {
  public:
    ParticleOutput(const std::string &directory, const std::string &base_name,
                   unsigned int rank, unsigned int n_ranks,
                   const ParticleFieldRegistry &fields = ParticleFieldRegistry());

    /// Writes snapshot number 'index' at 'time' (every rank writes its piece).
    void write(const ParticleStorage &particles, double time);
    /// Writes the pieces and the .pvtu of snapshot 'index' without adding it
    /// to the series; returns the .pvtu's name relative to the directory.
    std::string write_files(const ParticleStorage &particles, unsigned int index) const;

    unsigned int n_written() const { return series.size(); }
    /// The series index, for a checkpoint to save and a restart to restore.
    PvdSeries       &index() { return series; }
    const PvdSeries &index() const { return series; }

  private:
    std::string                directory, base_name;
    unsigned int               rank, n_ranks;
    std::vector<ParticleField> fields; // those written
    PvdSeries                  series;
  };
} // namespace sluice
