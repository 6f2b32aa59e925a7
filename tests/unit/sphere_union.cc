// Moments of a union of spheres (dem/sphere_union.h), the clumps' mass
// properties, against closed forms:
// - one sphere: V = 4/3 pi R^3, centroid, J = 2/5 V R^2;
// - two equal spheres overlapping along x, along z and along an oblique axis:
//   V = 2 V_s - V_lens, J about the axis 2 (2/5 V_s R^2) - 2 J_cap (the cap's
//   J = pi h^3 (20 R^2 - 15 R h + 3 h^2) / 30);
// - two unequal spheres: the lens volume and the centroid from the caps';
// - a well-separated dimer (parallel axes);
// - identical twins count once;
// - a tetrahedral clump (triple overlaps): the principal moments unchanged by
//   a rotation and a shift, and the quadrature converged (16 x 4 against
//   32 x 8 points).
// The union's shadow along a direction (sphere_union_shadow_area), against
// the area of two overlapping disks (2 pi R^2 less the lens
// 2 R^2 acos(c / 2R) - (c / 2) sqrt(4 R^2 - c^2) at projected distance c, and
// the general two-radius lens), from every side, and a tetrahedron's shadow
// against counting points of a fine grid; a rod seen end-on, whose disks are
// twins to round-off, casts one disk's shadow.

#include <sluice/dem/sphere_union.h>

#include "check.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace sluice;
using sluice::unit::check;

namespace
{
  double sphere_volume(const double R) { return 4. / 3. * M_PI * R * R * R; }
  double cap_volume(const double R, const double h) { return M_PI * h * h * (3. * R - h) / 3.; }
  double cap_axial_inertia(const double R, const double h)
  {
    return M_PI * h * h * h * (20. * R * R - 15. * R * h + 3. * h * h) / 30.;
  }

  double relative(const double a, const double b) { return std::abs(a - b) / std::abs(b); }

  void check_one_sphere()
  {
    const double             R = 0.7;
    const SphereUnionMoments m = sphere_union_moments({Vec3(0.1, 0.2, 0.3)}, {R});
    const double             V = sphere_volume(R);
    check(relative(m.volume, V) < 1e-12, "one sphere: volume", m.volume, V);
    check((m.centroid - Eigen::Vector3d(0.1, 0.2, 0.3)).norm() < 1e-13, "one sphere: centroid",
          m.centroid.x(), 0.1);
    const Eigen::Matrix3d J = 0.4 * V * R * R * Eigen::Matrix3d::Identity();
    check((m.inertia - J).norm() < 1e-12 * J.norm(), "one sphere: inertia", m.inertia(0, 0),
          J(0, 0));
    const double S = 4. * M_PI * R * R;
    check(relative(m.surface_area, S) < 1e-12, "one sphere: surface area", m.surface_area, S);
  }

  /// Two equal spheres (R = 1, centres d = 1.2 apart) along 'axis'.
  void check_equal_lens(const Eigen::Vector3d &axis, const char *name)
  {
    const double          R = 1., d = 1.2, h = R - 0.5 * d;
    const Eigen::Vector3d a = 0.5 * d * axis.normalized(), c(0.3, -0.2, 0.5);
    const SphereUnionMoments m = sphere_union_moments(
      {Vec3(c.x() + a.x(), c.y() + a.y(), c.z() + a.z()), Vec3(c.x() - a.x(), c.y() - a.y(), c.z() - a.z())},
      {R, R});
    const double V_lens = M_PI * (4. * R + d) * (2. * R - d) * (2. * R - d) / 12.;
    const double V      = 2. * sphere_volume(R) - V_lens;
    const double J_axis = 2. * 0.4 * sphere_volume(R) * R * R - 2. * cap_axial_inertia(R, h);
    const Eigen::Vector3d u = axis.normalized();
    std::printf("lens along %s: volume error %.1e, axial inertia error %.1e\n", name,
                relative(m.volume, V), relative(u.dot(m.inertia * u), J_axis));
    check(relative(cap_volume(R, h) * 2., V_lens) < 1e-14, "lens = two caps", 2. * cap_volume(R, h),
          V_lens);
    check(relative(m.volume, V) < 1e-9, "equal lens: volume", m.volume, V);
    check((m.centroid - c).norm() < 1e-9, "equal lens: centroid", m.centroid.norm(), c.norm());
    check(relative(u.dot(m.inertia * u), J_axis) < 1e-9, "equal lens: axial inertia",
          u.dot(m.inertia * u), J_axis);
    // Each sphere loses the cap of height h inside the other, of area 2 pi R h.
    const double S = 2. * (4. * M_PI * R * R - 2. * M_PI * R * h);
    std::printf("lens along %s: surface area error %.1e\n", name, relative(m.surface_area, S));
    check(relative(m.surface_area, S) < 1e-9, "equal lens: surface area", m.surface_area, S);
  }

