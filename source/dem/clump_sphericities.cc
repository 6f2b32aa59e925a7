// A clump's sphericities for Hoelzer & Sommerfeld's drag (see the header).

#include <sluice/dem/clump_sphericities.h>
#include <sluice/dem/sphere_union.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  namespace
  {
    /// Two unit vectors across the unit vector n, and n, right-handed.
    std::pair<Vec3, Vec3> across(const Vec3 &n)
    {
      const Vec3 e = std::abs(n.x) < 0.9 ? cross(n, Vec3(1., 0., 0.)) : cross(n, Vec3(0., 1., 0.));
      const Vec3 u = (1. / norm(e)) * e;
      return {u, cross(n, u)};
    }

    /// The direction at polar angle theta from z and azimuth phi.
    Vec3 direction_at(const double theta, const double phi)
    {
      return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                  std::cos(theta));
    }
  } // namespace

  Sphericities clump_sphericities(const ClumpTemplate &clump, const Vec3 &direction)
  {
    const Vec3   n          = (1. / norm(direction)) * direction;
    const double d_v        = clump.volume_equivalent_diameter();
    const double equivalent = 0.25 * M_PI * d_v * d_v; // the shadow of the sphere of same volume
    const auto   shadow     = [&](const Vec3 &along) {
      return sphere_union_shadow_area(clump.members, clump.radii, along);
    };
    const auto [u, v]          = across(n);
    const unsigned int n_cross = 32;
    double             mean_across = 0.;
    for (unsigned int k = 0; k < n_cross; ++k)
      {
        const double theta = M_PI * (k + 0.5) / n_cross;
        mean_across += shadow(std::cos(theta) * u + std::sin(theta) * v) / n_cross;
      }
    Sphericities s;
    s.sphericity = clump.sphericity();
    s.crosswise  = equivalent / shadow(n);
    s.lengthwise = equivalent / (0.5 * clump.surface_area - mean_across);
    return s;
  }

  SphericityTable::SphericityTable(const ClumpTemplate &clump, const unsigned int n_polar,
                                   const unsigned int n_azimuth)
    : clump(clump), n_polar(n_polar), n_azimuth(n_azimuth), sphericity(clump.sphericity())
  {
    const double d_v  = clump.volume_equivalent_diameter();
    equivalent_shadow = 0.25 * M_PI * d_v * d_v;
    lengthwise.resize(n_polar * n_azimuth);
    for (unsigned int i = 0; i < n_polar; ++i)
      for (unsigned int j = 0; j < n_azimuth; ++j)
        lengthwise[i * n_azimuth + j] =
          clump_sphericities(clump, direction_at(0.5 * M_PI * i / (n_polar - 1),
                                                 2. * M_PI * j / n_azimuth))
            .lengthwise;
  }

  Sphericities SphericityTable::operator()(const Vec3 &direction) const
  {
    // On the upper half sphere: -n casts the same shadows as n.
    const Vec3   n     = (direction.z < 0. ? -1. : 1.) / norm(direction) * direction;
    const double theta = std::acos(std::clamp(n.z, -1., 1.));
    double       phi   = std::atan2(n.y, n.x);
    if (phi < 0.)
      phi += 2. * M_PI;
    const double       a  = theta / (0.5 * M_PI) * (n_polar - 1);
    const double       b  = phi / (2. * M_PI) * n_azimuth;
    const unsigned int i  = std::min<unsigned int>(static_cast<unsigned int>(a), n_polar - 2);
    const unsigned int j  = static_cast<unsigned int>(b) % n_azimuth, j1 = (j + 1) % n_azimuth;
    const double       fa = a - i, fb = b - std::floor(b);
    const unsigned int k0 = i * n_azimuth, k1 = (i + 1) * n_azimuth;
    Sphericities       s;
    s.sphericity = sphericity;
    s.crosswise  = equivalent_shadow / sphere_union_shadow_area(clump.members, clump.radii, n);
    s.lengthwise = (1. - fa) * ((1. - fb) * lengthwise[k0 + j] + fb * lengthwise[k0 + j1]) +
                   fa * ((1. - fb) * lengthwise[k1 + j] + fb * lengthwise[k1 + j1]);
    return s;
  }
} // namespace sluice
