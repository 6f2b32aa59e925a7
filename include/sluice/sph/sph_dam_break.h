#pragma once
// The dam break of Martin & Moyce (1952), Phil. Trans. R. Soc. A 244, 312,
// Part IV (validation = dam_break; doc/sph.md): a column of water of width a
// and height n^2 a = 2 a stands against a wall on a floor and collapses when
// its other side is released. They measured the surge front's distance Z a
// from the wall against T = n t sqrt(g / a) = t sqrt(2 g / a); their points
// for a = 2.25 in (Fig. 3, as digitised in PySPH's dam-break data) are the
// reference. The scene's front is the furthest fluid particle's x plus dx/2
// (the edge of the volume it stands for: Z = 1 at t = 0).

#include <sluice/core/scene_parameters.h>
#include <sluice/core/scene_records.h>
#include <sluice/sph/sph_particles.h>
#include <sluice/sph/sph_validation.h>

#include <vector>

namespace sluice
{
  class DamBreakProbe
  {
  public:
    /// Throws InputError naming the entry when the scene is not the
    /// experiment: gravity along -z, walls on x- and z-, the column in the
    /// corner they make, twice as high as wide.
    DamBreakProbe(const SceneParameters &p, double end_time);

    /// The front Z = x_front / a now.
    double front(const SphParticles &P) const;
    /// A reference time falls in (time - dt, time].
    bool due(double time, double dt) const
    {
      const std::size_t k = measured_Z.size();
      return k < reference_T.size() && time > reference_T[k] * time_scale - 0.5 * dt;
    }
    /// Measures the front when due().
    void measure_if_due(const SphParticles &P, double time, double dt);
    /// The largest relative deviation of the front from the measurements.
    SphResult result(int precision) const;

    void save(SceneRecords &records) const;
    void restore(const SceneRecords &records);

  private:
    double              dx, wall, width, time_scale; // time_scale = sqrt(a / (2 g))
    std::vector<double> reference_T, reference_Z;   // the measurements up to the end
    std::vector<double> measured_Z;                  // the front at reference_T[0 .. ]
  };
} // namespace sluice
