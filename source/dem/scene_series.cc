// The files a DEM scene writes as it runs (see the header).

#include <sluice/dem/clump_output.h>
#include <sluice/dem/mesh_load_columns.h>
#include <sluice/dem/particle_csv.h>
#include <sluice/dem/particle_stream.h>
#include <sluice/dem/scene_series.h>
#include <sluice/dem/wear_and_breakage.h>

#include <cmath>
#include <fstream>

namespace sluice
{
  GlobalState reduce_state(const DemSystem &dem, MPI_Comm comm)
  {
    const ParticleStorage   &P           = dem.particles;
    const std::vector<Vec3> &wall_forces = dem.wall_forces;
    const MeshWallLoads     &loads       = dem.mesh_loads;
    const std::size_t n_meshes = loads.power.size(), meshes_at = 5 + 3 * wall_forces.size();
    std::vector<double> sums(meshes_at + 4 * n_meshes, 0.);
    if (dem.clumps)
      {
        // A clump scene's particles are its bodies.
        const ParticleStorage &B = dem.clumps->bodies;
        for (unsigned int b = 0; b < B.n_local; ++b)
          sums[0] += 0.5 * B.mass[b] * norm_square(B.velocity[b]);
        sums[1] = dem.clumps->rotational_energy();
        sums[4] = B.n_local;
      }
    else
      {
        for (unsigned int i = 0; i < P.n_local; ++i)
          {
            sums[0] += 0.5 * P.mass[i] * norm_square(P.velocity[i]);
            sums[1] += 0.5 / P.inverse_inertia[i] * norm_square(P.angular_velocity[i]);
          }
        sums[4] = P.n_local;
      }
    sums[2] = dem.stats.n_particle_contacts;
    sums[3] = dem.stats.n_wall_contacts;
    for (unsigned int w = 0; w < wall_forces.size(); ++w)
      for (unsigned int d = 0; d < 3; ++d)
        sums[5 + 3 * w + d] = wall_forces[w][d];
    for (std::size_t m = 0; m < n_meshes; ++m)
      {
        for (unsigned int d = 0; d < 3; ++d)
          sums[meshes_at + 4 * m + d] = loads.torque[m][d];
        sums[meshes_at + 4 * m + 3] = loads.power[m];
      }
    std::vector<double> global(sums.size());
    MPI_Allreduce(sums.data(), global.data(), sums.size(), MPI_DOUBLE, MPI_SUM, comm);
    GlobalState g;
    g.translational_energy = global[0];
    g.rotational_energy    = global[1];
    g.n_contacts           = std::round(global[2]);
    g.n_wall_contacts      = global[3];
    g.n_particles          = static_cast<unsigned long long>(global[4]);
    g.wall_forces.resize(wall_forces.size());
    for (unsigned int w = 0; w < wall_forces.size(); ++w)
      g.wall_forces[w] = Vec3(global[5 + 3 * w], global[6 + 3 * w], global[7 + 3 * w]);
    for (std::size_t m = 0; m < n_meshes; ++m)
      {
        const double *t = &global[meshes_at + 4 * m];
        g.mesh_loads.torque.emplace_back(t[0], t[1], t[2]);
        g.mesh_loads.power.push_back(t[3]);
      }
    MPI_Allreduce(&dem.stats.max_overlap_ratio, &g.max_overlap_ratio, 1, MPI_DOUBLE, MPI_MAX,
                  comm);
    return g;
  }

  ParticleFieldRegistry snapshot_fields(const DemSystem &dem)
  {
    return dem.clumps ? member_output_fields(dem.fields) : dem.fields;
  }

  void write_snapshot(ParticleOutput &vtu, const DemSystem &dem, const double time)
  {
    if (dem.clumps)
      vtu.write(member_snapshot(dem.particles, *dem.clumps, dem.fields), time);
    else
      vtu.write(dem.particles, time);
  }

  void write_particle_dump(const DemSystem &dem, const double time, const std::string &directory,
                           const std::string &base_name, const unsigned int index)
  {
    if (dem.clumps)
      {
        write_member_csv(dem.particles, *dem.clumps, time, directory, base_name, index, dem.comm);
        write_body_csv(*dem.clumps, time, directory, base_name, index, dem.comm);
      }
    else
      write_particle_csv(dem.particles, time, directory, base_name, index, dem.comm);
  }

