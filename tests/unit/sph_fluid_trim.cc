// The fluid block cut to the solid walls (sph/sph_fluid_trim.h):
// - the ray-parity test on a closed cube of 12 triangles agrees with
//   |x_i| < L at 20,000 random points, and at points on the planes of its
//   faces and diagonals (where a ray along an axis would graze edges);
// - a lattice over a box larger than the cube keeps exactly the points whose
//   distance to every face is at least R (points laid exactly R from a face
//   among them), leaves the wall particles, and keeps every array in step;
// - a tilted plane leaves out the points behind it or nearer than R.

#include <sluice/sph/sph_fluid_trim.h>

#include "check.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double L = 0.004;
  const PeriodicBox box(Vec3(-0.01, -0.01, -0.01), Vec3(0.01, 0.01, 0.01), {{false, false, false}});

  /// The closed cube [-L, L]^3, two triangles a face, as a gmsh 2.2 file.
  std::string cube_mesh_file()
  {
    const std::string path =
      (std::filesystem::temp_directory_path() / "sluice_unit_sph_fluid_trim_cube.msh").string();
    std::ofstream out(path);
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n";
    for (unsigned int v = 0; v < 8; ++v)
      out << v + 1 << " " << (v & 1 ? L : -L) << " " << (v & 2 ? L : -L) << " "
          << (v & 4 ? L : -L) << "\n";
    // Faces as vertex quadruples (nodes counted from 1), each split in two.
    const unsigned int faces[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                                      {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
    out << "$EndNodes\n$Elements\n12\n";
    for (unsigned int f = 0; f < 6; ++f)
      {
        const unsigned int *q = faces[f];
        out << 2 * f + 1 << " 2 2 1 1 " << q[0] << " " << q[1] << " " << q[2] << "\n"
            << 2 * f + 2 << " 2 2 1 1 " << q[0] << " " << q[2] << " " << q[3] << "\n";
      }
    out << "$EndElements\n";
    return path;
  }

  bool inside_cube(const Vec3 &x)
  {
    return std::abs(x.x) < L && std::abs(x.y) < L && std::abs(x.z) < L;
  }
} // namespace

int main()
{
  MeshWallParameters cube;
  cube.file   = cube_mesh_file();
  cube.name   = "cube";
  cube.closed = true;
  WallSet             walls({}, {cube}, box, "test");
  const TriangleMesh &mesh = walls.meshes()[0].mesh();

  {
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> u(-2. * L, 2. * L);
    unsigned int                           wrong = 0, n = 0;
    for (unsigned int k = 0; k < 20000; ++k, ++n)
      {
        const Vec3 x(u(random), u(random), u(random));
        wrong += inside_closed_mesh(mesh, x) != inside_cube(x);
      }
    // On the planes of faces, of the diagonals, and on the axes.
    for (const Vec3 &x : {Vec3(0., 0., 0.), Vec3(0.5 * L, 0., 0.), Vec3(0., 0.5 * L, 0.5 * L),
                          Vec3(0.3 * L, 0.3 * L, 0.3 * L), Vec3(1.5 * L, 0., 0.),
                          Vec3(0., 0., -1.5 * L), Vec3(1.5 * L, 1.5 * L, 0.),
                          Vec3(-0.5 * L, 0.5 * L, 0.)})
      {
        wrong += inside_closed_mesh(mesh, x) != inside_cube(x);
        ++n;
      }
    std::printf("inside the cube: %u of %u points wrong\n", wrong, n);
    check(wrong == 0, "points the ray parity places wrongly", wrong, 0);
  }

  {
    // A lattice of spacing dx over [-1.5 L, 1.5 L]^3, at (i + 1/2) dx, with
    // L = 4 dx: the points at +-3.5 dx lie exactly R = dx/2 from a face.
    const double dx = L / 4., R = 0.5 * dx;
    SphSetup     setup;
    unsigned int expected = 0, id = 0;
    for (int i = -6; i < 6; ++i)
      for (int j = -6; j < 6; ++j)
        for (int k = -6; k < 6; ++k, ++id)
          {
            const Vec3 x((i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx);
            setup.particles.push_back(id, x, 1e-6, 1000. + id, 1.5 * dx);
            expected += std::abs(x.x) <= L - R + 1e-15 && std::abs(x.y) <= L - R + 1e-15 &&
                        std::abs(x.z) <= L - R + 1e-15;
          }
    setup.particles.push_back(id, Vec3(9 * dx, 0., 0.), 1e-6, 1000., 1.5 * dx, true);
    setup.n_fluid  = id;
    setup.n_walls  = 1;
    setup.particles.n_local = setup.particles.size();
    const unsigned int removed = remove_fluid_beyond_walls(setup, walls, R);
    const SphParticles &P      = setup.particles;
    std::printf("cube lattice: kept %u fluid points (expected %u), removed %u\n",
                setup.n_fluid, expected, removed);
    check(setup.n_fluid == expected, "fluid points kept", setup.n_fluid, expected);
    check(expected == 512, "the 8 x 8 x 8 points inside", expected, 512);
    check(P.size() == expected + 1 && P.n_local == P.size() && P.wall.back() == 1,
          "the wall particle kept, arrays sized", P.size(), expected + 1);
    bool in_step = true;
    for (unsigned int a = 0; a + 1 < P.size(); ++a)
      in_step = in_step && P.density[a] == 1000. + P.id[a] && inside_cube(P.position[a]) &&
                P.smoothing.size() == P.size() && P.porosity.size() == P.size();
    check(in_step, "each kept point carries its own density", in_step, true);
  }

  {
    // A plane through (0, 0, 0.001) with the normal (0, 1, 1)/sqrt 2.
    const Vec3      n(0., 1. / std::sqrt(2.), 1. / std::sqrt(2.)), point(0., 0., 0.001);
    const PlaneWall plane{point, n, 0, "tilted", "", ""};
    WallSet         tilted({plane}, {}, box, "test");
    const double    R = 2.5e-4;
    SphSetup        setup;
    unsigned int    expected = 0, id = 0;
    for (int j = -10; j < 10; ++j)
      for (int k = -10; k < 10; ++k, ++id)
        {
          const Vec3 x(0., (j + 0.5) * 5e-4, (k + 0.5) * 5e-4);
          setup.particles.push_back(id, x, 1e-6, 1000., 1e-3);
          expected += dot(x - point, n) >= R;
        }
    setup.n_fluid           = id;
    setup.particles.n_local = id;
    remove_fluid_beyond_walls(setup, tilted, R);
    std::printf("tilted plane: kept %u of %u (expected %u)\n", setup.n_fluid, id, expected);
    check(setup.n_fluid == expected && expected > 0 && expected < id,
          "points in front of the plane by R or more", setup.n_fluid, expected);
  }
  std::filesystem::remove(cube.file);
  return sluice::unit::failures == 0 ? 0 : 1;
}
