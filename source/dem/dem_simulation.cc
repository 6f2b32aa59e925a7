// The DEM time loop (velocity Verlet, Allen & Tildesley): half kick with the
// forces of the previous step, drift, new forces, second half kick. Velocity-
// dependent forces (dashpots, tangential slip) see the half-step velocities, as in
// LIGGGHTS' nve/sphere.

#include <sluice/core/result_line.h>
#include <sluice/core/output_files.h>
#include <sluice/dem/particle_output.h>
#include <sluice/core/names.h>
#include <sluice/core/progress.h>
#include <sluice/core/scene_records.h>
#include <sluice/core/series_files.h>
#include <sluice/dem/contact_forces.h>
#include <sluice/dem/contact_properties.h>
#include <sluice/dem/dem_checkpoint.h>
#include <sluice/dem/dem_simulation.h>
#include <sluice/dem/dem_system.h>
#include <sluice/dem/insertion.h>
#include <sluice/dem/mesh_output.h>
#include <sluice/dem/energy_balance_validation.h>
#include <sluice/dem/mesh_plane_equivalence.h>
#include <sluice/dem/neighbour_list.h>
#include <sluice/dem/particle_csv.h>
#include <sluice/dem/particle_exchange.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/particle_stream.h>
#include <sluice/dem/validation.h>
#include <sluice/dem/wear_and_breakage.h>
#include <sluice/dem/velocity_verlet.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// Global sums and maxima of the quantities in the .csv time series.
    struct GlobalState
    {
      double translational_energy = 0., rotational_energy = 0.;
      double n_contacts = 0., n_wall_contacts = 0., max_overlap_ratio = 0.;
      unsigned long long n_particles = 0;
      std::vector<Vec3>  wall_forces;
      MeshWallLoads      mesh_loads;
    };

    GlobalState reduce_state(const ParticleStorage &P, const ContactStatistics &stats,
                             const std::vector<Vec3> &wall_forces, const MeshWallLoads &loads,
                             MPI_Comm comm)
    {
      const std::size_t   n_meshes = loads.power.size(), meshes_at = 5 + 3 * wall_forces.size();
      std::vector<double> sums(meshes_at + 4 * n_meshes, 0.);
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          sums[0] += 0.5 * P.mass[i] * norm_square(P.velocity[i]);
          sums[1] += 0.5 / P.inverse_inertia[i] * norm_square(P.angular_velocity[i]);
        }
      sums[2] = stats.n_particle_contacts;
      sums[3] = stats.n_wall_contacts;
      sums[4] = P.n_local;
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
      MPI_Allreduce(&stats.max_overlap_ratio, &g.max_overlap_ratio, 1, MPI_DOUBLE, MPI_MAX, comm);
      return g;
    }
  } // namespace

  int run_dem_scene(const SceneParameters &p, MPI_Comm comm, DemSceneExtension *extension)
  {
    if (p.validation == ValidationCase::mesh_plane_equivalence)
      return run_mesh_plane_equivalence(p, comm);
    if (p.validation == ValidationCase::energy_balance)
      return run_energy_balance_validation(p, comm);
    const auto wall_start = std::chrono::steady_clock::now();
    int        rank, n_ranks;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &n_ranks);
    std::ostream &out = std::cout;

    ParticleFieldRegistry fields = extension ? extension->fields() : ParticleFieldRegistry();
    WearAndBreakage::declare_fields(p, fields);
    DemSystem          dem(p, comm, fields);
    WearAndBreakage    wear(p, dem);
    ParticleStream     stream(p, dem);
    // A restart replaces the state before anything is written: a bad
    // checkpoint stops the run with the output as it was.
    const bool               restart = !p.restart_from.empty();
    std::vector<std::string> restored;
    if (restart)
      restored = load_dem_checkpoint(
        dem, find_checkpoint(p.restart_from, p.output_directory, p.base_name, p.file_name));
    const SceneRecords records(restored);
    if (!wear.set_state(records.numbers("impact_statistics"), comm))
      throw InputError("error: the checkpoint's impact statistics do not fit 'wear and "
                       "breakage' of '" + p.file_name + "'");
    wear.attach_when_due(dem);
    stream.set_state(records.numbers("stream"));
    if (extension)
      {
        extension->set_state(records.numbers("extension"));
        extension->attach(dem);
      }
    ParticleStorage   &particles  = dem.particles;
    ContactStatistics &stats      = dem.stats;
    std::vector<Vec3> &wall_forces = dem.wall_forces;
    const double       dt = dem.dt, skin = dem.skin;
    const unsigned long long n_inserted = dem.n_inserted;

    // ---- Output files: only now that the scene is known to be valid ----
    const bool checkpoints = p.checkpoint_step_interval > 0 || p.checkpoint_time_interval > 0.;
    const bool any_output  = p.vtu_interval > 0. || p.csv_interval > 0. ||
                            p.particle_csv_interval > 0. || checkpoints || p.wear.collect;
    const std::string output_directory =
      any_output ? prepare_output_directory(p.output_directory, {p.base_name}, p.if_output_exists,
                                            restart, p.file_name, comm) :
                   p.output_directory;
    ParticleOutput vtu(output_directory, p.base_name, rank, n_ranks, fields);
    vtu.index().restore(records.all("snapshot"));
    // Each mesh wall's surface, moving with it, at the particles' snapshot times.
    std::vector<MeshSeries> mesh_vtu;
    for (const MeshWall &m : dem.walls.meshes())
      {
        mesh_vtu.emplace_back(output_directory, p.base_name, m.name(), rank == 0);
        mesh_vtu.back().index().restore(records.all("mesh_snapshot_" + m.name()));
      }
    CsvSeries         csv;
    const std::string csv_name = output_directory + "/" + p.base_name + ".csv";
    if (p.csv_interval > 0.)
      {
        std::string header = "time,kinetic_energy_translational,kinetic_energy_rotational,"
                             "contacts,wall_contacts,max_overlap_ratio";
        for (unsigned int w = 0; w < dem.walls.n_walls(); ++w)
          header += "," + dem.walls.name(w) + "_fx," + dem.walls.name(w) + "_fy," +
                    dem.walls.name(w) + "_fz";
        // A mesh's torque about its motion origin and the power it puts in.
        for (const MeshWall &m : dem.walls.meshes())
          header += "," + m.name() + "_torque_x," + m.name() + "_torque_y," + m.name() +
                    "_torque_z," + m.name() + "_power";
        csv.open(csv_name, header, rank == 0, restart, dem.time());
        wear.open_csv(output_directory, p.base_name, restart, dem.time(), comm);
        stream.open_csv(output_directory, p.base_name, restart, dem.time(), comm);
      }

    unsigned int local_min = particles.n_local, local_max = particles.n_local;
    MPI_Allreduce(MPI_IN_PLACE, &local_min, 1, MPI_UNSIGNED, MPI_MIN, comm);
    MPI_Allreduce(MPI_IN_PLACE, &local_max, 1, MPI_UNSIGNED, MPI_MAX, comm);
    if (rank == 0)
      {
        out << "Sluice DEM - scene " << p.file_name << "\n"
            << "  particles: " << n_inserted << ", material types: " << p.n_materials()
            << ", walls: " << dem.walls.n_walls() << ", MPI ranks: " << n_ranks
            << ", background cells: " << dem.exchange->n_cells_global() << "\n"
            << "  particles per rank at the start: " << local_min << " to " << local_max
            << ", ghosts on rank 0: " << particles.n_ghost() << "\n"
            << "  contact law: " << name_of(p.normal_model)
            << ", tangential history: " << (dem.friction ? "yes" : "no (frictionless)")
            << ", rolling resistance: " << name_of(p.rolling_model) << "\n"
            << std::setprecision(4) << "  contact time t_c = " << dem.t_contact
            << " s, Rayleigh time = " << dem.t_rayleigh << " s, time step = " << dt
            << " s (t_c / " << dem.t_contact / dt
            << (p.automatic_time_step && dt < p.time_step_fraction * dem.t_contact ?
                  ", set by the damping" :
                  "")
            << ")\n"
            << "  neighbour skin = " << skin << " m\n";
        if (extension)
          extension->describe(out);
        if (p.vtu_interval > 0.)
          out << "  output: " << output_directory << "/" << p.base_name << ".pvd\n";
        if (p.csv_interval > 0.)
          out << "  output: " << csv_name << "\n";
        out << std::flush;
      }

    ValidationProbe   probe(p, dem.properties, dem.walls, comm);
    probe.set_state(records.numbers("probe"));

    const unsigned long long n_steps =
      static_cast<unsigned long long>(std::ceil(p.end_time / dt - 1e-9));
    double             time      = dem.time();
    double             next_vtu  = records.number("next_vtu", 0.);
    double             next_csv  = records.number("next_csv", 0.);
    double             next_dump = records.number("next_dump", 0.);
    unsigned int       n_dumps   = records.number("dumps", 0.);
    double             last_dump = records.number("last_dump", -1.);
    CheckpointSchedule checkpoint(p, time);
    unsigned long long n_particle_steps = 0;
    ProgressLine       progress(p.progress && rank == 0, p.end_time);

    auto dump_particles = [&]() {
      write_particle_csv(particles, time, output_directory, p.base_name, n_dumps++, comm);
      last_dump = time;
    };
    auto write_output = [&](const bool force) {
      if (p.particle_csv_interval > 0. && (time >= next_dump - 0.5 * dt || force))
        {
          dump_particles();
          next_dump += p.particle_csv_interval;
        }
      if (p.vtu_interval > 0. && (time >= next_vtu - 0.5 * dt || force))
        {
          vtu.write(particles, time);
          const auto wear_fields = wear.mesh_fields(dem.walls, comm);
          for (unsigned int m = 0; m < mesh_vtu.size(); ++m)
            mesh_vtu[m].write(dem.walls.meshes()[m].mesh(), time, wear_fields[m]);
          next_vtu += p.vtu_interval;
        }
      if (p.csv_interval > 0. && (time >= next_csv - 0.5 * dt || force))
        {
          const GlobalState g = reduce_state(particles, stats, wall_forces, dem.mesh_loads, comm);
          if (csv.is_open())
            {
              std::ofstream &row = csv.row();
              row << time << "," << g.translational_energy << "," << g.rotational_energy << ","
                  << g.n_contacts << "," << g.n_wall_contacts << "," << g.max_overlap_ratio;
              for (const auto &f : g.wall_forces)
                row << "," << f.x << "," << f.y << "," << f.z;
              for (std::size_t m = 0; m < g.mesh_loads.power.size(); ++m)
                row << "," << g.mesh_loads.torque[m].x << "," << g.mesh_loads.torque[m].y << ","
                    << g.mesh_loads.torque[m].z << "," << g.mesh_loads.power[m];
              csv.end_row();
            }
          wear.write_rows(time, particles, comm);
          stream.write_row(time, dem);
          next_csv += p.csv_interval;
        }
    };

    // The scene's records a checkpoint keeps, so that the series and probes
    // continue after a restart.
    const auto scene_records = [&]() {
      SceneRecords r;
      r.set("next_vtu", next_vtu);
      r.set("next_csv", next_csv);
      r.set("next_dump", next_dump);
      r.set("dumps", n_dumps);
      r.set("last_dump", last_dump);
      r.set_numbers("probe", probe.state());
      if (stream.active())
        r.set_numbers("stream", stream.state());
      if (extension)
        r.set_numbers("extension", extension->state());
      const std::vector<double> impact_statistics = wear.state(comm);
      if (!impact_statistics.empty())
        r.set_numbers("impact_statistics", impact_statistics);
      r.add_all("snapshot", vtu.index().to_text());
      for (unsigned int m = 0; m < mesh_vtu.size(); ++m)
        r.add_all("mesh_snapshot_" + dem.walls.meshes()[m].name(), mesh_vtu[m].index().to_text());
      return r.lines();
    };

    // A restarted run resumes where the checkpoint was written, just before
    // the stream's turn in that step.
    if (restart)
      stream.after_step(dem);
    // (A restarted run has observed and written its start already.)
    if (!restart)
      {
        if (probe.active())
          probe.observe(time, dt, particles);
        write_output(false);
      }

    const auto        loop_start = std::chrono::steady_clock::now();
    const GravityKick kick{p.gravity};
    for (unsigned long long step = dem.step + 1; step <= n_steps; ++step)
      {
        if (extension)
          extension->advance(dem);
        else
          dem.advance(kick);
        time = dem.time();
        wear.after_step(dem);
        wear.attach_when_due(dem);
        n_particle_steps += particles.n_local;

        if (probe.active())
          probe.observe(time, dt, particles);
        write_output(false);
        if (checkpoint.due(dem.step, time, dt))
          save_dem_checkpoint(dem, checkpoint_path(output_directory, p.base_name, dem.step),
                              scene_records(), p.checkpoints_kept);
        // After the checkpoint: a batch it schedules is the next step's, and
        // a restart plans it again from the same counters.
        stream.after_step(dem);
        // Only rank 0 draws the line, so nothing collective may happen here.
        if (progress.due())
          progress.update(time, step, n_inserted - dem.n_lost);
      }
    progress.finish();
    // The final state is always dumped.
    if (p.particle_csv_interval > 0. && last_dump < time)
      dump_particles();
    const double loop_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();

    // ---- Summary ----
    unsigned int end_min = particles.n_local, end_max = particles.n_local;
    MPI_Allreduce(MPI_IN_PLACE, &end_min, 1, MPI_UNSIGNED, MPI_MIN, comm);
    MPI_Allreduce(MPI_IN_PLACE, &end_max, 1, MPI_UNSIGNED, MPI_MAX, comm);
    const GlobalState final_state = reduce_state(particles, stats, wall_forces, dem.mesh_loads, comm);
    unsigned long long global_particle_steps = 0;
    MPI_Allreduce(&n_particle_steps, &global_particle_steps, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM,
                  comm);
    ValidationResult result;
    if (probe.active())
      result = probe.finish(particles, dem.n_lost, n_inserted);
    std::ostringstream wear_summary;
    wear_summary << std::setprecision(p.summary_precision);
    wear.finish(wear_summary, dem, output_directory, p.base_name);
    if (extension)
      wear_summary << extension->summary(dem);
    const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

    if (rank == 0)
      {
        out << std::setprecision(p.summary_precision);
        out << "final: time=" << time << " steps=" << n_steps
            << " particles=" << final_state.n_particles << " lost=" << dem.n_lost
            << " contacts=" << final_state.n_contacts
            << " wall_contacts=" << final_state.n_wall_contacts
            << " kinetic_energy=" << final_state.translational_energy
            << " rotational_energy=" << final_state.rotational_energy
            << " max_overlap_ratio=" << final_state.max_overlap_ratio << "\n";
        // Rates over the time loop alone (set-up and insertion excluded), as
        // LIGGGHTS reports its 'Loop time'.
        out << std::setprecision(4) << "timing: wall_s=" << wall_s << " loop_s=" << loop_s
            << " steps_per_s=" << n_steps / loop_s
            << " particle_steps_per_s=" << global_particle_steps / loop_s
            << " us_per_particle_step=" << 1e6 * loop_s / std::max(1ull, global_particle_steps)
            << " neighbour_list_builds=" << dem.list.n_builds
            << " repartitions=" << dem.exchange->n_repartitions()
            << " particles_per_rank=" << end_min << ".." << end_max << "\n";
        if (vtu.n_written() > 0)
          out << "output: " << vtu.n_written() << " snapshots in " << output_directory << "/"
              << p.base_name << ".pvd\n";
        for (const MeshWall &m : dem.walls.meshes())
          if (vtu.n_written() > 0)
            out << "output: mesh wall '" << m.name() << "' in " << output_directory << "/"
                << p.base_name << "_" << m.name() << ".pvd\n";
        if (n_dumps > 0)
          out << "output: " << n_dumps << " particle dumps in " << output_directory << "/"
              << p.base_name << "_state_*.csv\n";
        out << std::setprecision(p.summary_precision) << wear_summary.str();
        stream.summary(out, time);
        if (probe.active())
          {
            for (const auto &c : result.checks)
              out << c << "\n";
            write_result_line(out, result.name, result.value, result.reference, result.error,
                              wall_s);
          }
        out << std::flush;
      }
    if (probe.active() && p.validation_tolerance > 0. && result.error > p.validation_tolerance)
      {
        if (rank == 0)
          std::cerr << "sluice: validation error " << result.error << " exceeds the tolerance "
                    << p.validation_tolerance << " set in 'validation/tolerance'\n";
        return 3;
      }
    return extension ? extension->exit_code() : 0;
  }
} // namespace sluice
