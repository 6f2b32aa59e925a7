#pragma once
// The volume and mass of a sphere, the one place every module takes them
// from. The mass keeps the order of operations the DEM has always used
// (rho 4/3 pi r r r, left to right), so that masses, contact times and
// every reference output stay bit for bit what they were.

#include <cmath>

namespace sluice
{
  /// 4/3 pi r^3 [m^3].
  inline double sphere_volume(const double radius)
  {
    return 4. / 3. * M_PI * std::pow(radius, 3);
  }

  /// rho 4/3 pi r^3 [kg].
  inline double sphere_mass(const double density, const double radius)
  {
    return density * 4. / 3. * M_PI * radius * radius * radius;
  }
} // namespace sluice
