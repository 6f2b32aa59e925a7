// An imported flow field in time (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/coupling/imported_field_series.h>

#include <cmath>
#include <filesystem>

namespace sluice
{
  ImportedFieldSeries::ImportedFieldSeries(const ImportedFieldParameters &p,
                                           const std::string             &scene)
    : period(p.period)
  {
    arrays.velocity       = p.velocity_array;
    arrays.pressure       = p.pressure_array;
    arrays.porosity       = p.porosity_array;
    arrays.length_scale   = p.length_scale;
    arrays.pressure_scale = p.pressure_scale;
    arrays.need_pressure  = p.pressure_gradient_force;
    if (std::filesystem::path(p.file).extension() == ".pvd")
      snapshots = read_pvd(p.file);
    else
      snapshots.push_back({0., {p.file}});
    const double span = snapshots.back().time - snapshots.front().time;
    if (period > 0. && period < span)
      throw InputError("error in '" + scene + "': entry 'imported field/period' = " +
                       std::to_string(period) + " s is shorter than the time series '" +
                       p.file + "' (" + std::to_string(span) + " s from first to last frame)");
    if (period > 0. && snapshots.size() < 2)
      throw InputError("error in '" + scene + "': entry 'imported field/period' is set, but '" +
                       p.file + "' is a single snapshot");
    a = load(0, nullptr);
    b = a;
    set_time(snapshots.front().time);
  }

  std::shared_ptr<ImportedField> ImportedFieldSeries::load(const std::size_t    index,
                                                           const ImportedField *beside) const
  {
    return std::make_shared<ImportedField>(snapshots[index].files, arrays,
                                           beside ? beside->geometry() : nullptr);
  }

  void ImportedFieldSeries::set_time(double t)
  {
    const std::size_t n  = snapshots.size();
    const double      t0 = snapshots.front().time;
    std::size_t       ia = 0, ib = 0;
    double            w  = 0.;
    if (period > 0.)
      {
        t = t0 + (t - t0) - period * std::floor((t - t0) / period);
        ia = n - 1, ib = 0; // between the last frame and the first one period on
        for (std::size_t k = 0; k + 1 < n; ++k)
          if (t < snapshots[k + 1].time)
            {
              ia = k, ib = k + 1;
              break;
            }
        const double tb = ib == 0 ? t0 + period : snapshots[ib].time;
        w = tb > snapshots[ia].time ? (t - snapshots[ia].time) / (tb - snapshots[ia].time) : 0.;
      }
    else if (t >= snapshots.back().time)
      ia = ib = n - 1; // held at the last frame
    else if (t > t0)
      {
        while (ia + 1 < n && snapshots[ia + 1].time <= t)
          ++ia;
        ib = ia + 1;
        w  = (t - snapshots[ia].time) / (snapshots[ib].time - snapshots[ia].time);
      }
    // Load only what changed; a frame already held is reused.
    if (ia != index_a || !a)
      a = ia == index_b && b ? b : load(ia, b.get());
    if (ib != index_b || !b || ib == ia)
      b = ib == ia ? a : load(ib, a.get());
    index_a = ia, index_b = ib, weight_b = w;
  }

  ParticleFluidSample ImportedFieldSeries::sample(const Vec3 &x, long &hint) const
  {
    ParticleFluidSample s;
    const CellPoint     in_a = a->geometry()->locate(x, hint);
    if (in_a.cell < 0)
      return s;
    hint = in_a.cell;
    a->evaluate(in_a, s);
    if (b == a || weight_b == 0.)
      return s;
    const CellPoint in_b =
      b->geometry() == a->geometry() ? in_a : b->geometry()->locate(x, -1);
    if (in_b.cell < 0)
      return ParticleFluidSample(); // in one frame's grid only
    ParticleFluidSample s_b;
    b->evaluate(in_b, s_b);
    const double w = weight_b;
    s.velocity          = (1. - w) * s.velocity + w * s_b.velocity;
    s.pressure_gradient = (1. - w) * s.pressure_gradient + w * s_b.pressure_gradient;
    s.porosity          = (1. - w) * s.porosity + w * s_b.porosity;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        s.velocity_gradient[i][j] =
          (1. - w) * s.velocity_gradient[i][j] + w * s_b.velocity_gradient[i][j];
    return s;
  }

  std::size_t ImportedFieldSeries::n_points() const { return a->geometry()->n_points(); }
  std::size_t ImportedFieldSeries::n_cells() const { return a->geometry()->n_cells(); }
} // namespace sluice
