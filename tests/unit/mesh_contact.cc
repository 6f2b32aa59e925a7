// One contact per patch between a sphere and a triangle mesh:
// - above (and below) a flat plate of jittered triangles of very different
//   sizes, anywhere, including right above edges and vertices: exactly one
//   contact, with the plate's normal and the overlap r - h (no double force
//   where the sphere crosses an edge or a vertex);
// - across a convex ridge: exactly one contact everywhere, at the distance to
//   the surface (no spurious edge force beside the ridge, the ridge once);
// - in the concave corner of three faces: one contact per face, each with its
//   plane's normal and overlap, as three plane walls give;
// - outside a cube's vertex, edge and face: one contact each.

#include <sluice/dem/mesh_contact.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace sluice;
using sluice::unit::check;

namespace
{
  using Facets = std::vector<std::array<Vec3, 3>>;

  std::vector<unsigned int> all(const TriangleMesh &m)
  {
    std::vector<unsigned int> t(m.size());
    for (unsigned int k = 0; k < m.size(); ++k)
      t[k] = k;
    return t;
  }

  /// The distance from x to the surface, by brute force over the triangles.
  double distance_to(const TriangleMesh &m, const Vec3 &x)
  {
    double best = 1e300;
    for (const auto &t : m.triangles)
      best = std::min(best, norm(x - closest_point_on_triangle(x, m.vertices[t[0]],
                                                               m.vertices[t[1]],
                                                               m.vertices[t[2]])
                                       .point));
    return best;
  }

  /// The plate [0, 1]^2 at z = 0 from an n x n grid whose inner vertices are
  /// moved by up to 0.45 of a cell (triangles of very different sizes), the
  /// diagonals alternating.
  TriangleMesh jittered_plate(const unsigned int n)
  {
    std::mt19937_64                        rng(3);
    std::uniform_real_distribution<double> u(-0.45, 0.45);
    std::vector<Vec3>                      p((n + 1) * (n + 1));
    for (unsigned int j = 0; j <= n; ++j)
      for (unsigned int i = 0; i <= n; ++i)
        {
          const bool inner = i > 0 && i < n && j > 0 && j < n;
          p[j * (n + 1) + i] = Vec3((i + (inner ? u(rng) : 0.)) / n, (j + (inner ? u(rng) : 0.)) / n, 0.);
        }
    Facets f;
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        {
          const Vec3 &a = p[j * (n + 1) + i], &b = p[j * (n + 1) + i + 1],
                     &c = p[(j + 1) * (n + 1) + i + 1], &d = p[(j + 1) * (n + 1) + i];
          if ((i + j) % 2 == 0)
            {
              f.push_back({{a, b, c}});
              f.push_back({{a, c, d}});
            }
          else
            {
              f.push_back({{a, b, d}});
              f.push_back({{b, c, d}});
            }
        }
    return make_triangle_mesh(f, false, "plate");
  }

  void flat_plate()
  {
    const TriangleMesh plate = jittered_plate(6);
    const auto         cand  = all(plate);
    const double       r     = 0.1;
    std::mt19937_64                        rng(11);
    std::uniform_real_distribution<double> u(0.15, 0.85), h(1e-3, 0.099);
    std::vector<Vec3>                      centres;
    for (unsigned int k = 0; k < 20000; ++k)
      centres.emplace_back(u(rng), u(rng), (k % 2 ? 1. : -1.) * h(rng));
    // Right above every inner vertex and every edge's midpoint.
    for (const Vec3 &v : plate.vertices)
      if (v.x > 0.1 && v.x < 0.9 && v.y > 0.1 && v.y < 0.9)
        centres.emplace_back(v.x, v.y, 0.05);
    for (const auto &t : plate.triangles)
      for (unsigned int e = 0; e < 3; ++e)
        {
          const Vec3 m = 0.5 * (plate.vertices[t[e]] + plate.vertices[t[(e + 1) % 3]]);
          if (m.x > 0.1 && m.x < 0.9 && m.y > 0.1 && m.y < 0.9)
            centres.emplace_back(m.x, m.y, 0.03);
        }
    unsigned int             wrong_count = 0;
    double                   worst_normal = 0., worst_overlap = 0.;
    std::vector<MeshContact> contacts;
    for (const Vec3 &x : centres)
      {
        contacts.clear();
        mesh_contacts(plate, x, r, cand, contacts);
        if (contacts.size() != 1)
          {
            ++wrong_count;
            continue;
          }
        const Vec3 n_expected(0., 0., x.z > 0. ? 1. : -1.);
        worst_normal  = std::max(worst_normal, norm(contacts[0].normal - n_expected));
        worst_overlap = std::max(worst_overlap, std::abs(contacts[0].overlap - (r - std::abs(x.z))));
      }
    std::printf("plate: %zu centres (above and below, over edges and vertices): %u without "
                "exactly one contact; normal error %.1e, overlap error %.1e m\n",
                centres.size(), wrong_count, worst_normal, worst_overlap);
    check(wrong_count == 0, "exactly one contact on a flat plate", wrong_count, 0);
    check(worst_normal < 1e-12, "the plate's normal", worst_normal, 0.);
    check(worst_overlap < 1e-12, "overlap r - h on the plate", worst_overlap, 0.);
  }

