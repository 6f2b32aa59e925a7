// Moments of a union of spheres (see the header).

#include <sluice/dem/sphere_union.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace sluice
{
  namespace
  {
    /// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
    struct GaussRule
    {
      std::vector<double> x, w;
      explicit GaussRule(const unsigned int n)
      {
        for (unsigned int i = 0; i < n; ++i)
          {
            double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0.;
            for (unsigned int iteration = 0; iteration < 100; ++iteration)
              {
                double p0 = 1., p1 = z;
                for (unsigned int k = 2; k <= n; ++k)
                  {
                    const double p2 = ((2. * k - 1.) * z * p1 - (k - 1.) * p0) / k;
                    p0 = p1, p1 = p2;
                  }
                dp = n * (z * p1 - p0) / (z * z - 1.);
                const double step = p1 / dp;
                z -= step;
                if (std::abs(step) < 1e-16)
                  break;
              }
            x.push_back(z);
            w.push_back(2. / ((1. - z * z) * dp * dp));
          }
      }
    };

    /// Area moments of a slice: 1, x, y, x^2, y^2, xy; and the union's surface
    /// area per unit height there, sum R_k theta_k (a sphere's zone between z
    /// and z + dz has the area 2 pi R dz, Archimedes, so each exposed arc of
    /// angle theta of sphere k's slice circle carries R_k theta dz).
    using SliceMoments = std::array<double, 7>;

    struct Disk
    {
      double x, y, r;
      unsigned int index;
      double       R; // the sphere's radius
    };

    /// Adds the arc theta in [a, b] of circle d (counter-clockwise) to the
    /// moments, by Green's theorem: int f dA = closed integral of Q dy with
    /// dQ/dx = f.
    void add_arc(const Disk &d, const double a, const double b, SliceMoments &m)
    {
      m[6] += d.R * (b - a);
      static const GaussRule rule(8);
      const unsigned int     n_pieces = std::max(1, static_cast<int>(std::ceil((b - a) / (M_PI / 4))));
      const double           h        = (b - a) / n_pieces;
      for (unsigned int p = 0; p < n_pieces; ++p)
        for (std::size_t q = 0; q < rule.x.size(); ++q)
          {
            const double theta = a + h * (p + 0.5 * (rule.x[q] + 1.));
            const double x = d.x + d.r * std::cos(theta), y = d.y + d.r * std::sin(theta);
            const double dy = d.r * std::cos(theta) * 0.5 * h * rule.w[q];
            m[0] += x * dy;
            m[1] += 0.5 * x * x * dy;
            m[2] += x * y * dy;
            m[3] += x * x * x / 3. * dy;
            m[4] += x * y * y * dy;
            m[5] += 0.5 * x * x * y * dy;
          }
    }

    /// Calls arc(d, a, b) for every arc theta in [a, b] of a circle of the
    /// disks' union boundary (each circle's angles outside every other disk,
    /// counter-clockwise; a disk inside another, or a twin, has none).
    template <typename Arc>
    void for_each_exposed_arc(const std::vector<Disk> &disks, const Arc &arc)
    {
      for (const Disk &d : disks)
        {
          // The angles of d's circle inside another disk.
          std::vector<std::pair<double, double>> covered;
          bool                                   inside = false;
          for (const Disk &o : disks)
            {
              if (o.index == d.index)
                continue;
              const double dx = o.x - d.x, dy = o.y - d.y, dist = std::hypot(dx, dy);
              // Twins (equal to round-off) count once: the first of them.
              const bool same = dist <= 1e-14 * d.r && std::abs(o.r - d.r) <= 1e-14 * d.r;
              if (same ? o.index < d.index : dist <= o.r - d.r)
                {
                  inside = true; // d's whole circle
                  break;
                }
              if (same || dist >= d.r + o.r || dist <= d.r - o.r)
                continue; // a later twin, apart, or o inside d
              const double phi   = std::atan2(dy, dx);
              const double alpha = std::acos(
                std::clamp((d.r * d.r + dist * dist - o.r * o.r) / (2. * d.r * dist), -1., 1.));
              covered.emplace_back(phi - alpha, phi + alpha);
            }
          if (inside)
            continue;
          // Unwrap to [0, 2 pi), merge, and visit the gaps.
          std::vector<std::pair<double, double>> pieces;
          for (const auto &[a0, b0] : covered)
            {
              const double a = a0 - 2. * M_PI * std::floor(a0 / (2. * M_PI)), b = a + (b0 - a0);
              if (b > 2. * M_PI)
                {
                  pieces.emplace_back(a, 2. * M_PI);
                  pieces.emplace_back(0., b - 2. * M_PI);
                }
              else
                pieces.emplace_back(a, b);
            }
          std::sort(pieces.begin(), pieces.end());
          double at = 0.;
          for (const auto &[a, b] : pieces)
            {
              if (a > at)
                arc(d, at, a);
              at = std::max(at, b);
            }
          if (at < 2. * M_PI)
            arc(d, at, 2. * M_PI);
        }
    }

    /// The moments of the union of the disks.
    SliceMoments slice_moments(const std::vector<Disk> &disks)
    {
      SliceMoments m{};
      for_each_exposed_arc(disks, [&m](const Disk &d, const double a, const double b) {
        add_arc(d, a, b, m);
      });
      return m;
    }

    double slice_radius_squared(const Vec3 &c, const double R, const double z)
    {
      return R * R - (z - c.z) * (z - c.z);
    }

    /// The sign changes of f on [lo, hi], sampled at 256 points and refined
    /// by bisection, appended to 'events'.
    template <typename Function>
    void add_roots(const Function &f, const double lo, const double hi,
                   std::vector<double> &events)
    {
      const unsigned int samples = 256;
      for (unsigned int s = 0; s < samples; ++s)
        {
          double a = lo + (hi - lo) * s / samples, b = lo + (hi - lo) * (s + 1) / samples;
          const double fa = f(a), fb = f(b);
          if (!std::isfinite(fa) || !std::isfinite(fb) || (fa < 0.) == (fb < 0.))
            continue;
          for (unsigned int k = 0; k < 200 && b - a > 1e-15 * (hi - lo); ++k)
            {
              const double mid = 0.5 * (a + b), fm = f(mid);
              if (!std::isfinite(fm))
                break;
              ((fm < 0.) == (f(a) < 0.) ? a : b) = mid;
            }
          events.push_back(0.5 * (a + b));
        }
    }

    struct Point2
    {
      double x, y;
    };

    /// The two points where two circles cross (NaN when they do not).
    std::array<Point2, 2> crossings(const double x1, const double y1, const double r1,
                                                   const double x2, const double y2, const double r2)
    {
      const double dx = x2 - x1, dy = y2 - y1, d = std::hypot(dx, dy);
      const double a = (r1 * r1 - r2 * r2 + d * d) / (2. * d), h2 = r1 * r1 - a * a;
      const double h = h2 >= 0. && d > 0. ? std::sqrt(h2) : std::nan("");
      const double mx = x1 + a * dx / d, my = y1 + a * dy / d;
      return {{Point2{mx - h * dy / d, my + h * dx / d}, Point2{mx + h * dy / d, my - h * dx / d}}};
    }
  } // namespace

  SphereUnionMoments sphere_union_moments(const std::vector<Vec3>   &centres,
                                          const std::vector<double> &radii,
                                          const unsigned int gauss_points, const unsigned int pieces)
  {
    const std::size_t   n = centres.size();
    std::vector<double> events;
    for (std::size_t i = 0; i < n; ++i)
      events.insert(events.end(), {centres[i].z - radii[i], centres[i].z + radii[i]});
    // Where two slice circles touch or have equal radii: sign changes of
    // d - (r_i + r_j) and d - |r_i - r_j| over their common range, refined
    // by bisection, and the equal-radius height in closed form.
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        {
          const double lo = std::max(centres[i].z - radii[i], centres[j].z - radii[j]);
          const double hi = std::min(centres[i].z + radii[i], centres[j].z + radii[j]);
          if (!(hi > lo))
            continue;
          const double d = std::hypot(centres[i].x - centres[j].x, centres[i].y - centres[j].y);
          const auto   ri = [&](const double z) {
            return std::sqrt(std::max(0., slice_radius_squared(centres[i], radii[i], z)));
          };
          const auto rj = [&](const double z) {
            return std::sqrt(std::max(0., slice_radius_squared(centres[j], radii[j], z)));
          };
          for (const int sign : {1, -1})
            add_roots([&](const double z) { return d - std::abs(ri(z) + sign * rj(z)); }, lo, hi,
                      events);
          const double dz = centres[i].z - centres[j].z;
          if (std::abs(dz) > 0.)
            {
              const double z = 0.5 * (centres[i].z + centres[j].z) +
                               (radii[j] * radii[j] - radii[i] * radii[i]) / (2. * dz);
              if (z > lo && z < hi)
                events.push_back(z);
            }
        }
    // Where a crossing of two slice circles passes through a third: a small
    // triangle of the three disks appears or goes.
    const auto radius = [&](const std::size_t i, const double z) {
      return std::sqrt(std::max(0., slice_radius_squared(centres[i], radii[i], z)));
    };
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        for (std::size_t k = 0; k < n; ++k)
          {
            if (k == i || k == j)
              continue;
            double lo = -1e300, hi = 1e300;
            for (const std::size_t m : {i, j, k})
              lo = std::max(lo, centres[m].z - radii[m]), hi = std::min(hi, centres[m].z + radii[m]);
            if (!(hi > lo))
              continue;
            for (const unsigned int which : {0u, 1u})
              add_roots(
                [&](const double z) {
                  const auto p = crossings(centres[i].x, centres[i].y, radius(i, z), centres[j].x,
                                           centres[j].y, radius(j, z))[which];
                  return std::hypot(p.x - centres[k].x, p.y - centres[k].y) - radius(k, z);
                },
                lo, hi, events);
          }
    std::sort(events.begin(), events.end());

    // Integrate the slice moments between consecutive events.
    const GaussRule       rule(gauss_points);
    std::array<double, 10> M{}; // 1, x, y, z, xx, yy, zz, xy, xz, yz
    double                 area = 0.;
    for (std::size_t e = 0; e + 1 < events.size(); ++e)
      {
        const double length = events[e + 1] - events[e];
        if (!(length > 0.))
          continue;
        // z = a + (b - a) g(s), g = s^2 (3 - 2 s): g' vanishes at both ends,
        // which turns an endpoint singularity (z - z*)^(3/2) into one of s^3.
        for (unsigned int p = 0; p < pieces; ++p)
          for (std::size_t q = 0; q < rule.x.size(); ++q)
            {
              const double h = 1. / pieces;
              const double u = h * (p + 0.5 * (rule.x[q] + 1.));
              const double z = events[e] + length * u * u * (3. - 2. * u);
              const double w = 0.5 * h * rule.w[q] * length * 6. * u * (1. - u);
              std::vector<Disk> disks;
              for (std::size_t i = 0; i < n; ++i)
                {
                  const double r2 = slice_radius_squared(centres[i], radii[i], z);
                  if (r2 > 0.)
                    disks.push_back({centres[i].x, centres[i].y, std::sqrt(r2),
                                     static_cast<unsigned int>(i), radii[i]});
                }
              const SliceMoments s = slice_moments(disks);
              const double       values[10] = {s[0], s[1], s[2], z * s[0], s[3],
                                         s[4], z * z * s[0], s[5], z * s[1], z * s[2]};
              for (unsigned int k = 0; k < 10; ++k)
                M[k] += w * values[k];
              area += w * s[6];
            }
      }

    SphereUnionMoments out;
    out.volume       = M[0];
    out.surface_area = area;
    out.centroid = Eigen::Vector3d(M[1], M[2], M[3]) / M[0];
    Eigen::Matrix3d second;
    second << M[4], M[7], M[8], M[7], M[5], M[9], M[8], M[9], M[6];
    const Eigen::Matrix3d C = second - M[0] * out.centroid * out.centroid.transpose();
    out.inertia = C.trace() * Eigen::Matrix3d::Identity() - C;
    return out;
  }
  double sphere_union_shadow_area(const std::vector<Vec3>   &centres,
                                  const std::vector<double> &radii, const Vec3 &direction)
  {
    // An orthonormal pair (e1, e2) across the direction; the shadow of sphere
    // i is the disk of radius R_i about its centre's projection.
    const Vec3 n  = (1. / norm(direction)) * direction;
    const Vec3 e1 = std::abs(n.x) < 0.9 ? cross(n, Vec3(1., 0., 0.)) : cross(n, Vec3(0., 1., 0.));
    const Vec3 u  = (1. / norm(e1)) * e1, v = cross(n, u);
    std::vector<Disk> disks;
    for (std::size_t i = 0; i < centres.size(); ++i)
      disks.push_back({dot(centres[i], u), dot(centres[i], v), radii[i],
                       static_cast<unsigned int>(i), radii[i]});
    // Green's theorem in closed form: over the arc [a, b] of circle (c, r),
    // x dy integrates to c_x r (sin b - sin a) + r^2 ((b - a) + (sin 2b - sin 2a) / 2) / 2.
    double area = 0.;
    for_each_exposed_arc(disks, [&area](const Disk &d, const double a, const double b) {
      area += d.x * d.r * (std::sin(b) - std::sin(a)) +
              0.5 * d.r * d.r * ((b - a) + 0.5 * (std::sin(2. * b) - std::sin(2. * a)));
    });
    return area;
  }
} // namespace sluice