  void check_unequal_lens()
  {
    const double R = 1., r = 0.6, d = 1.1; // centres at x = 0 and x = d
    const SphereUnionMoments m = sphere_union_moments({Vec3(0, 0, 0), Vec3(d, 0, 0)}, {R, r});
    const double V_lens = M_PI * std::pow(R + r - d, 2) *
                          (d * d + 2. * d * r - 3. * r * r + 2. * d * R + 6. * r * R - 3. * R * R) /
                          (12. * d);
    const double h1 = (r - R + d) * (r + R - d) / (2. * d), h2 = (R - r + d) * (R + r - d) / (2. * d);
    const double x1 = 3. * std::pow(2. * R - h1, 2) / (4. * (3. * R - h1));
    const double x2 = d - 3. * std::pow(2. * r - h2, 2) / (4. * (3. * r - h2));
    const double V  = sphere_volume(R) + sphere_volume(r) - V_lens;
    const double x  = (sphere_volume(r) * d - cap_volume(R, h1) * x1 - cap_volume(r, h2) * x2) / V;
    check(relative(cap_volume(R, h1) + cap_volume(r, h2), V_lens) < 1e-13, "unequal lens = caps",
          cap_volume(R, h1) + cap_volume(r, h2), V_lens);
    check(relative(m.volume, V) < 1e-9, "unequal lens: volume", m.volume, V);
    check(std::abs(m.centroid.x() - x) < 1e-9, "unequal lens: centroid", m.centroid.x(), x);
    const double S = 4. * M_PI * (R * R + r * r) - 2. * M_PI * (R * h1 + r * h2);
    check(relative(m.surface_area, S) < 1e-9, "unequal lens: surface area", m.surface_area, S);
  }

  void check_dimer_and_twins()
  {
    const double             R = 1., s = 1.5;
    const SphereUnionMoments m = sphere_union_moments({Vec3(-s, 0, 0), Vec3(s, 0, 0)}, {R, R});
    const double             Vs = sphere_volume(R);
    check(relative(m.volume, 2. * Vs) < 1e-12, "dimer: volume", m.volume, 2. * Vs);
    check(relative(m.inertia(0, 0), 0.8 * Vs * R * R) < 1e-11, "dimer: axial inertia",
          m.inertia(0, 0), 0.8 * Vs * R * R);
    const double J_perp = 2. * (0.4 * Vs * R * R + Vs * s * s);
    check(relative(m.inertia(1, 1), J_perp) < 1e-11, "dimer: transverse inertia",
          m.inertia(1, 1), J_perp);
    const SphereUnionMoments twins = sphere_union_moments({Vec3(1, 2, 3), Vec3(1, 2, 3)}, {R, R});
    check(relative(twins.volume, Vs) < 1e-12, "twins count once", twins.volume, Vs);
    check(relative(m.surface_area, 8. * M_PI * R * R) < 1e-11, "dimer: surface area",
          m.surface_area, 8. * M_PI * R * R);
    check(relative(twins.surface_area, 4. * M_PI * R * R) < 1e-12, "twins: surface area once",
          twins.surface_area, 4. * M_PI * R * R);
  }

