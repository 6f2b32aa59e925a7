#pragma once
// An imported flow field in time: one snapshot (a .vtu or .pvtu, steady), or
// a .pvd series interpolated linearly between the two snapshots around t,
//   f(x, t) = (1 - a) f_k(x) + a f_k+1(x),  a = (t - t_k) / (t_k+1 - t_k),
// optionally periodic (t taken modulo the period, the last snapshot blending
// into the first). Only the two snapshots in use are held; a snapshot on the
// grid of the one before shares its geometry and search tree, so a particle
// is located once for both.

#include <sluice/core/imported_field_parameters.h>
#include <sluice/coupling/imported_field.h>

#include <iosfwd>
#include <memory>
#include <vector>

namespace sluice
{
  class ImportedFieldSeries
  {
  public:
    /// Reads the first snapshots. Throws InputError naming the file.
    ImportedFieldSeries(const ImportedFieldParameters &parameters, const std::string &scene);

    /// Chooses (loading when needed) the snapshots around t; per step, once.
    void set_time(double t);

    /// The fluid at x (at the time set), 'hint' the particle's last cell
    /// (updated). Not found outside the grid.
    ParticleFluidSample sample(const Vec3 &x, long &hint) const;

    std::size_t n_snapshots() const { return snapshots.size(); }
    /// Points and cells of the grid in use.
    std::size_t n_points() const;
    std::size_t n_cells() const;
    double      first_time() const { return snapshots.front().time; }
    double      last_time() const { return snapshots.back().time; }

  private:
    ImportedFieldArrays      arrays;
    double                   period = 0.;
    std::vector<PvdSnapshot> snapshots;
    // The snapshots in use (indices into 'snapshots') and the weight of 'next'.
    std::size_t                    index_a = 0, index_b = 0;
    double                         weight_b = 0.;
    std::shared_ptr<ImportedField> a, b;
    std::shared_ptr<ImportedField> load(std::size_t index, const ImportedField *beside) const;
  };
} // namespace sluice
