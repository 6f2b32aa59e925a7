// The imported flow field (coupling/imported_field*.h, core/vtu_reader.h):
// - in every supported VTK cell (tetrahedron, voxel, hexahedron, wedge,
//   pyramid), distorted, 2,000 random points inside are found with shape
//   functions that sum to 1 and place the point exactly, and a linear field
//   and its gradient are interpolated exactly; points outside are not found;
// - the analytic vortex files in prm/fields decode to u = Omega e_z x x at
//   every point, in each encoding there (ascii; inline base64 with zlib;
//   appended raw; appended zlib Float32 cell data) and through the search tree;
// - a .pvd of three frames is held before its first and after its last
//   time, blended linearly between them, and with a period wraps from the
//   last frame into the first;
// - bad files stop with InputError naming the file and the array, cell or
//   entry: a missing array, a polyhedron, a NaN, a truncated binary array.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/vtu_reader.h>
#include <sluice/coupling/imported_field.h>
#include <sluice/coupling/imported_field_series.h>
#include <sluice/coupling/vtk_cell_shapes.h>

#include "check.h"

#include <cmath>
#include <fstream>
#include <random>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  /// Reference nodes of each cell type (VTK's parametric corners).
  std::vector<Vec3> reference_nodes(const std::uint8_t type)
  {
    switch (type)
      {
        case 10: return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        case 11: return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                         {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
        case 12: return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
        case 13: return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
        default: return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
      }
  }

  void check_cells()
  {
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> unit(0., 1.), wobble(-0.08, 0.08);
    const Vec3 a(0.3, -1.2, 2.5);
    const double b = 0.7;
    for (const std::uint8_t type : {10, 11, 12, 13, 14})
      {
        // An affine map (with rotation and shear) plus a small distortion of
        // each node, except for the linear cells whose map must stay affine.
        std::vector<Vec3> X = reference_nodes(type);
        for (Vec3 &x : X)
          {
            x = Vec3(0.02 * x.x + 0.004 * x.y, -0.003 * x.x + 0.015 * x.y + 0.002 * x.z,
                     0.001 * x.x + 0.025 * x.z) + Vec3(1., 2., 3.);
            if (type == 11 || type == 12)
              x += 0.004 * Vec3(wobble(rng), wobble(rng), wobble(rng));
          }
        std::vector<double> f;
        for (const Vec3 &x : X)
          f.push_back(dot(a, x) + b);
        unsigned int found = 0, tried = 0;
        for (unsigned int k = 0; k < 2000; ++k)
          {
            // A point of the cell: the map at random reference coordinates.
            Vec3 r(unit(rng), unit(rng), unit(rng));
            if ((type == 10 && r.x + r.y + r.z > 1.) || (type == 13 && r.x + r.y > 1.))
              continue;
            if (type == 14)
              r = Vec3(r.x * (1. - r.z), r.y * (1. - r.z), r.z); // inside the pyramid
            double N[8];
            Vec3   dN[8];
            vtk_cell::shape(type, r, N, dN);
            Vec3 x;
            for (std::size_t n = 0; n < X.size(); ++n)
              x += N[n] * X[n];
            ++tried;
            CellPoint p;
            if (!locate_in_cell(type, X.data(), x, p))
              continue;
            ++found;
            double sum = 0., value = 0.;
            Vec3   placed, gradient;
            for (unsigned int n = 0; n < p.n_nodes; ++n)
              {
                sum += p.N[n];
                placed += p.N[n] * X[n];
                value += p.N[n] * f[n];
                gradient += f[n] * p.gradient[n];
              }
            check(std::abs(sum - 1.) < 1e-12, "shape functions sum to 1", sum, 1.);
            check(norm(placed - x) < 1e-14, "shape functions place the point", norm(placed - x), 0.);
            check(std::abs(value - dot(a, x) - b) < 1e-12, "linear field interpolated", value,
                  dot(a, x) + b);
            check(norm(gradient - a) < 1e-8 * norm(a), "linear field's gradient",
                  norm(gradient - a), 0.);
          }
        check(found == tried && tried > 300, "every inside point found", found, tried);
        // Outside: beyond a face.
        CellPoint p;
        check(!locate_in_cell(type, X.data(), X[0] - Vec3(0.001, 0.001, 0.001), p),
              "a point outside is not found", type, 0.);
      }
  }

  void check_vortex_files(const std::string &fields)
  {
    ImportedFieldArrays arrays;
    arrays.need_pressure = true;
    const double omega = 2.;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> in(-0.099, 0.099), thin(-0.0099, 0.0099);
    for (const auto &[file, tolerance] :
         {std::pair{"vortex_coarse.vtu", 1e-14}, {"vortex_coarse_tets.vtu", 1e-14},
          {"vortex_fine.vtu", 1e-14}, {"vortex_fine_cell_data.vtu", 1e-5}})
      {
        const ImportedField field({fields + "/" + file}, arrays);
        double              worst = 0.;
        long                hint  = -1;
        for (unsigned int k = 0; k < 2000; ++k)
          {
            // Away from the boundary, where cell data averaged onto points
            // lose the linear field's exactness.
            const Vec3 x(0.9 * in(rng), 0.9 * in(rng), thin(rng));
            const CellPoint p = field.geometry()->locate(x, hint);
            check(p.cell >= 0, "a point inside the vortex grid is found", k, 0.);
            if (p.cell < 0)
              continue;
            hint = p.cell;
            ParticleFluidSample s;
            field.evaluate(p, s);
            worst = std::max(worst, norm(s.velocity - omega * Vec3(-x.y, x.x, 0.)) / (omega * 0.1));
            // du_y/dx = Omega, du_x/dy = -Omega.
            worst = std::max(worst, std::abs(s.velocity_gradient[1][0] - omega) / omega);
            worst = std::max(worst, std::abs(s.velocity_gradient[0][1] + omega) / omega);
          }
        check(worst < tolerance, file, worst, 0.);
        const CellPoint outside = field.geometry()->locate(Vec3(0.2, 0., 0.), -1);
        check(outside.cell < 0, "a point beyond the grid is not found", outside.cell, -1);
      }
  }

  /// A single voxel [0,1]^3 with a uniform velocity (u, 0, 0) and p = 0, ascii.
  void write_voxel(const std::string &file, const double u)
  {
    std::ofstream out(file);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
           "<UnstructuredGrid><Piece NumberOfPoints=\"8\" NumberOfCells=\"1\">\n<PointData>\n"
           "<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\">";
    for (int k = 0; k < 8; ++k)
      out << u << " 0 0 ";
    out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"pressure\">0 0 0 0 0 0 0 0"
           "</DataArray>\n</PointData>\n<Points><DataArray type=\"Float64\" "
           "NumberOfComponents=\"3\">0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1</DataArray>"
           "</Points>\n<Cells><DataArray type=\"Int32\" Name=\"connectivity\">0 1 2 3 4 5 6 7"
           "</DataArray><DataArray type=\"Int32\" Name=\"offsets\">8</DataArray>"
           "<DataArray type=\"UInt8\" Name=\"types\">11</DataArray></Cells>\n"
           "</Piece></UnstructuredGrid>\n</VTKFile>\n";
  }

  void check_series()
  {
    // Frames at t = 1, 2, 4 with u = 10, 20, 0.
    write_voxel("series_0.vtu", 10.);
    write_voxel("series_1.vtu", 20.);
    write_voxel("series_2.vtu", 0.);
    std::ofstream("series.pvd")
      << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
         "<Collection>\n<DataSet timestep=\"2\" file=\"series_1.vtu\"/>\n"
         "<DataSet timestep=\"1\" file=\"series_0.vtu\"/>\n"
         "<DataSet timestep=\"4\" file=\"series_2.vtu\"/>\n</Collection>\n</VTKFile>\n";
    ImportedFieldParameters p;
    p.file = "series.pvd";
    const Vec3 x(0.5, 0.5, 0.5);
    for (const double period : {0., 5.})
      {
        p.period = period;
        ImportedFieldSeries series(p, "unit");
        long hint = -1;
        const auto u_at = [&](const double t) {
          series.set_time(t);
          return series.sample(x, hint).velocity.x;
        };
        // Without a period: held at 10 before t = 1 and at 0 after t = 4.
        // With period 5: t = 4..6 blends frame 3 (u = 0) into frame 1 (u = 10).
        const std::vector<std::pair<double, double>> expected =
          period == 0. ? std::vector<std::pair<double, double>>{{0., 10.}, {1., 10.}, {1.5, 15.},
                                                               {2., 20.}, {3., 10.}, {3.5, 5.},
                                                               {4., 0.}, {9., 0.}, {2.5, 15.}} :
                         std::vector<std::pair<double, double>>{{1.5, 15.}, {4.5, 2.5}, {5.5, 7.5},
                                                               {6., 10.}, {8., 10.}, {0.5, 7.5},
                                                               {-2.5, 15.}, {12.5, 15.}, {9.5, 2.5}};
        for (const auto &[t, u] : expected)
          check(std::abs(u_at(t) - u) < 1e-12, period == 0. ? "series held and blended" :
                                                               "periodic series wraps",
                u_at(t), u);
      }
  }

  /// Whether reading 'text' as a .vtu throws InputError mentioning 'word'.
  void check_bad_file(const std::string &text, const std::string &word)
  {
    std::ofstream("bad.vtu") << text;
    ImportedFieldArrays arrays;
    bool               named = false;
    try
      {
        ImportedField field({"bad.vtu"}, arrays);
      }
    catch (const InputError &e)
      {
        const std::string what = e.what();
        named = what.find("bad.vtu") != std::string::npos && what.find(word) != std::string::npos;
        if (!named)
          std::printf("message without '%s': %s\n", word.c_str(), what.c_str());
      }
    check(named, ("bad file named with " + word).c_str(), named, 1.);
  }

  void check_bad_files()
  {
    const std::string head = "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\"><UnstructuredGrid>"
                             "<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\"><PointData>";
    const std::string points =
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\">0 0 0 1 0 0 0 1 0 0 0 1"
      "</DataArray></Points>";
    const auto cells = [](const int type) {
      return "<Cells><DataArray type=\"Int32\" Name=\"connectivity\">0 1 2 3</DataArray>"
             "<DataArray type=\"Int32\" Name=\"offsets\">4</DataArray><DataArray type=\"UInt8\" "
             "Name=\"types\">" + std::to_string(type) + "</DataArray></Cells>";
    };
    const std::string tail = "</Piece></UnstructuredGrid></VTKFile>";
    const std::string u = "<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\">"
                          "1 0 0 1 0 0 1 0 0 1 0 0</DataArray>";
    const std::string p = "<DataArray type=\"Float64\" Name=\"pressure\">0 0 0 0</DataArray>";
    check_bad_file(head + p + "</PointData>" + points + cells(10) + tail, "'velocity'");
    check_bad_file(head + u + p + "</PointData>" + points + cells(42) + tail, "cell 1");
    check_bad_file(head + u + "<DataArray type=\"Float64\" Name=\"pressure\">0 nan 0 0"
                                "</DataArray></PointData>" + points + cells(10) + tail,
                   "'pressure'");
    // A base64 array whose header promises more bytes than follow.
    check_bad_file(head + u + "<DataArray type=\"Float64\" Name=\"pressure\" format=\"binary\">"
                              "AAEAAAAAAAA=</DataArray></PointData>" + points + cells(10) + tail,
                   "'pressure'");
    check_bad_file("<html></html>", "VTKFile");
  }
} // namespace

int main(int argc, char **argv)
{
  if (argc != 2)
    {
      std::printf("usage: unit_imported_field <prm/fields directory>\n");
      return 2;
    }
  check_cells();
  check_vortex_files(argv[1]);
  check_series();
  check_bad_files();
  if (sluice::unit::failures == 0)
    std::printf("imported field: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
