#pragma once
// What an SPH scene's validation case measures, and its result line
// (doc/sph.md, doc/validation.md):
//  - hydrostatic: a column at rest on a floor; the bottom layer's pressure
//    against rho_0 g (H - z), with the mean density's drift and the largest
//    speed against sqrt(g H) as checks;
//  - poiseuille: the start-up of plane Poiseuille flow, driven by a body
//    force F (the gravity entry, along a periodic direction) between two
//    no-slip walls a distance L apart, from rest (Morris, Fox & Zhu 1997,
//    J. Comput. Phys. 136, 214, Eq. 21):
//      v(y, t) = F/(2 nu) y (L - y)
//                - sum_n 4 F L^2 / (nu pi^3 (2n+1)^3) sin((2n+1) pi y / L)
//                  exp(-(2n+1)^2 pi^2 nu t / L^2);
//    each layer of particles' mean velocity against v at its mean y, at
//    nu t / L^2 = 0.0225, 0.045, 0.1125 (Morris' times) and at the end.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/scene_records.h>
#include <sluice/sph/sph_particles.h>
#include <sluice/sph/sph_setup.h>

#include <string>
#include <vector>

namespace sluice
{
  /// A validation's result line and its check lines.
  struct SphResult
  {
    std::string              name;
    double                   value = 0., reference = 0., error = 0.;
    std::vector<std::string> checks;
  };

  /// The column at rest (validation = hydrostatic), from the final state.
  SphResult hydrostatic_result(const SphParticles &P, const SceneParameters &p,
                               const SphSetup &setup, double mean_density_start,
                               double mean_density_end, double max_speed_end);

  /// Morris et al.'s series for the start-up of plane Poiseuille flow (in the
  /// header's comment), summed until its terms fall below 1e-16 of F L^2/nu.
  double poiseuille_series(double y, double t, double width, double force, double nu);

  /// The velocity profiles of the Poiseuille start-up (validation = poiseuille).
  class PoiseuilleProbe
  {
  public:
    /// Throws InputError naming the entry when the scene is not a channel:
    /// walls on the two faces of one direction, the fluid filling the domain,
    /// gravity across them along periodic directions, a viscosity.
    PoiseuilleProbe(const SceneParameters &p, double end_time);

    /// A probe time falls in (time - dt, time].
    bool due(double time, double dt) const
    {
      const std::size_t k = measured.size();
      return k < times.size() && time > times[k] - 0.5 * dt;
    }
    /// Measures the profile when due().
    void measure_if_due(const SphParticles &P, double time, double dt);
    /// The largest deviation of a layer's velocity from the series, over
    /// the probes, against the steady centre-line velocity F L^2 / (8 nu).
    SphResult result(int precision) const;

    /// The profiles measured so far, for a checkpoint.
    void save(SceneRecords &records) const;
    void restore(const SceneRecords &records);

  private:
    double              dx, width, lower, force, nu;
    unsigned int        normal = 1;
    Vec3                flow;
    std::vector<double> times;
    // One line per probe: time, largest deviation [m/s], the centre layer's
    // velocity and the series there.
    std::vector<std::vector<double>> measured;
  };
} // namespace sluice