  SceneSeries::SceneSeries(const SceneParameters &p, const DemSystem &dem,
                           const std::string &directory, const bool restart,
                           const SceneRecords &records, WearAndBreakage &wear,
                           ParticleStream &stream)
    : p(p), directory(directory), wear(wear), stream(stream)
    , vtu(directory, p.base_name, dem.rank, dem.n_ranks, snapshot_fields(dem))
    , csv_path(directory + "/" + p.base_name + ".csv")
    , next_vtu(records.number("next_vtu", 0.)), next_csv(records.number("next_csv", 0.))
    , next_dump(records.number("next_dump", 0.)), last_dump(records.number("last_dump", -1.))
    , dumps(records.number("dumps", 0.))
  {
    const bool root = dem.rank == 0;
    vtu.index().restore(records.all("snapshot"));
    for (const MeshWall &m : dem.walls.meshes())
      {
        mesh_vtu.emplace_back(directory, p.base_name, m.name(), root);
        mesh_vtu.back().index().restore(records.all("mesh_snapshot_" + m.name()));
      }
    if (p.csv_interval > 0.)
      {
        std::string header = "time,kinetic_energy_translational,kinetic_energy_rotational,"
                             "contacts,wall_contacts,max_overlap_ratio";
        for (unsigned int w = 0; w < dem.walls.n_walls(); ++w)
          header += "," + dem.walls.name(w) + "_fx," + dem.walls.name(w) + "_fy," +
                    dem.walls.name(w) + "_fz";
        // A mesh's torque about its motion origin and the power it puts in.
        for (const MeshWall &m : dem.walls.meshes())
          header += mesh_load_header(m.name());
        csv.open(csv_path, header, root, restart, dem.time());
        wear.open_csv(directory, p.base_name, restart, dem.time(), dem.comm);
        stream.open_csv(directory, p.base_name, restart, dem.time(), dem.comm);
      }
  }

  void SceneSeries::dump_particles(const double time, const DemSystem &dem)
  {
    write_particle_dump(dem, time, directory, p.base_name, dumps++);
    last_dump = time;
  }

  void SceneSeries::write_csv_row(const double time, const DemSystem &dem)
  {
    const GlobalState g = reduce_state(dem, dem.comm);
    if (csv.is_open())
      {
        std::ofstream &row = csv.row();
        row << time << "," << g.translational_energy << "," << g.rotational_energy << ","
            << g.n_contacts << "," << g.n_wall_contacts << "," << g.max_overlap_ratio;
        for (const auto &f : g.wall_forces)
          row << "," << f.x << "," << f.y << "," << f.z;
        for (std::size_t m = 0; m < g.mesh_loads.power.size(); ++m)
          write_mesh_load(row, g.mesh_loads.torque[m], g.mesh_loads.power[m]);
        csv.end_row();
      }
    wear.write_rows(time, dem.handler_particles(), dem.comm);
    stream.write_row(time, dem);
  }

  void SceneSeries::write(const double time, const bool force, const DemSystem &dem)
  {
    const double half_step = 0.5 * dem.dt;
    if (p.particle_csv_interval > 0. && (time >= next_dump - half_step || force))
      {
        dump_particles(time, dem);
        next_dump += p.particle_csv_interval;
      }
    if (p.vtu_interval > 0. && (time >= next_vtu - half_step || force))
      {
        write_snapshot(vtu, dem, time);
        const auto wear_fields = wear.mesh_fields(dem.walls, dem.comm);
        for (unsigned int m = 0; m < mesh_vtu.size(); ++m)
          mesh_vtu[m].write(dem.walls.meshes()[m].mesh(), time, wear_fields[m]);
        next_vtu += p.vtu_interval;
      }
    if (p.csv_interval > 0. && (time >= next_csv - half_step || force))
      {
        write_csv_row(time, dem);
        next_csv += p.csv_interval;
      }
  }

  void SceneSeries::dump_final(const double time, const DemSystem &dem)
  {
    if (p.particle_csv_interval > 0. && last_dump < time)
      dump_particles(time, dem);
  }

  std::vector<std::string> SceneSeries::write_at_stop(const double time, const DemSystem &dem)
  {
    write(time, true, dem);
    std::vector<std::string> written;
    if (p.vtu_interval > 0.)
      {
        written.push_back(directory + "/" + p.base_name + ".pvd");
        for (const MeshWall &m : dem.walls.meshes())
          written.push_back(directory + "/" + p.base_name + "_" + m.name() + ".pvd");
      }
    if (p.csv_interval > 0.)
      written.push_back(csv_path);
    if (p.particle_csv_interval > 0.)
      written.push_back(particle_csv_path(directory, p.base_name, dumps - 1));
    return written;
  }

  void SceneSeries::add_records(SceneRecords &r, const DemSystem &dem) const
  {
    r.set("next_vtu", next_vtu);
    r.set("next_csv", next_csv);
    r.set("next_dump", next_dump);
    r.set("dumps", dumps);
    r.set("last_dump", last_dump);
    r.add_all("snapshot", vtu.index().to_text());
    for (unsigned int m = 0; m < mesh_vtu.size(); ++m)
      r.add_all("mesh_snapshot_" + dem.walls.meshes()[m].name(), mesh_vtu[m].index().to_text());
  }
} // namespace sluice
