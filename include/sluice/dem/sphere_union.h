#pragma once
// Volume, centroid and inertia of a union of overlapping spheres (a clump's
// members, overlaps counted once), per unit density.
//
// Method: slices z = const. The slice of the union is a union of disks, whose
// area and first and second moments follow exactly from Green's theorem on
// the arcs of its boundary (each circle's arcs outside every other disk), the
// arc integrals by Gauss-Legendre on pieces of at most pi/4 (their trig
// polynomials to round-off). Along z these moments are smooth between the
// events where the slice's topology changes: a sphere's top or bottom, two
// circles touching from outside or inside, two circles of equal radius, a
// crossing of two circles passing through a third (found by sampling and
// bisection; O(n^3) for n members, once per clump template). The
// z integral is Gauss-Legendre between consecutive events, whose endpoint
// singularities are at most (z - z*)^(3/2); with the default 16 points on 4
// pieces per interval the relative error is about 1e-10 (unit.sphere_union
// checks it against closed forms). The surface area comes from the same
// slices: the exposed arcs' angles times their spheres' radii, integrated
// over z (each sphere's zone of height dz has the area 2 pi R dz).

#include <sluice/core/vector3.h>

#include <Eigen/Dense>

#include <vector>

namespace sluice
{
  struct SphereUnionMoments
  {
    double          volume = 0.;                         // [m^3]
    double          surface_area = 0.;                   // of the union [m^2]
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // [m]
    Eigen::Matrix3d inertia  = Eigen::Matrix3d::Zero();  // about the centroid, per density [m^5]
  };

  /// The moments of the union of the spheres (centres, radii > 0).
  SphereUnionMoments sphere_union_moments(const std::vector<Vec3>   &centres,
                                          const std::vector<double> &radii,
                                          unsigned int gauss_points = 16, unsigned int pieces = 4);

  /// The area of the union's shadow along 'direction' (its orthogonal
  /// projection on a plane across it): the union of the members' disks, by
  /// the same exposed arcs, exact to round-off [m^2].
  double sphere_union_shadow_area(const std::vector<Vec3>   &centres,
                                  const std::vector<double> &radii, const Vec3 &direction);
} // namespace sluice
