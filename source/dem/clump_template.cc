// Clump templates (see the header).

#include <sluice/dem/clump_template.h>
#include <sluice/dem/eigen_conversion.h>
#include <sluice/dem/sphere_union.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  double ClumpTemplate::bounding_radius() const
  {
    double r = 0.;
    for (std::size_t m = 0; m < members.size(); ++m)
      r = std::max(r, norm(members[m]) + radii[m]);
    return r;
  }

  double ClumpTemplate::volume_equivalent_diameter() const
  {
    return std::cbrt(6. * volume / M_PI);
  }

  double ClumpTemplate::sphericity() const
  {
    const double d = volume_equivalent_diameter();
    return M_PI * d * d / surface_area;
  }

  ClumpTemplate make_clump_template(const std::string &name, const std::vector<Vec3> &centres,
                                    const std::vector<double> &radii)
  {
    const SphereUnionMoments moments = sphere_union_moments(centres, radii);
    // Principal axes: the inertia's eigenvectors, ascending, as a proper
    // rotation (a reflection would mirror the clump).
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(moments.inertia);
    Eigen::Matrix3d axes = eigen.eigenvectors();
    if (axes.determinant() < 0.)
      axes.col(2) *= -1.;
    ClumpTemplate t;
    t.name              = name;
    t.radii             = radii;
    t.volume            = moments.volume;
    t.surface_area      = moments.surface_area;
    t.principal_inertia = eigen.eigenvalues();
    t.frame             = axes;
    t.origin            = moments.centroid;
    for (const Vec3 &c : centres)
      {
        const Eigen::Vector3d body = axes.transpose() * (to_eigen(c) - t.origin);
        t.members.emplace_back(body.x(), body.y(), body.z());
      }
    return t;
  }

  ClumpTemplate tetrahedron_clump(const double radius, const double overlap)
  {
    const double      edge = 2. * radius * (1. - overlap), s = edge / (2. * std::sqrt(2.));
    std::vector<Vec3> c    = {Vec3(s, s, s), Vec3(s, -s, -s), Vec3(-s, s, -s), Vec3(-s, -s, s)};
    return make_clump_template("tetrahedron", c, std::vector<double>(4, radius));
  }

  ClumpTemplate rod_clump(const unsigned int n, const double radius, const double overlap)
  {
    std::vector<Vec3> c;
    for (unsigned int k = 0; k < n; ++k)
      c.emplace_back(2. * radius * (1. - overlap) * k, 0., 0.);
    return make_clump_template("rod", c, std::vector<double>(n, radius));
  }

  ClumpTemplate cube_clump(const double radius, const double overlap)
  {
    const double      h = radius * (1. - overlap);
    std::vector<Vec3> c;
    for (const double x : {-h, h})
      for (const double y : {-h, h})
        for (const double z : {-h, h})
          c.emplace_back(x, y, z);
    return make_clump_template("cube", c, std::vector<double>(8, radius));
  }
} // namespace sluice
