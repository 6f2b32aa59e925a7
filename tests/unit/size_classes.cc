// 'insertion/size classes': a discrete mixture inserted by the lattice and by
// random sequential addition. Each class gets the mass share it asked for, to
// within one particle of that class; the classes are mixed: their
// mass-weighted mean heights (Gao & Sun Eq. 46) agree to within 5% of the
// filled height (perfectly mixed: equal but for the sampling noise, about
// 1.3% of it here); random addition leaves no two spheres overlapping; and the same
// seed gives the same particles.

#include <sluice/dem/insertion.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace sluice;
using sluice::unit::check;

namespace
{
  /// A 50/50 mixture by mass of 1.5 mm and 2.5 mm glass beads, and a
  /// 20/80 mixture of a third, denser class.
  SceneParameters mixture(const InsertionMethod method, const bool three_classes)
  {
    SceneParameters p;
    p.density          = {2523., 2523., 7800.};
    p.insertion_method = method;
    p.n_particles      = 3000;
    p.region_lower     = Vec3(0., 0., 0.01);
    p.region_upper     = Vec3(0.03, 0.015, method == InsertionMethod::random ? 0.11 : 0.4);
    p.size_classes     = {{7.5e-4, 0.5, 0}, {1.25e-3, 0.5, 1}};
    if (three_classes)
      p.size_classes = {{7.5e-4, 0.2, 0}, {1.25e-3, 0.3, 1}, {1e-3, 0.5, 2}};
    p.seed = 7;
    return p;
  }

  void check_mixture(const SceneParameters &p, const char *label)
  {
    const std::vector<ParticleRecord> particles = create_particles(p);
    check(particles.size() == p.n_particles, label, particles.size(), p.n_particles);

    const std::size_t   n_classes = p.size_classes.size();
    std::vector<double> mass(n_classes, 0.), moment(n_classes, 0.);
    double              total = 0.;
    for (const ParticleRecord &r : particles)
      {
        std::size_t c = 0;
        while (c < n_classes && !(p.size_classes[c].radius == r.radius &&
                                  p.size_classes[c].type == r.type))
          ++c;
        check(c < n_classes, "every particle is of a class", r.radius, 0.);
        if (c == n_classes)
          return;
        const double m = p.density[r.type] * 4. / 3. * M_PI * std::pow(r.radius, 3);
        mass[c] += m;
        moment[c] += m * r.position.z;
        total += m;
      }
    double lowest = particles[0].position.z, highest = lowest;
    for (const ParticleRecord &r : particles)
      lowest = std::min(lowest, r.position.z), highest = std::max(highest, r.position.z);
    const double height = highest - lowest; // of the filled part of the region
    for (std::size_t c = 0; c < n_classes; ++c)
      {
        const SizeClass &k   = p.size_classes[c];
        const double     one = p.density[k.type] * 4. / 3. * M_PI * std::pow(k.radius, 3);
        std::printf("%s class %zu: mass share %.5f (asked %.5f), mean height %.5f m\n", label, c,
                    mass[c] / total, k.mass_fraction, moment[c] / mass[c]);
        check(std::abs(mass[c] / total - k.mass_fraction) <= one / total,
              "a class's mass share within one particle of its fraction", mass[c] / total,
              k.mass_fraction);
        check(std::abs(moment[c] / mass[c] - moment[0] / mass[0]) < 0.05 * height,
              "the classes' mean heights agree (mixed)", moment[c] / mass[c], moment[0] / mass[0]);
      }

    if (p.insertion_method == InsertionMethod::random)
      {
        double deepest = 0.;
        for (std::size_t i = 0; i < particles.size(); ++i)
          for (std::size_t j = i + 1; j < particles.size(); ++j)
            {
              const double gap = norm(particles[i].position - particles[j].position) -
                                 particles[i].radius - particles[j].radius;
              deepest = std::min(deepest, gap);
            }
        check(deepest >= 0., "random addition: no overlap", deepest, 0.);
      }

    const std::vector<ParticleRecord> again = create_particles(p);
    bool                              same  = again.size() == particles.size();
    for (std::size_t i = 0; same && i < again.size(); ++i)
      same = again[i].radius == particles[i].radius && again[i].type == particles[i].type &&
             norm(again[i].position - particles[i].position) == 0.;
    check(same, "the same seed gives the same particles", same, 1.);
  }
} // namespace

int main()
{
  check_mixture(mixture(InsertionMethod::random, false), "random, two classes");
  check_mixture(mixture(InsertionMethod::lattice, false), "lattice, two classes");
  check_mixture(mixture(InsertionMethod::random, true), "random, three classes");

  // The largest class decides the lattice's spacing and the cell size.
  const SceneParameters p = mixture(InsertionMethod::lattice, false);
  check(p.largest_radius() == 1.25e-3, "largest radius of a mixture", p.largest_radius(),
        1.25e-3);
  return sluice::unit::failures == 0 ? 0 : 1;
}
