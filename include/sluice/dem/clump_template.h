#pragma once
// A rigid clump's shape (Bell, Yu & Mucha 2005): its member spheres in the
// body frame, which has its origin at the centroid of the members' union and
// its axes along the principal axes of inertia (ascending moments), with the
// union's volume and principal moments per unit density (sphere_union.h, so
// overlaps count once). Built from any members, or as a regular tetrahedron,
// a rod of n spheres or a cube of eight, whose neighbouring members overlap
// by a fraction of their diameter (0: touching).

#include <sluice/core/vector3.h>

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace sluice
{
  struct ClumpTemplate
  {
    std::string         name;
    std::vector<Vec3>   members; // body frame [m]
    std::vector<double> radii;   // [m]
    double              volume = 0.; // of the union [m^3]
    double              surface_area = 0.; // of the union [m^2]
    // Principal moments of inertia per unit density, ascending [m^5].
    Eigen::Vector3d principal_inertia = Eigen::Vector3d::Zero();
    // The body frame's axes in the frame the members were given in (columns),
    // and where its origin lay there: x_given = frame x_body + origin.
    Eigen::Matrix3d frame  = Eigen::Matrix3d::Identity();
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();

    /// The largest distance of a member's surface from the centroid [m].
    double bounding_radius() const;
    /// The diameter of the sphere of the same volume [m].
    double volume_equivalent_diameter() const;
    /// Wadell's sphericity: the surface of the sphere of the same volume over
    /// the union's, pi d_v^2 / S (1 for a sphere; the drag correlations of
    /// Haider & Levenspiel 1989 and Hoelzer & Sommerfeld 2008 take it).
    double sphericity() const;
  };

  /// The template of these members (given in any frame; radii > 0).
  ClumpTemplate make_clump_template(const std::string &name, const std::vector<Vec3> &centres,
                                    const std::vector<double> &radii);

  /// Four spheres of 'radius' on a regular tetrahedron of edge 2 radius (1 - overlap).
  ClumpTemplate tetrahedron_clump(double radius, double overlap);
  /// n spheres in a row, 2 radius (1 - overlap) apart.
  ClumpTemplate rod_clump(unsigned int n, double radius, double overlap);
  /// Eight spheres on the corners of a cube of edge 2 radius (1 - overlap).
  ClumpTemplate cube_clump(double radius, double overlap);
} // namespace sluice
