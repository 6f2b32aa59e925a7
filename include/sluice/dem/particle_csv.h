#pragma once
// A plain-text dump of every particle, for Python or a spreadsheet: one row per
// particle, sorted by id, with id, type, radius, position, velocity, angular
// velocity and force (SI). Gathered on rank 0, which writes the file whole
// (through a temporary name), so a killed run never leaves half a dump.

#include <sluice/dem/particle_storage.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace sluice
{
  /// Collective: writes the owned particles of every rank to
  /// <directory>/<base_name>_state_<index, 5 digits>.csv.
  void write_particle_csv(const ParticleStorage &particles, double time,
                          const std::string &directory, const std::string &base_name,
                          unsigned int index, MPI_Comm comm);

  /// <directory>/<base_name>_<kind>_<index, 5 digits>.csv
  std::string particle_csv_path(const std::string &directory, const std::string &base_name,
                                unsigned int index, const std::string &kind = "state");

  /// Collective: gathers every rank's rows ('n_fields' doubles each, the id
  /// first) on rank 0, which writes them sorted by id under a '# time' line
  /// and the header; the first 'n_integer_fields' columns as integers.
  void write_rows_by_id(const std::vector<double> &rows, int n_fields, int n_integer_fields,
                        const std::string &header, double time, const std::string &path,
                        MPI_Comm comm);
} // namespace sluice
