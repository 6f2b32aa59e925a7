// A triangle mesh as a .vtu (see the header).

#include <sluice/core/output_files.h>
#include <sluice/core/vtk_arrays.h>
#include <sluice/dem/mesh_output.h>

#include <cstdint>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace sluice
{
  void write_mesh_vtu(const std::string &path, const TriangleMesh &mesh,
                      const std::vector<TriangleField> &fields)
  {
    const std::size_t n_points = mesh.vertices.size(), n_cells = mesh.size();
    std::vector<double> points(3 * n_points);
    for (std::size_t v = 0; v < n_points; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        points[3 * v + d] = mesh.vertices[v][d];
    std::vector<std::int64_t> connectivity(3 * n_cells), offsets(n_cells);
    for (std::size_t t = 0; t < n_cells; ++t)
      {
        for (unsigned int k = 0; k < 3; ++k)
          connectivity[3 * t + k] = mesh.triangles[t][k];
        offsets[t] = 3 * (t + 1);
      }
    const std::vector<std::uint8_t> types(n_cells, 5); // VTK_TRIANGLE

    std::ostringstream out;
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt32\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\"" << n_cells
        << "\">\n      <Points>\n";
    vtk::data_array(out, "position", 3, points);
    out << "      </Points>\n      <Cells>\n";
    vtk::data_array(out, "connectivity", 1, connectivity);
    vtk::data_array(out, "offsets", 1, offsets);
    vtk::data_array(out, "types", 1, types);
    out << "      </Cells>\n      <CellData Scalars=\"area\">\n";
    vtk::data_array(out, "area", 1, mesh.areas);
    for (const auto &[name, values] : fields)
      {
        if (values.size() != n_cells)
          throw std::logic_error("write_mesh_vtu: field '" + name + "' has " +
                                 std::to_string(values.size()) + " values for " +
                                 std::to_string(n_cells) + " triangles");
        vtk::data_array(out, name, 1, values);
      }
    out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
    write_file_atomically(path, out.str());
  }

  MeshSeries::MeshSeries(const std::string &directory, const std::string &base_name,
                         const std::string &wall_name, const bool writes)
    : directory(directory), prefix(base_name + "_" + wall_name), writes(writes),
      series(directory + "/" + prefix + ".pvd", writes)
  {}

  void MeshSeries::write(const TriangleMesh &mesh, const double time,
                         const std::vector<TriangleField> &fields)
  {
    std::ostringstream name;
    name << prefix << "_" << std::setw(5) << std::setfill('0') << series.size() << ".vtu";
    if (writes)
      write_mesh_vtu(directory + "/" + name.str(), mesh, fields);
    series.add(time, name.str());
  }
} // namespace sluice
