#pragma once
// A plain-text dump of every particle, for Python or a spreadsheet: one row per
// particle, sorted by id, with id, type, radius, position, velocity, angular
// velocity and force (SI). Gathered on rank 0, which writes the file whole
// (through a temporary name), so a killed run never leaves half a dump.

#include <sluice/dem/particle_storage.h>

#include <mpi.h>

#include <string>

namespace sluice
{
  /// Collective: writes the owned particles of every rank to
  /// <directory>/<base_name>_state_<index, 5 digits>.csv.
  void write_particle_csv(const ParticleStorage &particles, double time,
                          const std::string &directory, const std::string &base_name,
                          unsigned int index, MPI_Comm comm);
} // namespace sluice
