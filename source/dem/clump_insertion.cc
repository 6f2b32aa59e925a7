// The bodies of a clump scene at the start (see the header).

#include <sluice/dem/clump_insertion.h>
#include <sluice/dem/insertion.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace sluice
{
  double largest_bounding_radius(const ClumpParameters            &parameters,
                                 const std::vector<ClumpTemplate> &templates)
  {
    double r = 0.;
    for (std::size_t k = 0; k < templates.size(); ++k)
      {
        const ClumpTemplateParameters &t = parameters.templates[k];
        r = std::max(r, std::max(t.scale, t.scale_max) * templates[k].bounding_radius());
      }
    return r;
  }

  std::vector<ParticleRecord> create_clump_bodies(const SceneParameters            &p,
                                                  const std::vector<ClumpTemplate> &templates)
  {
    const ClumpParameters &c = p.clumps;
    if (p.insertion_method == InsertionMethod::list || p.insertion_method == InsertionMethod::file)
      {
        std::vector<ParticleRecord> bodies = p.particle_list;
        for (ParticleRecord &b : bodies)
          b.radius = b.clump_scale * templates[b.clump_template].bounding_radius();
        return bodies;
      }
    // The sites of spheres as large as the largest body's bounding sphere.
    SceneParameters sites = p;
    sites.radius          = largest_bounding_radius(c, templates);
    sites.radius_max      = 0.;
    std::vector<ParticleRecord> bodies;
    try
      {
        bodies = create_particles(sites);
      }
    catch (const InputError &e)
      {
        throw InputError(std::string(e.what()) + " (in a clump scene a site holds a body's "
                         "bounding sphere, of the largest template's radius at its largest "
                         "scale)");
      }

    std::mt19937_64 rng(p.seed + 0x5eed);
    for (ParticleRecord &b : bodies)
      draw_clump_body(c, templates, rng, b);
    return bodies;
  }

  void draw_clump_body(const ClumpParameters &c, const std::vector<ClumpTemplate> &templates,
                       std::mt19937_64 &rng, ParticleRecord &b)
  {
    std::vector<double> fractions;
    for (const ClumpTemplateParameters &t : c.templates)
      fractions.push_back(t.fraction);
    std::discrete_distribution<unsigned>   which(fractions.begin(), fractions.end());
    std::uniform_real_distribution<double> u(0., 1.);
    b.clump_template                 = templates.size() > 1 ? which(rng) : 0;
    const ClumpTemplateParameters &t = c.templates[b.clump_template];
    b.clump_scale = t.scale_max > t.scale ? t.scale + u(rng) * (t.scale_max - t.scale) : t.scale;
    b.radius      = b.clump_scale * templates[b.clump_template].bounding_radius();
    if (c.random_orientation)
      {
        const double u1 = u(rng), u2 = 2. * M_PI * u(rng), u3 = 2. * M_PI * u(rng);
        const double a = std::sqrt(1. - u1), s = std::sqrt(u1);
        b.orientation = {{a * std::sin(u2), a * std::cos(u2), s * std::sin(u3), s * std::cos(u3)}};
      }
  }

  double mean_clump_mass(const ClumpParameters &c, const std::vector<ClumpTemplate> &templates,
                         const double rho)
  {
    // E[s^3] for s uniform in [a, b] is (b^4 - a^4) / (4 (b - a)).
    double mass = 0., total = 0.;
    for (std::size_t k = 0; k < templates.size(); ++k)
      {
        const ClumpTemplateParameters &t = c.templates[k];
        const double a = t.scale, b = std::max(t.scale, t.scale_max);
        const double s3 = b > a ? (std::pow(b, 4) - std::pow(a, 4)) / (4. * (b - a)) : a * a * a;
        mass += t.fraction * rho * s3 * templates[k].volume;
        total += t.fraction;
      }
    return mass / total;
  }
} // namespace sluice
