// Triangle meshes and the closest point on a triangle:
// - the closest point of 20,000 random points is no farther than the best of
//   a dense sampling of the triangle, lies in the region it names, and the
//   region is the expected one at points placed in each of the seven;
// - a unit cube written as ASCII STL and as binary STL reads as 12 triangles
//   on 8 welded vertices, closed, every edge shared by two triangles, area 6,
//   outward normals; the placement (scale, rotation, offset) moves it exactly;
// - vertices 1e-12 apart are welded; a generator's round-off at 2 pi too;
// - binned into a cell grid, every triangle within reach of a point is among
//   the candidates of the point's cell (against brute force, 20,000 points);
// - written as a .vtu, the cube's points, triangles and per-triangle fields
//   decode back to the values written;
// - bad files stop with InputError naming the file and the facet: not an STL,
//   a NaN vertex, a degenerate facet, an open surface where a closed one is
//   asked for.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/mesh_output.h>
#include <sluice/dem/triangle_bins.h>
#include <sluice/dem/triangle_geometry.h>
#include <sluice/dem/triangle_mesh.h>

#include "check.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  using Facets = std::vector<std::array<Vec3, 3>>;

  /// The unit cube [0, 1]^3, two triangles a face, counter-clockwise seen
  /// from outside (normals outward).
  Facets unit_cube()
  {
    const auto v = [](int i, int j, int k) { return Vec3(i, j, k); };
    Facets     f;
    const auto quad = [&](const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d) {
      f.push_back({{a, b, c}});
      f.push_back({{a, c, d}});
    };
    quad(v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0)); // z = 0, normal -z
    quad(v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)); // z = 1, +z
    quad(v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1)); // y = 0, -y
    quad(v(0, 1, 0), v(0, 1, 1), v(1, 1, 1), v(1, 1, 0)); // y = 1, +y
    quad(v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0)); // x = 0, -x
    quad(v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1)); // x = 1, +x
    return f;
  }

  void write_ascii(const std::string &file, const Facets &facets, const std::string &bad = "")
  {
    std::ofstream out(file);
    out.precision(17);
    out << "solid cube\n";
    for (std::size_t k = 0; k < facets.size(); ++k)
      {
        out << "facet normal 0 0 0\n outer loop\n";
        for (const Vec3 &p : facets[k])
          out << "  vertex " << p.x << " " << p.y << " " << (k == 4 && !bad.empty() ? bad : std::to_string(p.z)) << "\n";
        out << " endloop\nendfacet\n";
      }
    out << "endsolid cube\n";
  }

  void write_binary(const std::string &file, const Facets &facets)
  {
    std::ofstream out(file, std::ios::binary);
    char          header[80] = "solid (a binary file may start like an ASCII one)";
    out.write(header, 80);
    const std::uint32_t n = facets.size();
    out.write(reinterpret_cast<const char *>(&n), 4);
    for (const auto &f : facets)
      {
        float values[12] = {0.f, 0.f, 0.f};
        for (unsigned int v = 0; v < 3; ++v)
          for (unsigned int d = 0; d < 3; ++d)
            values[3 + 3 * v + d] = static_cast<float>(f[v][d]);
        out.write(reinterpret_cast<const char *>(values), 48);
        const std::uint16_t attribute = 0;
        out.write(reinterpret_cast<const char *>(&attribute), 2);
      }
  }

  /// The cube as gmsh writes it (format 2.2 or 4.1): its 8 corners as nodes
  /// numbered from 10, a line and a point element to be skipped, and the 12
  /// triangles.
  void write_gmsh(const std::string &file, const Facets &facets, const bool v4,
                  const std::string &format = "")
  {
    std::vector<Vec3> corners;
    std::vector<std::array<int, 3>> tri;
    for (const auto &f : facets)
      {
        std::array<int, 3> t{};
        for (unsigned int v = 0; v < 3; ++v)
          {
            unsigned int k = 0;
            while (k < corners.size() && norm(corners[k] - f[v]) > 0.)
              ++k;
            if (k == corners.size())
              corners.push_back(f[v]);
            t[v] = 10 + k;
          }
        tri.push_back(t);
      }
    std::ofstream out(file);
    out << "$MeshFormat\n" << (format.empty() ? (v4 ? "4.1 0 8" : "2.2 0 8") : format)
        << "\n$EndMeshFormat\n$Nodes\n";
    if (v4)
      {
        out << "1 " << corners.size() << " 10 " << 9 + corners.size() << "\n2 1 0 "
            << corners.size() << "\n";
        for (unsigned int k = 0; k < corners.size(); ++k)
          out << 10 + k << "\n";
        for (const Vec3 &c : corners)
          out << c.x << " " << c.y << " " << c.z << "\n";
        out << "$EndNodes\n$Elements\n3 " << tri.size() + 2 << " 1 " << tri.size() + 2
            << "\n0 1 15 1\n1 10\n1 1 1 1\n2 10 11\n2 1 2 " << tri.size() << "\n";
        for (unsigned int e = 0; e < tri.size(); ++e)
          out << 3 + e << " " << tri[e][0] << " " << tri[e][1] << " " << tri[e][2] << "\n";
      }
    else
      {
        out << corners.size() << "\n";
        for (unsigned int k = 0; k < corners.size(); ++k)
          out << 10 + k << " " << corners[k].x << " " << corners[k].y << " " << corners[k].z
              << "\n";
        out << "$EndNodes\n$Elements\n" << tri.size() + 2 << "\n1 15 2 0 1 10\n2 1 2 0 1 10 11\n";
        for (unsigned int e = 0; e < tri.size(); ++e)
          out << 3 + e << " 2 2 0 1 " << tri[e][0] << " " << tri[e][1] << " " << tri[e][2]
              << "\n";
      }
    out << "$EndElements\n";
  }

  /// The drum of ../shared/peers/liggghts/make_drum_stl.py: a closed cylinder
  /// of radius 0.05 m from y = 0 to 0.03 m, n segments, normals inward.
  Facets drum_facets(const unsigned int n)
  {
    const double       R = 0.05, L = 0.03;
    const auto         rim = [&](const unsigned int k, const double y) {
      const double a = 2. * M_PI * k / n;
      return Vec3(R * std::cos(a), y, R * std::sin(a));
    };
    Facets drum;
    for (unsigned int k = 0; k < n; ++k)
      {
        drum.push_back({{rim(k, 0.), rim(k + 1, 0.), rim(k, L)}});
        drum.push_back({{rim(k + 1, 0.), rim(k + 1, L), rim(k, L)}});
        drum.push_back({{Vec3(0., 0., 0.), rim(k + 1, 0.), rim(k, 0.)}});
        drum.push_back({{Vec3(0., L, 0.), rim(k, L), rim(k + 1, L)}});
      }
    return drum;
  }

  void check_cube(const TriangleMesh &m, const double side, const char *what)
  {
    check(m.size() == 12 && m.vertices.size() == 8, what, m.vertices.size(), 8);
    check(m.n_open_edges == 0 && m.n_nonmanifold_edges == 0, "a closed cube has no open edge",
          m.n_open_edges, 0);
    for (const auto &n : m.neighbours)
      for (const unsigned int t : n)
        check(t != TriangleMesh::none, "every edge of the cube has a neighbour", 0, 0);
    check(std::abs(m.total_area() - 6. * side * side) < 1e-12 * side * side, "cube area",
          m.total_area(), 6. * side * side);
  }

  /// Expects an InputError whose message contains every one of 'parts'.
  template <typename F>
  void expect_error(F &&f, const std::vector<std::string> &parts, const char *what)
  {
    try
      {
        f();
        check(false, what, 0, 1);
      }
    catch (const InputError &e)
      {
        bool all = true;
        for (const auto &p : parts)
          all = all && std::string(e.what()).find(p) != std::string::npos;
        if (!all)
          std::printf("message: %s\n", e.what());
        check(all, what, 0, 0);
        std::printf("%-28s %s\n", what, e.what());
      }
  }

  void closest_points()
  {
    const Vec3 a(0.1, -0.2, 0.3), b(1.3, 0.1, -0.2), c(0.2, 0.9, 0.4);
    std::mt19937_64                        rng(7);
    std::uniform_real_distribution<double> u(-1.5, 2.5);
    double                                 worst = 0.;
    for (unsigned int n = 0; n < 20000; ++n)
      {
        const Vec3         p(u(rng), u(rng), u(rng));
        const ClosestPoint q = closest_point_on_triangle(p, a, b, c);
        double             best = 1e300;
        for (unsigned int i = 0; i <= 60; ++i)
          for (unsigned int j = 0; i + j <= 60; ++j)
            best = std::min(best, norm(p - (a + (i / 60.) * (b - a) + (j / 60.) * (c - a))));
        worst = std::max(worst, norm(p - q.point) - best);
      }
    check(worst <= 1e-14, "no sample of the triangle is closer than its closest point", worst, 0.);
    // One point in each region: vertex, edge and face regions.
    const Vec3 n = cross(b - a, c - a), centre = (1. / 3.) * (a + b + c);
    const auto region = [&](const Vec3 &p) { return closest_point_on_triangle(p, a, b, c).region; };
    check(region(a + 0.5 * (a - centre)) == TriangleRegion::vertex_a, "vertex a region", 0, 0);
    check(region(b + 0.5 * (b - centre)) == TriangleRegion::vertex_b, "vertex b region", 0, 0);
    check(region(c + 0.5 * (c - centre)) == TriangleRegion::vertex_c, "vertex c region", 0, 0);
    const auto outside = [&](const Vec3 &p, const Vec3 &q) {
      const Vec3 m = 0.5 * (p + q);
      return m + 0.3 * (m - centre) + 0.1 * n;
    };
    check(region(outside(a, b)) == TriangleRegion::edge_ab, "edge ab region", 0, 0);
    check(region(outside(b, c)) == TriangleRegion::edge_bc, "edge bc region", 0, 0);
    check(region(outside(c, a)) == TriangleRegion::edge_ca, "edge ca region", 0, 0);
    const ClosestPoint above = closest_point_on_triangle(centre + 0.7 * n, a, b, c);
    check(above.region == TriangleRegion::face && norm(above.point - centre) < 1e-15,
          "a point above the face: the face, at its foot", norm(above.point - centre), 0.);
    std::printf("closest point: worst excess over a dense sampling %.2e\n", worst);
  }

  void cubes()
  {
    const Facets cube = unit_cube();
    write_ascii("unit_triangle_mesh_cube.stl", cube);
    write_binary("unit_triangle_mesh_cube_binary.stl", cube);
    const TriangleMesh ascii =
      read_triangle_mesh("unit_triangle_mesh_cube.stl", MeshPlacement(), true, "test");
    check_cube(ascii, 1., "ASCII cube: 12 triangles on 8 vertices");
    const TriangleMesh binary =
      read_triangle_mesh("unit_triangle_mesh_cube_binary.stl", MeshPlacement(), true, "test");
    check_cube(binary, 1., "binary cube: 12 triangles on 8 vertices");
    for (const bool v4 : {false, true})
      {
        const std::string file = v4 ? "unit_triangle_mesh_cube41.msh" : "unit_triangle_mesh_cube22.msh";
        write_gmsh(file, cube, v4);
        const TriangleMesh msh = read_triangle_mesh(file, MeshPlacement(), true, "test");
        check_cube(msh, 1., v4 ? "gmsh 4.1 cube" : "gmsh 2.2 cube");
        for (unsigned int t = 0; t < msh.size(); ++t)
          check(norm(msh.normals[t] - ascii.normals[t]) < 1e-15, "gmsh keeps the orientation", t, 0);
      }
    // Outward normals: each points away from the centre.
    for (unsigned int t = 0; t < ascii.size(); ++t)
      check(dot(ascii.normals[t], ascii.vertices[ascii.triangles[t][0]] - Vec3(0.5, 0.5, 0.5)) > 0.,
            "outward normal", t, 0);

    // Scale 0.01, a quarter turn about z, then an offset: (1, 0, 0) -> (0, 0.01, 0) + offset.
    MeshPlacement place;
    place.scale  = 0.01;
    place.angle  = M_PI / 2.;
    place.offset = Vec3(1., 2., 3.);
    const TriangleMesh placed =
      read_triangle_mesh("unit_triangle_mesh_cube.stl", place, true, "test");
    check_cube(placed, 0.01, "placed cube");
    bool found = false;
    for (const Vec3 &v : placed.vertices)
      found = found || norm(v - Vec3(1., 2.01, 3.)) < 1e-15;
    check(found, "(1, 0, 0) placed at (1, 2.01, 3)", 0, 0);

    // Welding: a copy of a vertex 1e-12 away is the same vertex.
    Facets nudged = cube;
    nudged[5][1] += Vec3(1e-12, -1e-12, 0.);
    check_cube(make_triangle_mesh(nudged, true, "nudged"), 1., "vertices 1e-12 apart weld");

    // A closed drum as ../shared/peers/liggghts/make_drum_stl.py writes it: the
    // last segment ends at angle 2 pi, where sin gives -2.4e-16, not 0.
    const unsigned int n           = 24;
    const TriangleMesh closed_drum = make_triangle_mesh(drum_facets(n), true, "drum");
    check(closed_drum.vertices.size() == 2 * n + 2 && closed_drum.n_open_edges == 0,
          "the drum's seam at 2 pi welds: 2 n + 2 vertices, closed", closed_drum.vertices.size(),
          2 * n + 2);
  }

  /// A drum of 96 segments binned into cells as large as the reach: every
  /// triangle within reach of a point is in the point's cell list.
  void binning()
  {
    const TriangleMesh mesh = make_triangle_mesh(drum_facets(96), true, "drum");
    const double       reach = 0.004;
    TriangleBins       bins(Vec3(-0.05, 0., -0.05), Vec3(0.004, 0.003, 0.004), {{25, 10, 25}});
    bins.build(mesh, reach);
    std::mt19937_64                        rng(5);
    std::uniform_real_distribution<double> u(-0.06, 0.06), w(-0.01, 0.04);
    unsigned int                           missed = 0;
    double                                 listed = 0., near = 0.;
    for (unsigned int k = 0; k < 20000; ++k)
      {
        const Vec3 x(u(rng), w(rng), u(rng)); // also outside the grid
        std::vector<bool> in_list(mesh.size(), false);
        for (const unsigned int *t = bins.begin(x); t != bins.end(x); ++t)
          in_list[*t] = true;
        listed += bins.end(x) - bins.begin(x);
        for (unsigned int t = 0; t < mesh.size(); ++t)
          {
            const auto &v = mesh.triangles[t];
            const double d = norm(x - closest_point_on_triangle(x, mesh.vertices[v[0]],
                                                                mesh.vertices[v[1]],
                                                                mesh.vertices[v[2]])
                                        .point);
            if (d < reach)
              {
                near += 1.;
                missed += !in_list[t];
              }
          }
      }
    check(missed == 0, "every triangle within reach is a candidate of the point's cell", missed, 0);
    std::printf("binning: %zu entries for %u triangles; per point %.1f candidates, %.2f within "
                "reach; none missed\n",
                bins.n_entries(), mesh.size(), listed / 20000., near / 20000.);
  }

  /// The doubles of the <DataArray Name="name"> in a .vtu written by
  /// write_mesh_vtu (base64 of a 32-bit byte count and the values).
  std::vector<double> read_array(const std::string &text, const std::string &name)
  {
    const std::size_t at    = text.find("Name=\"" + name + "\"");
    const std::size_t begin = text.find('>', at) + 1, end = text.find('<', begin);
    std::string       code;
    for (const char c : text.substr(begin, end - begin))
      if (!std::isspace(static_cast<unsigned char>(c)))
        code += c;
    const std::string alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::vector<unsigned char> bytes;
    for (std::size_t i = 0; i + 3 < code.size(); i += 4)
      {
        unsigned int v = 0, pad = 0;
        for (unsigned int k = 0; k < 4; ++k)
          {
            const char c = code[i + k];
            pad += c == '=';
            v = (v << 6) | (c == '=' ? 0u : static_cast<unsigned int>(alphabet.find(c)));
          }
        for (unsigned int k = 0; k < 3 - pad; ++k)
          bytes.push_back((v >> (16 - 8 * k)) & 255);
      }
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data(), 4);
    std::vector<double> values(n / sizeof(double));
    std::memcpy(values.data(), bytes.data() + 4, n);
    return values;
  }

  void vtu_output()
  {
    const TriangleMesh  cube = make_triangle_mesh(unit_cube(), true, "cube");
    std::vector<double> wear(cube.size());
    for (unsigned int t = 0; t < cube.size(); ++t)
      wear[t] = 1e-6 * (t + 1);
    write_mesh_vtu("unit_triangle_mesh_cube.vtu", cube, {{"wear_depth", wear}});
    std::ifstream     in("unit_triangle_mesh_cube.vtu");
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    check(text.find("NumberOfPoints=\"8\" NumberOfCells=\"12\"") != std::string::npos,
          "the .vtu has 8 points and 12 triangles", 0, 0);
    check(read_array(text, "area") == cube.areas, "areas decode to the values written", 0, 0);
    check(read_array(text, "wear_depth") == wear, "a triangle field decodes back", 0, 0);
    const std::vector<double> points = read_array(text, "position");
    bool same = points.size() == 24;
    for (unsigned int v = 0; same && v < 8; ++v)
      same = norm(Vec3(points[3 * v], points[3 * v + 1], points[3 * v + 2]) - cube.vertices[v]) == 0.;
    check(same, "the points decode to the vertices", points.size(), 24);
    std::printf("vtu: cube written and read back (points, areas, a triangle field)\n");
  }

  void bad_files()
  {
    {
      std::ofstream("unit_triangle_mesh_text.stl") << "hello, this is not a mesh\n";
    }
    expect_error([] { read_triangle_mesh("unit_triangle_mesh_text.stl", MeshPlacement(), false, "ctx"); },
                 {"ctx", "unit_triangle_mesh_text.stl", "not a triangle mesh"}, "not a mesh file");
    write_ascii("unit_triangle_mesh_nan.stl", unit_cube(), "nan");
    expect_error([] { read_triangle_mesh("unit_triangle_mesh_nan.stl", MeshPlacement(), false, "ctx"); },
                 {"unit_triangle_mesh_nan.stl", "facet 5", "not a finite number"}, "NaN vertex");
    Facets degenerate = unit_cube();
    degenerate[7] = {{Vec3(0., 0., 0.), Vec3(1., 1., 1.), Vec3(2., 2., 2.)}};
    expect_error([&] { make_triangle_mesh(degenerate, false, "file 'x.stl'"); },
                 {"x.stl", "facet 8", "degenerate"}, "degenerate facet");
    Facets open = unit_cube();
    open.resize(10); // the x = 1 face removed
    expect_error([&] { make_triangle_mesh(open, true, "file 'open.stl'"); },
                 {"open.stl", "not a closed surface", "4 open edges"}, "open surface, closed asked");
    const TriangleMesh accepted = make_triangle_mesh(open, false, "open.stl");
    check(accepted.n_open_edges == 4, "an open box has 4 open edges", accepted.n_open_edges, 4);
    write_gmsh("unit_triangle_mesh_binary.msh", unit_cube(), true, "4.1 1 8");
    expect_error([] { read_triangle_mesh("unit_triangle_mesh_binary.msh", MeshPlacement(), false, "ctx"); },
                 {"unit_triangle_mesh_binary.msh", "binary .msh"}, "binary .msh");
    write_gmsh("unit_triangle_mesh_v3.msh", unit_cube(), false, "3.0 0 8");
    expect_error([] { read_triangle_mesh("unit_triangle_mesh_v3.msh", MeshPlacement(), false, "ctx"); },
                 {"unit_triangle_mesh_v3.msh", "format 3"}, ".msh format 3");
    expect_error([] { read_triangle_mesh("no_such_file.stl", MeshPlacement(), false, "ctx"); },
                 {"no_such_file.stl", "cannot be read"}, "missing file");
  }
} // namespace

int main()
{
  closest_points();
  cubes();
  binning();
  vtu_output();
  bad_files();
  return sluice::unit::failures == 0 ? 0 : 1;
}
