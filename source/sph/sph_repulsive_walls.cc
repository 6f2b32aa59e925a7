// Solid walls as repulsive boundary particles (see the header).

#include <sluice/sph/sph_repulsive_walls.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  Vec3 LennardJonesLaw::acceleration(const Vec3 &r) const
  {
    const double r_2 = norm_square(r);
    if (!(r_2 < range * range))
      return Vec3();
    const double q_4 = (range * range / r_2) * (range * range / r_2);
    return (strength * (q_4 * q_4 * q_4 - q_4) / r_2) * r;
  }

  double LennardJonesLaw::potential(const Vec3 &r) const
  {
    const double r_2 = norm_square(r);
    if (!(r_2 < range * range))
      return 0.;
    const double q_4 = (range * range / r_2) * (range * range / r_2);
    return strength * ((q_4 * q_4 * q_4 - 1.) / 12. - (q_4 - 1.) / 4.);
  }

  RepulsiveWalls::RepulsiveWalls(const std::vector<std::pair<unsigned int, int>> &wall_faces,
                                 const Vec3 &lower, const Vec3 &upper,
                                 const std::array<bool, 3> &periodic, const double offset,
                                 const LennardJonesLaw &law)
    : law_(law)
  {
    for (const auto &[d, side] : wall_faces)
      {
        Face f;
        f.normal = d;
        f.plane  = side > 0 ? upper[d] + offset : lower[d] - offset;
        for (unsigned int k = 0; k < 2; ++k)
          {
            const unsigned int e = (d + 1 + k) % 3;
            const double       length = upper[e] - lower[e];
            f.along[k]    = e;
            f.periodic[k] = periodic[e];
            // Whole steps as close to 'spacing' as the face allows: a periodic
            // lattice closes on itself, another reaches both edges.
            const double n = periodic[e] ? std::max(1., std::round(length / law.spacing)) :
                                           std::max(1., std::ceil(length / law.spacing - 1e-9));
            f.origin[k]  = lower[e];
            f.step[k]    = length / n;
            f.n_steps[k] = static_cast<int>(n);
          }
        faces.push_back(f);
      }
  }

  template <typename Function>
  void RepulsiveWalls::for_each_in_reach(const Vec3 &x, const Function &f) const
  {
    const double r_0 = law_.range;
    for (const Face &face : faces)
      {
        if (!(std::abs(x[face.normal] - face.plane) < r_0))
          continue;
        int first[2], last[2];
        for (unsigned int k = 0; k < 2; ++k)
          {
            // Unwrapped lattice indices: along a periodic direction they reach
            // the images beyond the box's ends by themselves.
            const double u = x[face.along[k]] - face.origin[k];
            first[k]       = static_cast<int>(std::ceil((u - r_0) / face.step[k]));
            last[k]        = static_cast<int>(std::floor((u + r_0) / face.step[k]));
            if (!face.periodic[k])
              first[k] = std::max(first[k], 0), last[k] = std::min(last[k], face.n_steps[k]);
          }
        Vec3 b;
        b[face.normal] = face.plane;
        for (int i = first[0]; i <= last[0]; ++i)
          for (int j = first[1]; j <= last[1]; ++j)
            {
              b[face.along[0]] = face.origin[0] + i * face.step[0];
              b[face.along[1]] = face.origin[1] + j * face.step[1];
              f(x - b);
            }
      }
  }

  Vec3 RepulsiveWalls::acceleration(const Vec3 &x) const
  {
    Vec3 a;
    for_each_in_reach(x, [&](const Vec3 &r) { a += law_.acceleration(r); });
    return a;
  }

  double RepulsiveWalls::potential(const Vec3 &x) const
  {
    double phi = 0.;
    for_each_in_reach(x, [&](const Vec3 &r) { phi += law_.potential(r); });
    return phi;
  }

  void RepulsiveWalls::add_accelerations(SphParticles &P) const
  {
    if (faces.empty())
      return;
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        P.acceleration[a] += acceleration(P.position[a]);
  }

  std::vector<Vec3> RepulsiveWalls::boundary_particles() const
  {
    std::vector<Vec3> points;
    for (const Face &face : faces)
      for (int i = 0; i < face.n_steps[0] + !face.periodic[0]; ++i)
        for (int j = 0; j < face.n_steps[1] + !face.periodic[1]; ++j)
          {
            Vec3 b;
            b[face.normal]   = face.plane;
            b[face.along[0]] = face.origin[0] + i * face.step[0];
            b[face.along[1]] = face.origin[1] + j * face.step[1];
            points.push_back(b);
          }
    return points;
  }
} // namespace sluice
