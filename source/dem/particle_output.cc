#include <sluice/core/output_files.h>
#include <sluice/core/vtk_arrays.h>
#include <sluice/dem/particle_output.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace sluice
{
  namespace
  {
    std::vector<double> flatten(const std::vector<Vec3> &v, const unsigned int n)
    {
      std::vector<double> out(3 * n);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          out[3 * i + d] = v[i][d];
      return out;
    }

    using vtk::data_array;

    const char *point_fields[][3] = {{"velocity", "Float64", "3"},
                                     {"angular_velocity", "Float64", "3"},
                                     {"radius", "Float64", "1"},
                                     {"type", "Int32", "1"},
                                     {"force", "Float64", "3"},
                                     {"coordination_number", "Int32", "1"},
                                     {"id", "Int64", "1"}};
  } // namespace

  ParticleOutput::ParticleOutput(const std::string &directory_, const std::string &base_name_,
                                 const unsigned int rank_, const unsigned int n_ranks_,
                                 const ParticleFieldRegistry &registry)
    : directory(directory_), base_name(base_name_), rank(rank_), n_ranks(n_ranks_)
    , series(directory_ + "/" + base_name_ + ".pvd", rank_ == 0)
  {
    for (const ParticleField &f : registry.fields())
      if (f.output)
        fields.push_back(f);
  }

  void ParticleOutput::write(const ParticleStorage &particles, const double time)
  {
    // The index is replaced whole, after the files it lists.
    series.add(time, write_files(particles, series.size()));
  }

  std::string ParticleOutput::write_files(const ParticleStorage &particles,
                                          const unsigned int     index) const
  {
    const unsigned int n     = particles.n_local;
    std::ostringstream stem;
    stem << base_name << "_" << std::setw(5) << std::setfill('0') << index;

    {
      std::ostringstream piece_name;
      piece_name << directory << "/" << stem.str() << "_" << std::setw(4) << std::setfill('0')
                 << rank << ".vtu";
      std::ofstream out(piece_name.str());
      check_stream(out, piece_name.str());
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
             "header_type=\"UInt32\">\n"
          << "  <UnstructuredGrid>\n"
          << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
          << "      <Points>\n";
      data_array(out, "position", 3, flatten(particles.position, n));
      out << "      </Points>\n      <Cells>\n";
      std::vector<std::int64_t> connectivity(n), offsets(n);
      std::vector<std::uint8_t> types(n, 1); // VTK_VERTEX
      std::vector<std::int32_t> type(n), coordination(n);
      std::vector<std::int64_t> ids(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          connectivity[i] = i;
          offsets[i]      = i + 1;
          type[i]         = particles.type[i];
          coordination[i] = particles.coordination[i];
          ids[i]          = particles.id[i];
        }
      data_array(out, "connectivity", 1, connectivity);
      data_array(out, "offsets", 1, offsets);
      data_array(out, "types", 1, types);
      out << "      </Cells>\n      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
      data_array(out, "velocity", 3, flatten(particles.velocity, n));
      data_array(out, "angular_velocity", 3, flatten(particles.angular_velocity, n));
      data_array(out, "radius", 1,
                 std::vector<double>(particles.radius.begin(), particles.radius.begin() + n));
      data_array(out, "type", 1, type);
      data_array(out, "force", 3, flatten(particles.force, n));
      data_array(out, "coordination_number", 1, coordination);
      data_array(out, "id", 1, ids);
      for (const ParticleField &f : fields)
        {
          std::vector<double> values(f.size * n);
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int c = 0; c < f.size; ++c)
              values[f.size * i + c] = particles.extra_of(i)[f.offset + c];
          data_array(out, f.name, f.size, values);
        }
      out << "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
      out.flush();
      check_stream(out, piece_name.str());
    }

    if (rank != 0)
      return stem.str() + ".pvtu";

    std::ostringstream pvtu;
    pvtu << "<?xml version=\"1.0\"?>\n"
         << "<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
            "header_type=\"UInt32\">\n"
         << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
         << "    <PPoints><PDataArray type=\"Float64\" Name=\"position\" "
            "NumberOfComponents=\"3\"/></PPoints>\n"
         << "    <PPointData Scalars=\"radius\" Vectors=\"velocity\">\n";
    for (const auto &f : point_fields)
      pvtu << "      <PDataArray type=\"" << f[1] << "\" Name=\"" << f[0]
           << "\" NumberOfComponents=\"" << f[2] << "\"/>\n";
    for (const ParticleField &f : fields)
      pvtu << "      <PDataArray type=\"Float64\" Name=\"" << f.name
           << "\" NumberOfComponents=\"" << f.size << "\"/>\n";
    pvtu << "    </PPointData>\n";
    for (unsigned int r = 0; r < n_ranks; ++r)
      pvtu << "    <Piece Source=\"" << stem.str() << "_" << std::setw(4) << std::setfill('0')
           << r << ".vtu\"/>\n";
    pvtu << "  </PUnstructuredGrid>\n</VTKFile>\n";
    write_file_atomically(directory + "/" + stem.str() + ".pvtu", pvtu.str());
    return stem.str() + ".pvtu";
  }
} // namespace sluice
