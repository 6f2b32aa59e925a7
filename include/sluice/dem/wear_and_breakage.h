#pragma once
// What a DEM scene with 'wear and breakage/collect' records, and writes
// (doc/geometry.md): a contact observer attached from the start time, the
// particles' impact energies and the spectra (impact_statistics.h), and per
// mesh triangle the cumulative impact and shear energy and the wear depth
// (Gao & Sun Eq. 12, or Archard's law). A scene that does not collect builds
// none of it and its kernels do not record.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/series_files.h>
#include <sluice/dem/contact_observer.h>
#include <sluice/dem/dem_system.h>
#include <sluice/dem/energy_balance.h>
#include <sluice/dem/impact_statistics.h>
#include <sluice/dem/mesh_output.h>
#include <sluice/dem/particle_fields.h>

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace sluice
{
  class WearAndBreakage
  {
  public:
    /// Declares the particle field 'impact_energy' [J] (cumulative normal
    /// impact energy; migrates, written to the snapshots, checkpointed), if the
    /// scene collects. Call before the DemSystem is made.
    static void declare_fields(const SceneParameters &p, ParticleFieldRegistry &fields);

    /// Attaches the observer to the DEM (so that a restart restores its sums).
    WearAndBreakage(const SceneParameters &p, DemSystem &dem);

    bool active() const { return observer_ != nullptr; }

    /// Observes from the start time on (detaches before it): call after a
    /// restart's load and after every step.
    void attach_when_due(DemSystem &dem);
    /// Takes this step's impacts and books the step's energy.
    void after_step(DemSystem &dem);

    /// '<base>_impacts.csv': one row per material type at each call. Collective.
    void open_csv(const std::string &directory, const std::string &base_name, bool restart,
                  double time, MPI_Comm comm);
    void write_rows(double time, const ParticleStorage &particles, MPI_Comm comm);

    /// Per mesh wall: its triangles' impact_energy [J], shear_energy [J] and
    /// wear_depth [m], summed over all ranks. Collective.
    std::vector<std::vector<TriangleField>> mesh_fields(const WallSet &walls, MPI_Comm comm) const;

    /// The summary lines ('wear:' per mesh, 'breakage:' per type) on rank 0
    /// and the spectra file. Collective.
    void finish(std::ostream &out, const DemSystem &dem, const std::string &directory,
                const std::string &base_name);

    /// The statistics' state summed over the ranks, for the scene records
    /// (collective; the observer's sums are the DEM checkpoint's), and back:
    /// rank 0 takes the sums, the others start from zero.
    std::vector<double> state(MPI_Comm comm) const;
    bool                set_state(const std::vector<double> &numbers, MPI_Comm comm);

  private:
    WearParameters                    parameters;
    EnergyBalance                     balance;
    std::unique_ptr<ContactObserver>  observer_;
    std::unique_ptr<ImpactStatistics> impacts;
    CsvSeries                         csv;
  };
} // namespace sluice
