#pragma once
// A particle stream (the 'stream' subsection, doc/geometry.md): spheres
// inserted at a number or mass rate through an inlet region (a box or a
// disc) with a uniform size distribution and without overlap, removed at an
// outlet (a box or the half-space behind a plane) and counted per material
// type, and, with 'recycle', put back at the inlet as they leave (the seed's
// semi-periodic pump; a hopper held at its fill).
//
// Every 'interval' the stream finds the particles at the outlet and plans
// the next batch on every rank alike: the particles near the inlet are
// gathered from all ranks, positions are drawn from a generator seeded by the
// batch's number and kept where they overlap nothing, and the DEM replaces
// the particles at its next list update (DemSystem::schedule_replacement).
// A batch that finds no room carries the rest over, and the summary says how
// many were never placed.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/series_files.h>
#include <sluice/dem/dem_system.h>

#include <ostream>
#include <string>
#include <vector>

namespace sluice
{
  class ParticleStream
  {
  public:
    ParticleStream(const SceneParameters &p, const DemSystem &dem);

    bool active() const { return parameters.any(); }

    /// After each step: at each interval, the outlet and the next batch. Collective.
    void after_step(DemSystem &dem);

    /// '<base>_discharge.csv': the cumulative counts and masses at each call. Collective.
    void open_csv(const std::string &directory, const std::string &base_name, bool restart,
                  double time, MPI_Comm comm);
    void write_row(double time, const DemSystem &dem);

    /// 'stream: ...' (rank 0).
    void summary(std::ostream &out, double time) const;

    std::vector<double> state() const;
    void                set_state(const std::vector<double> &numbers);

  private:
    /// The batch's records, placed without overlap among the given spheres
    /// (x, y, z, r each) and each other; 'recycled' first, then 'n_new'.
    std::vector<ParticleRecord> place(const std::vector<ParticleRecord> &recycled,
                                      unsigned int n_new, const std::vector<double> &obstacles);
    bool at_outlet(const Vec3 &x) const;
    bool near_inlet(const Vec3 &x, double reach) const;

    StreamParameters parameters;
    std::vector<double> density;
    double              mean_mass = 0.;
    // A clump scene's bodies (null for spheres) and how they are drawn.
    const ClumpSystem     *clumps = nullptr;
    const ClumpParameters &clump_parameters;
    // State (checkpointed).
    double              next_time = 0., owed = 0.;
    unsigned long long  batch = 0, next_id = 0, inserted = 0, not_placed = 0, recycled = 0;
    std::vector<double> removed, removed_mass; // per material type
    CsvSeries           csv;
  };
} // namespace sluice