  void convex_ridge()
  {
    // z = -0.5 |y|, the ridge along x at y = 0.
    const auto v = [](double x, double y) { return Vec3(x, y, -0.5 * std::abs(y)); };
    Facets     f;
    f.push_back({{v(-1, 0), v(1, 0), v(1, 1)}});
    f.push_back({{v(-1, 0), v(1, 1), v(-1, 1)}});
    f.push_back({{v(-1, -1), v(1, -1), v(1, 0)}});
    f.push_back({{v(-1, -1), v(1, 0), v(-1, 0)}});
    const TriangleMesh ridge = make_triangle_mesh(f, false, "ridge");
    const auto         cand  = all(ridge);
    const double       r     = 0.2; // every centre below reaches the surface
    unsigned int       wrong = 0, at_ridge = 0;
    double             worst = 0.;
    std::vector<MeshContact> contacts;
    for (int k = -200; k <= 200; ++k)
      {
        const Vec3 x(0.1, 0.3 * k / 200., 0.02);
        contacts.clear();
        mesh_contacts(ridge, x, r, cand, contacts);
        if (contacts.size() != 1)
          {
            ++wrong;
            continue;
          }
        at_ridge += contacts[0].region != TriangleRegion::face;
        worst = std::max(worst, std::abs(contacts[0].overlap - (r - distance_to(ridge, x))));
      }
    std::printf("ridge: 401 centres across it: %u without exactly one contact, %u on the ridge "
                "itself, overlap error %.1e m\n", wrong, at_ridge, worst);
    check(wrong == 0, "exactly one contact across a convex ridge", wrong, 0);
    check(at_ridge > 0 && at_ridge < 401, "the ridge's own contacts lie between the faces'",
          at_ridge, 100);
    check(worst < 1e-14, "overlap at the distance to the surface", worst, 0.);
  }

  void concave_corner()
  {
    // The inside of the corner of three faces x = 0, y = 0, z = 0 (unit squares).
    Facets     f;
    const auto quad = [&](const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d) {
      f.push_back({{a, b, c}});
      f.push_back({{a, c, d}});
    };
    const Vec3 o, ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
    quad(o, ex, ex + ey, ey); // z = 0
    quad(o, ez, ez + ex, ex); // y = 0
    quad(o, ey, ey + ez, ez); // x = 0
    const TriangleMesh corner = make_triangle_mesh(f, false, "corner");
    const double       r      = 0.1;
    std::vector<MeshContact> contacts;
    const Vec3               x(0.03, 0.05, 0.07);
    mesh_contacts(corner, x, r, all(corner), contacts);
    check(contacts.size() == 3, "three contacts in a concave corner", contacts.size(), 3);
    double worst = 0.;
    for (const MeshContact &c : contacts)
      {
        // Each is a plane wall's contact: along an axis, overlap r - that coordinate.
        unsigned int axis = std::abs(c.normal.x) > 0.5 ? 0 : std::abs(c.normal.y) > 0.5 ? 1 : 2;
        Vec3         e;
        e[axis] = 1.;
        worst   = std::max({worst, norm(c.normal - e), std::abs(c.overlap - (r - x[axis]))});
      }
    check(worst < 1e-15, "each corner contact as its plane wall's", worst, 0.);
    contacts.clear();
    mesh_contacts(corner, Vec3(0.03, 0.05, 0.5), r, all(corner), contacts);
    check(contacts.size() == 2, "two contacts along a concave edge", contacts.size(), 2);
    std::printf("corner: 3 contacts in the corner, 2 along its edge, each as a plane's (%.1e)\n",
                worst);
  }

  void cube_outside()
  {
    Facets     f;
    const auto quad = [&](const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d) {
      f.push_back({{a, b, c}});
      f.push_back({{a, c, d}});
    };
    const auto v = [](int i, int j, int k) { return Vec3(i, j, k); };
    quad(v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0));
    quad(v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1));
    quad(v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1));
    quad(v(0, 1, 0), v(0, 1, 1), v(1, 1, 1), v(1, 1, 0));
    quad(v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0));
    quad(v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1));
    const TriangleMesh cube = make_triangle_mesh(f, true, "cube");
    const double       r = 0.1, a = 0.04;
    std::vector<MeshContact> contacts;
    for (const Vec3 &x : {Vec3(1 + a, 1 + a, 1 + a), Vec3(1 + a, 1 + a, 0.5), Vec3(1 + a, 0.5, 0.5),
                          Vec3(1 + a, 0.5, 0.5 + 1e-17), Vec3(0.5, 0.5, 1 + a)})
      {
        contacts.clear();
        mesh_contacts(cube, x, r, all(cube), contacts);
        const double expected = r - distance_to(cube, x);
        check(contacts.size() == 1 && std::abs(contacts[0].overlap - expected) < 1e-15,
              "one contact outside a cube's vertex, edge or face", contacts.size(), 1);
      }
    std::printf("cube: one contact outside a vertex, an edge and faces\n");
  }
} // namespace

int main()
{
  flat_plate();
  convex_ridge();
  concave_corner();
  cube_outside();
  return sluice::unit::failures == 0 ? 0 : 1;
}
