#include <sluice/dem/insertion.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

namespace sluice
{
  namespace
  {
    double draw_radius(const SceneParameters &p, std::mt19937_64 &rng)
    {
      if (p.radius_max <= p.radius)
        return p.radius;
      return std::uniform_real_distribution<double>(p.radius, p.radius_max)(rng);
    }

    /// The class of each of the n particles of a size mixture: as many of each
    /// as is nearest its mass share (largest remainders make up the total),
    /// shuffled (Fisher-Yates) so that the classes are perfectly mixed.
    std::vector<unsigned int> class_sequence(const SceneParameters &p, std::mt19937_64 &rng)
    {
      const std::vector<SizeClass> &classes = p.size_classes;
      std::vector<double>           share(classes.size());
      double                        total = 0.;
      for (std::size_t c = 0; c < classes.size(); ++c)
        {
          const double r = classes[c].radius;
          share[c]       = classes[c].mass_fraction / (p.density[classes[c].type] * r * r * r);
          total += share[c];
        }
      std::vector<unsigned long long> count(classes.size());
      std::vector<std::pair<double, std::size_t>> remainder;
      unsigned long long                           placed = 0;
      for (std::size_t c = 0; c < classes.size(); ++c)
        {
          const double exact = p.n_particles * share[c] / total;
          count[c]           = static_cast<unsigned long long>(std::floor(exact));
          placed += count[c];
          remainder.emplace_back(-(exact - count[c]), c);
        }
      std::sort(remainder.begin(), remainder.end());
      for (std::size_t k = 0; placed < p.n_particles; ++k, ++placed)
        ++count[remainder[k % remainder.size()].second];

      std::vector<unsigned int> sequence;
      sequence.reserve(p.n_particles);
      for (std::size_t c = 0; c < classes.size(); ++c)
        sequence.insert(sequence.end(), count[c], static_cast<unsigned int>(c));
      std::uniform_real_distribution<double> u(0., 1.);
      for (std::size_t k = sequence.size(); k > 1; --k)
        std::swap(sequence[k - 1],
                  sequence[std::min(k - 1, static_cast<std::size_t>(u(rng) * k))]);
      return sequence;
    }

    /// The radius and type of the k-th inserted particle.
    struct SizeDraw
    {
      const SceneParameters    &p;
      std::vector<unsigned int> classes; // empty without 'size classes'

      std::pair<double, unsigned int> operator()(const unsigned long long k,
                                                 std::mt19937_64         &rng) const
      {
        if (classes.empty())
          return {draw_radius(p, rng), p.particle_type};
        const SizeClass &c = p.size_classes[classes[k]];
        return {c.radius, c.type};
      }
    };

    SizeDraw size_draw(const SceneParameters &p, std::mt19937_64 &rng)
    {
      return SizeDraw{p, p.size_classes.empty() ? std::vector<unsigned int>() :
                                                  class_sequence(p, rng)};
    }

    ParticleRecord make_record(const SceneParameters &p, const Vec3 &x,
                               const std::pair<double, unsigned int> &size)
    {
      ParticleRecord rec;
      rec.position         = x;
      rec.radius           = size.first;
      rec.type             = size.second;
      rec.velocity         = p.initial_velocity;
      rec.angular_velocity = p.initial_angular_velocity;
      return rec;
    }

    std::string region_text(const SceneParameters &p)
    {
      auto pt = [](const Vec3 &v) {
        return "(" + to_text(v.x) + ", " + to_text(v.y) + ", " + to_text(v.z) + ")";
      };
      return pt(p.region_lower) + " to " + pt(p.region_upper);
    }

    /// Simple cubic lattice with a spacing of 2.1 largest radii, filled from the
    /// bottom layer up, each site displaced at random by up to 'lattice jitter'
    /// times half the gap so that no two spheres overlap.
    std::vector<ParticleRecord> lattice(const SceneParameters &p)
    {
      const double r_max   = p.largest_radius();
      const double spacing = p.lattice_spacing > 0. ? p.lattice_spacing : 2.1 * r_max;
      const double jitter  = p.lattice_jitter * 0.5 * std::max(0., spacing - 2. * r_max);
      unsigned long long n[3];
      for (unsigned int d = 0; d < 3; ++d)
        {
          const double room = p.region_upper[d] - p.region_lower[d] - 2. * r_max;
          n[d] = room < 0. ? 0 :
                             static_cast<unsigned long long>(std::floor(room / spacing + 1e-9)) + 1;
        }
      const unsigned long long capacity = n[0] * n[1] * n[2];
      if (capacity < p.n_particles)
        throw InputError("error in '" + p.file_name + "': entry 'insertion/number of particles' = " +
                         std::to_string(p.n_particles) + " does not fit: a lattice in the region " +
                         region_text(p) + " holds at most " + std::to_string(capacity) +
                         " spheres of radius " + to_text(r_max));
      std::mt19937_64                        rng(p.seed);
      const SizeDraw                         size = size_draw(p, rng);
      std::uniform_real_distribution<double> shift(-jitter, jitter);
      std::vector<ParticleRecord>            out;
      out.reserve(p.n_particles);
      for (unsigned long long k = 0; k < p.n_particles; ++k)
        {
          const unsigned long long ix = k % n[0], iy = (k / n[0]) % n[1], iz = k / (n[0] * n[1]);
          Vec3 x = p.region_lower + Vec3(r_max + ix * spacing, r_max + iy * spacing,
                                         r_max + iz * spacing);
          x += Vec3(shift(rng), shift(rng), shift(rng));
          out.push_back(make_record(p, x, size(k, rng)));
        }
      return out;
    }

