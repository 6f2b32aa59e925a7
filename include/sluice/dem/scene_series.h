#pragma once
// The files a DEM scene writes as it runs, on their schedules: the particle
// snapshots (.pvd/.vtu) with each mesh wall's surface beside them, the .csv
// time series (energies, contacts, wall forces, mesh torques and powers, and
// the wear and stream rows), and the particle dumps. Their counters are part
// of a checkpoint's scene records, so that a restarted run continues every
// series where it stopped.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/scene_records.h>
#include <sluice/core/series_files.h>
#include <sluice/dem/dem_system.h>
#include <sluice/dem/mesh_output.h>
#include <sluice/dem/particle_output.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace sluice
{
  class ParticleStream;
  class WearAndBreakage;

  /// Global sums and maxima of the quantities in the .csv time series.
  struct GlobalState
  {
    double translational_energy = 0., rotational_energy = 0.;
    double n_contacts = 0., n_wall_contacts = 0., max_overlap_ratio = 0.;
    unsigned long long n_particles = 0;
    std::vector<Vec3>  wall_forces;
    MeshWallLoads      mesh_loads;
  };

  /// Collective.
  GlobalState reduce_state(const DemSystem &dem, MPI_Comm comm);

  /// The fields of a scene's particle snapshots: the particles', or in a
  /// clump scene its members' with their bodies' (clump_output.h).
  ParticleFieldRegistry snapshot_fields(const DemSystem &dem);
  /// Collective: the scene's particle snapshot at 'time' (spheres, or members).
  void write_snapshot(ParticleOutput &vtu, const DemSystem &dem, double time);
  /// Collective: the scene's particle dump number 'index': the spheres' CSV,
  /// or a clump scene's bodies' and members' CSVs.
  void write_particle_dump(const DemSystem &dem, double time, const std::string &directory,
                           const std::string &base_name, unsigned int index);

  class SceneSeries
  {
  public:
    /// Opens the .csv files (the scene's, the wear's and the stream's) and
    /// restores the counters from a checkpoint's records.
    SceneSeries(const SceneParameters &p, const DemSystem &dem, const std::string &directory,
                bool restart, const SceneRecords &records, WearAndBreakage &wear,
                ParticleStream &stream);

    /// Collective: writes what is due at 'time' (all of it when 'force').
    void write(double time, bool force, const DemSystem &dem);
    /// The final state is always dumped (when the scene dumps at all).
    void dump_final(double time, const DemSystem &dem);
    /// Collective, when a run stops (RunStopped): one more entry of every
    /// series the scene writes, at 'time'; returns those files' names.
    std::vector<std::string> write_at_stop(double time, const DemSystem &dem);

    /// The counters and series indices, for a checkpoint.
    void add_records(SceneRecords &r, const DemSystem &dem) const;

    std::string  csv_name() const { return csv_path; }
    unsigned int n_snapshots() const { return vtu.n_written(); }
    unsigned int n_dumps() const { return dumps; }

  private:
    const SceneParameters  &p;
    const std::string       directory;
    WearAndBreakage        &wear;
    ParticleStream         &stream;
    ParticleOutput          vtu;
    std::vector<MeshSeries> mesh_vtu; // each mesh wall's surface, moving with it
    CsvSeries               csv;
    std::string             csv_path;
    double                  next_vtu, next_csv, next_dump, last_dump;
    unsigned int            dumps;
    void dump_particles(double time, const DemSystem &dem);
    void write_csv_row(double time, const DemSystem &dem);
  };
} // namespace sluice