  void check_tetrahedron()
  {
    // Unit spheres on a regular tetrahedron of edge 1.2: every pair overlaps,
    // and the triples do.
    const double             e = 1.2;
    std::vector<Eigen::Vector3d> v = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    for (auto &p : v)
      p *= e / (2. * std::sqrt(2.));
    const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, -1., 0.5).normalized()).toRotationMatrix();
    std::vector<Vec3> plain, turned;
    for (const auto &p : v)
      {
        plain.emplace_back(p.x(), p.y(), p.z());
        const Eigen::Vector3d q = rotation * p + Eigen::Vector3d(0.4, -0.3, 2.);
        turned.emplace_back(q.x(), q.y(), q.z());
      }
    const std::vector<double> radii(4, 1.);
    const SphereUnionMoments  a = sphere_union_moments(plain, radii);
    const SphereUnionMoments  b = sphere_union_moments(turned, radii);
    const SphereUnionMoments  fine = sphere_union_moments(plain, radii, 32, 8);
    const Eigen::Vector3d ea = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(a.inertia).eigenvalues();
    const Eigen::Vector3d eb = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(b.inertia).eigenvalues();
    std::printf("tetrahedron: volume %.12f (%.12f with 32 x 8 points, %.12f of four spheres), "
                "principal moments %.10f %.10f %.10f\n",
                a.volume, fine.volume, 4. * sphere_volume(1.), ea[0], ea[1], ea[2]);
    check(relative(a.volume, b.volume) < 1e-9, "tetrahedron: volume unchanged by a rotation",
          b.volume, a.volume);
    check((ea - eb).norm() < 1e-9 * ea.norm(), "tetrahedron: principal moments unchanged",
          eb[0], ea[0]);
    check(relative(a.volume, fine.volume) < 1e-10, "tetrahedron: quadrature converged",
          a.volume, fine.volume);
    check((a.inertia - fine.inertia).norm() < 1e-10 * fine.inertia.norm(),
          "tetrahedron: inertia converged", a.inertia(0, 0), fine.inertia(0, 0));
    check(a.centroid.norm() < 1e-10, "tetrahedron: centroid at the centre", a.centroid.norm(), 0.);
    check(std::abs(ea[2] - ea[0]) < 1e-9 * ea[0], "tetrahedron: isotropic inertia", ea[2], ea[0]);
    // Surface: four spheres less the six lenses' caps (two per pair, each of
    // height 1 - e/2); the triple regions lie inside every sphere's caps and
    // are removed twice, so this bounds the area from below.
    const double caps = 6. * 2. * 2. * M_PI * (1. - 0.5 * e);
    std::printf("tetrahedron: surface area %.12f (%.12f with 32 x 8 points; four spheres less "
                "the pair caps %.12f)\n", a.surface_area, fine.surface_area,
                16. * M_PI - caps);
    check(relative(a.surface_area, fine.surface_area) < 1e-9, "tetrahedron: area converged",
          a.surface_area, fine.surface_area);
    check(a.surface_area > 16. * M_PI - caps && a.surface_area < 16. * M_PI,
          "tetrahedron: area between the caps' bound and four spheres", a.surface_area,
          16. * M_PI - caps);
  }
  /// The area common to two disks of radii a, b whose centres are c apart.
  double lens_area(const double a, const double b, const double c)
  {
    if (c >= a + b)
      return 0.;
    if (c <= std::abs(a - b))
      return M_PI * std::min(a, b) * std::min(a, b);
    const double alpha = std::acos((c * c + a * a - b * b) / (2. * c * a));
    const double beta  = std::acos((c * c + b * b - a * a) / (2. * c * b));
    return a * a * (alpha - 0.5 * std::sin(2. * alpha)) + b * b * (beta - 0.5 * std::sin(2. * beta));
  }

  void check_shadows()
  {
    // One sphere: pi R^2 from anywhere.
    const double R = 0.7;
    for (const Vec3 n : {Vec3(0, 0, 1), Vec3(1, -2, 0.3), Vec3(-1, 0, 0)})
      check(relative(sphere_union_shadow_area({Vec3(0.1, 0.2, 0.3)}, {R}, n), M_PI * R * R) <
              1e-14,
            "shadow: one sphere", sphere_union_shadow_area({Vec3(0.1, 0.2, 0.3)}, {R}, n),
            M_PI * R * R);
    // Two spheres of radii 1 and 0.6, 1.1 apart along a = (1, 1, 1)/sqrt(3),
    // seen at angle t from a: two disks at c = 1.1 sin t.
    const Vec3   a = (1. / std::sqrt(3.)) * Vec3(1, 1, 1), o(0.2, -0.1, 0.4);
    const Vec3   b = (1. / std::sqrt(2.)) * Vec3(1, -1, 0); // across a
    const double r1 = 1., r2 = 0.6, d = 1.1;
    double       worst = 0.;
    for (const double t : {0., 0.1, 0.5, 1.0, M_PI / 2, 2.5, M_PI})
      {
        const Vec3   n = std::cos(t) * a + std::sin(t) * b;
        const double c = d * std::abs(std::sin(t));
        const double exact = M_PI * (r1 * r1 + r2 * r2) - lens_area(r1, r2, c);
        const double area  = sphere_union_shadow_area({o, o + d * a}, {r1, r2}, n);
        worst              = std::max(worst, relative(area, exact));
      }
    check(worst < 1e-13, "shadow: two spheres from every side", worst, 0.);
    // A rod of three seen end-on, and tilted by a hair: the disks are twins
    // to round-off (a body frame from an eigensolver is off the axis by
    // 1e-21 m), and the shadow is one disk.
    const std::vector<Vec3> rod = {Vec3(-0.64, 1e-17, 0), Vec3(0, 1e-17, 0), Vec3(0.64, 1e-17, 0)};
    double rod_worst = 0.;
    for (const double tilt : {0., 1e-17, 1e-15, 1e-12})
      rod_worst = std::max(rod_worst,
                           relative(sphere_union_shadow_area(rod, {0.4, 0.4, 0.4}, Vec3(1, tilt, 0)),
                                    M_PI * 0.16));
    check(rod_worst < 1e-12, "shadow: a rod end-on, tilted by a hair", rod_worst, 0.);
    // A tetrahedral clump's shadow against a grid count (spacing 1/1000).
    const double e = 1.5; // edge, radius 1: overlapping pairs
    const std::vector<Vec3> centres = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1),
                                       Vec3(-1, -1, 1)};
    std::vector<Vec3> scaled;
    for (const Vec3 &c : centres)
      scaled.push_back((e / (2. * std::sqrt(2.))) * c);
    const std::vector<double> radii(4, 1.);
    const Vec3 n = (1. / std::sqrt(1. + 0.09 + 0.49)) * Vec3(1, 0.3, -0.7);
    const Vec3 u0 = cross(n, Vec3(0, 0, 1)), u = (1. / norm(u0)) * u0, v = cross(n, u);
    const double h = 1e-3;
    long         inside = 0;
    for (double x = -3.; x < 3.; x += h)
      for (double y = -3.; y < 3.; y += h)
        for (const Vec3 &c : scaled)
          {
            const double dx = x + 0.5 * h - dot(c, u), dy = y + 0.5 * h - dot(c, v);
            if (dx * dx + dy * dy < 1.)
              {
                ++inside;
                break;
              }
          }
    const double counted = inside * h * h, area = sphere_union_shadow_area(scaled, radii, n);
    std::printf("tetrahedron: shadow %.9f, grid count %.9f\n", area, counted);
    check(relative(area, counted) < 1e-5, "shadow: tetrahedron against a grid count", area,
          counted);
  }
} // namespace

int main()
{
  check_one_sphere();
  check_equal_lens(Eigen::Vector3d(1, 0, 0), "x");
  check_equal_lens(Eigen::Vector3d(0, 0, 1), "z");
  check_equal_lens(Eigen::Vector3d(1, -2, 0.7), "an oblique axis");
  check_unequal_lens();
  check_dimer_and_twins();
  check_tetrahedron();
  check_shadows();
  if (sluice::unit::failures == 0)
    std::printf("sphere union: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