    /// Random sequential addition: candidates uniform in the region, rejected when
    /// they overlap an accepted sphere (checked on a cell grid, O(1) per try).
    std::vector<ParticleRecord> random_fill(const SceneParameters &p)
    {
      const double r_max = p.largest_radius();
      Vec3         lo = p.region_lower + Vec3(r_max, r_max, r_max);
      Vec3         hi = p.region_upper - Vec3(r_max, r_max, r_max);
      for (unsigned int d = 0; d < 3; ++d)
        if (!(hi[d] > lo[d]))
          throw InputError("error in '" + p.file_name +
                           "': entry 'insertion/region upper corner': the region " +
                           region_text(p) + " is narrower than one sphere of radius " +
                           to_text(r_max));
      const double cell = 2. * r_max;
      long long    n[3];
      for (unsigned int d = 0; d < 3; ++d)
        n[d] = std::max(1LL, static_cast<long long>(std::ceil((hi[d] - lo[d]) / cell)));
      auto key = [&](long long i, long long j, long long k) { return i + n[0] * (j + n[1] * k); };
      std::unordered_multimap<long long, unsigned int> grid;
      grid.reserve(2 * p.n_particles);

      std::mt19937_64                        rng(p.seed);
      const SizeDraw                         size = size_draw(p, rng);
      std::uniform_real_distribution<double> u(0., 1.);
      std::vector<ParticleRecord>            out;
      out.reserve(p.n_particles);
      const unsigned long long max_tries = 1000ULL * std::max<unsigned long long>(p.n_particles, 1);
      unsigned long long       tries     = 0;
      while (out.size() < p.n_particles)
        {
          if (++tries > max_tries)
            throw InputError(
              "error in '" + p.file_name + "': entry 'insertion/number of particles' = " +
              std::to_string(p.n_particles) + " does not fit: random insertion without overlap "
              "placed only " + std::to_string(out.size()) + " spheres in the region " +
              region_text(p) + " after " + std::to_string(max_tries) +
              " tries (random packing stops near a solid fraction of 0.3; enlarge the region)");
          const auto   drawn = size(out.size(), rng);
          const double r     = drawn.first;
          const Vec3   x(lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y),
                         lo.z + u(rng) * (hi.z - lo.z));
          long long c[3];
          for (unsigned int d = 0; d < 3; ++d)
            c[d] = std::min(n[d] - 1, static_cast<long long>((x[d] - lo[d]) / cell));
          bool free = true;
          for (long long dz = -1; dz <= 1 && free; ++dz)
            for (long long dy = -1; dy <= 1 && free; ++dy)
              for (long long dx = -1; dx <= 1 && free; ++dx)
                {
                  const long long i = c[0] + dx, j = c[1] + dy, k = c[2] + dz;
                  if (i < 0 || j < 0 || k < 0 || i >= n[0] || j >= n[1] || k >= n[2])
                    continue;
                  const auto range = grid.equal_range(key(i, j, k));
                  for (auto it = range.first; it != range.second && free; ++it)
                    {
                      const ParticleRecord &o    = out[it->second];
                      const double          dmin = r + o.radius;
                      if (norm_square(x - o.position) < dmin * dmin)
                        free = false;
                    }
                }
          if (!free)
            continue;
          grid.emplace(key(c[0], c[1], c[2]), out.size());
          out.push_back(make_record(p, x, drawn));
        }
      return out;
    }
  } // namespace

  std::vector<ParticleRecord> create_particles(const SceneParameters &p)
  {
    switch (p.insertion_method)
      {
        case InsertionMethod::lattice:
          return lattice(p);
        case InsertionMethod::random:
          return random_fill(p);
        default:
          return p.particle_list;
      }
  }
} // namespace sluice
