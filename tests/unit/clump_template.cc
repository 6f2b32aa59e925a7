// Clump templates (dem/clump_template.h):
// - one member: a sphere at the origin, J = 2/5 V R^2 per density;
// - an asymmetric clump of three unequal, overlapping members: in the body
//   frame its union's centroid is at the origin and its inertia diagonal with
//   the template's ascending moments; the frame is a rotation and maps the
//   body-frame members back onto the given ones;
// - rods of touching spheres (closed forms by parallel axes), a regular
//   tetrahedron and a cube (isotropic), touching (volume n V_s) and
//   overlapping (volume below n V_s, bounding radius as placed).

#include <sluice/dem/clump_template.h>
#include <sluice/dem/sphere_union.h>

#include "check.h"

#include <cmath>
#include <cstdio>

using namespace sluice;
using sluice::unit::check;

namespace
{
  double sphere_volume(const double R) { return 4. / 3. * M_PI * R * R * R; }
  double relative(const double a, const double b) { return std::abs(a - b) / std::abs(b); }

  void check_one_member()
  {
    const ClumpTemplate t = make_clump_template("one", {Vec3(1, 2, 3)}, {0.5});
    check(norm(t.members[0]) < 1e-14, "one member at the origin", norm(t.members[0]), 0.);
    check(relative(t.volume, sphere_volume(0.5)) < 1e-13, "one member: volume", t.volume,
          sphere_volume(0.5));
    check(relative(t.principal_inertia[0], 0.4 * sphere_volume(0.5) * 0.25) < 1e-12,
          "one member: J = 2/5 V R^2", t.principal_inertia[0], 0.4 * sphere_volume(0.5) * 0.25);
    check(std::abs(t.sphericity() - 1.) < 1e-12, "one member: sphericity 1", t.sphericity(), 1.);
  }

  void check_asymmetric()
  {
    const std::vector<Vec3>   given = {Vec3(0.1, 0.2, -0.3), Vec3(0.9, 0.5, 0.1), Vec3(0.3, 1.1, 0.6)};
    const std::vector<double> radii = {0.5, 0.4, 0.3};
    const ClumpTemplate       t     = make_clump_template("odd", given, radii);
    const SphereUnionMoments  body  = sphere_union_moments(t.members, t.radii);
    const Eigen::Matrix3d     off   = body.inertia - Eigen::Matrix3d(body.inertia.diagonal().asDiagonal());
    check(body.centroid.norm() < 1e-12, "body frame: centroid at the origin", body.centroid.norm(), 0.);
    check(off.norm() < 1e-12 * body.inertia.norm(), "body frame: inertia diagonal", off.norm(), 0.);
    check((body.inertia.diagonal() - t.principal_inertia).norm() < 1e-12 * t.principal_inertia.norm(),
          "body frame: the template's moments", body.inertia(0, 0), t.principal_inertia[0]);
    check(t.principal_inertia[0] <= t.principal_inertia[1] &&
            t.principal_inertia[1] <= t.principal_inertia[2],
          "moments ascending", t.principal_inertia[0], t.principal_inertia[2]);
    check(std::abs(t.frame.determinant() - 1.) < 1e-13, "frame is a rotation", t.frame.determinant(), 1.);
    double worst = 0.;
    for (std::size_t m = 0; m < given.size(); ++m)
      {
        const Eigen::Vector3d back =
          t.frame * Eigen::Vector3d(t.members[m].x, t.members[m].y, t.members[m].z) + t.origin;
        worst = std::max(worst, (back - Eigen::Vector3d(given[m].x, given[m].y, given[m].z)).norm());
      }
    check(worst < 1e-14, "frame maps the members back", worst, 0.);
  }

  void check_built_in()
  {
    const double r = 0.01, Vs = sphere_volume(r);
    const ClumpTemplate rod = rod_clump(3, r, 0.);
    const double J_axis = 3. * 0.4 * Vs * r * r, J_perp = J_axis + 2. * Vs * 4. * r * r;
    check(relative(rod.volume, 3. * Vs) < 1e-11, "rod of touching spheres: volume", rod.volume, 3. * Vs);
    check(relative(rod.principal_inertia[0], J_axis) < 1e-10, "rod: axial inertia",
          rod.principal_inertia[0], J_axis);
    check(relative(rod.principal_inertia[2], J_perp) < 1e-10, "rod: transverse inertia",
          rod.principal_inertia[2], J_perp);
    check(relative(rod.bounding_radius(), 3. * r) < 1e-12, "rod: bounding radius",
          rod.bounding_radius(), 3. * r);
    for (const ClumpTemplate &t : {tetrahedron_clump(r, 0.), cube_clump(r, 0.)})
      {
        const double n = t.members.size();
        check(relative(t.volume, n * Vs) < 1e-10, (t.name + " touching: volume").c_str(), t.volume, n * Vs);
        check(relative(t.principal_inertia[2], t.principal_inertia[0]) < 1e-9,
              (t.name + ": isotropic").c_str(), t.principal_inertia[2], t.principal_inertia[0]);
        // Touching spheres: n spheres' surface, so (pi d_v^2) / (n 4 pi r^2) = n^(-1/3).
        const double psi = std::pow(n, -1. / 3.);
        check(relative(t.sphericity(), psi) < 1e-10, (t.name + " touching: sphericity").c_str(),
              t.sphericity(), psi);
      }
    const ClumpTemplate tet = tetrahedron_clump(r, 0.3);
    std::printf("tetrahedron, overlap 0.3: volume %.6g of 4 V_s, equivalent diameter %.6g r, "
                "bounding radius %.6g r, sphericity %.6g\n",
                tet.volume / (4. * Vs), tet.volume_equivalent_diameter() / r, tet.bounding_radius() / r,
                tet.sphericity());
    check(tet.sphericity() > std::pow(4., -1. / 3.) && tet.sphericity() < 1.,
          "tetrahedron overlapping: sphericity between the touching one's and 1", tet.sphericity(),
          1.);
    check(tet.volume < 4. * Vs && tet.volume > Vs, "tetrahedron overlapping: volume", tet.volume, 4. * Vs);
    const double placed = r + 2. * r * 0.7 * std::sqrt(3.) / (2. * std::sqrt(2.));
    check(relative(tet.bounding_radius(), placed) < 1e-12, "tetrahedron: bounding radius",
          tet.bounding_radius(), placed);
  }
} // namespace

int main()
{
  check_one_member();
  check_asymmetric();
  check_built_in();
  if (sluice::unit::failures == 0)
    std::printf("clump template: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
