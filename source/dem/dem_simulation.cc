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
#include <sluice/dem/clump_validation.h>
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
#include <sluice/dem/scene_series.h>
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
    /// A clump scene's header line: its templates and bodies.
    void describe_clumps(std::ostream &out, const ClumpSystem &clumps,
                         const unsigned long long n_members)
    {
      out << "  clumps: " << clumps.templates.size() << " template(s), " << n_members
          << " member spheres;";
      for (std::size_t k = 0; k < clumps.templates.size(); ++k)
        {
          const ClumpTemplate &t = clumps.templates[k];
          out << (k ? "," : "") << " " << k << ": " << t.name << " of " << t.members.size()
              << ", volume-equivalent diameter " << t.volume_equivalent_diameter()
              << " m, sphericity " << t.sphericity() << ", bounding radius "
              << t.bounding_radius() << " m (at scale 1)";
        }
      out << "\n";
    }

    /// The header's lines, on rank 0 (collective: the particles per rank).
    void print_header(std::ostream &out, const SceneParameters &p, const DemSystem &dem,
                      const std::string &output_directory, const std::string &csv_name,
                      const DemSceneExtension *extension)
    {
      const ParticleStorage &particles = dem.handler_particles();
      unsigned int           local_min = particles.n_local, local_max = particles.n_local;
      MPI_Allreduce(MPI_IN_PLACE, &local_min, 1, MPI_UNSIGNED, MPI_MIN, dem.comm);
      MPI_Allreduce(MPI_IN_PLACE, &local_max, 1, MPI_UNSIGNED, MPI_MAX, dem.comm);
      unsigned long long n_members = dem.particles.n_local;
      MPI_Allreduce(MPI_IN_PLACE, &n_members, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, dem.comm);
      if (dem.rank != 0)
        return;
      const double dt = dem.dt;
      out << "Sluice DEM - scene " << p.file_name << "\n"
          << "  particles: " << dem.n_inserted << ", material types: " << p.n_materials()
          << ", walls: " << dem.walls.n_walls() << ", MPI ranks: " << dem.n_ranks
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
          << "  neighbour skin = " << dem.skin << " m\n";
      if (dem.clumps)
        describe_clumps(out, *dem.clumps, n_members);
      if (extension)
        extension->describe(out);
      if (p.vtu_interval > 0.)
        out << "  output: " << output_directory << "/" << p.base_name << ".pvd\n";
      if (p.csv_interval > 0.)
        out << "  output: " << csv_name << "\n";
      out << std::flush;
    }

    /// What the time loop measured, for the timing line.
    struct LoopTiming
    {
      double             wall_s = 0., loop_s = 0.;
      unsigned long long n_steps = 0, particle_steps = 0; // over all ranks
      unsigned long long local_particle_steps = 0;        // this rank's
    };

    /// The summary's lines, on rank 0 (collective: the final state).
    void print_summary(std::ostream &out, const SceneParameters &p, const DemSystem &dem,
                       const double time, const LoopTiming &timing, const SceneSeries &series,
                       const std::string &output_directory, const std::string &statistics,
                       const ParticleStream &stream)
    {
      const ParticleStorage &particles = dem.handler_particles();
      unsigned int           end_min = particles.n_local, end_max = particles.n_local;
      MPI_Allreduce(MPI_IN_PLACE, &end_min, 1, MPI_UNSIGNED, MPI_MIN, dem.comm);
      MPI_Allreduce(MPI_IN_PLACE, &end_max, 1, MPI_UNSIGNED, MPI_MAX, dem.comm);
      const GlobalState final_state = reduce_state(dem, dem.comm);
      if (dem.rank != 0)
        return;
      out << std::setprecision(p.summary_precision);
      out << "final: time=" << time << " steps=" << timing.n_steps
          << " particles=" << final_state.n_particles << " lost=" << dem.n_lost
          << " contacts=" << final_state.n_contacts
          << " wall_contacts=" << final_state.n_wall_contacts
          << " kinetic_energy=" << final_state.translational_energy
          << " rotational_energy=" << final_state.rotational_energy
          << " max_overlap_ratio=" << final_state.max_overlap_ratio << "\n";
      // Rates over the time loop alone (set-up and insertion excluded), as
      // LIGGGHTS reports its 'Loop time'.
      const double loop_s = timing.loop_s;
      out << std::setprecision(4) << "timing: wall_s=" << timing.wall_s << " loop_s=" << loop_s
          << " steps_per_s=" << timing.n_steps / loop_s
          << " particle_steps_per_s=" << timing.particle_steps / loop_s
          << " us_per_particle_step=" << 1e6 * loop_s / std::max(1ull, timing.particle_steps)
          << " neighbour_list_builds=" << dem.list.n_builds
          << " repartitions=" << dem.exchange->n_repartitions()
          << " particles_per_rank=" << end_min << ".." << end_max << "\n";
      // Rank 0's own particle-steps: its stages' times are its own.
      out << "cost: us per particle-step: "
          << dem.clock.line(static_cast<double>(timing.local_particle_steps), 1e6)
          << "\n";
      if (series.n_snapshots() > 0)
        {
          out << "output: " << series.n_snapshots() << " snapshots in " << output_directory
              << "/" << p.base_name << ".pvd\n";
          for (const MeshWall &m : dem.walls.meshes())
            out << "output: mesh wall '" << m.name() << "' in " << output_directory << "/"
                << p.base_name << "_" << m.name() << ".pvd\n";
        }
      if (series.n_dumps() > 0)
        out << "output: " << series.n_dumps() << " particle dumps in " << output_directory << "/"
            << p.base_name << "_state_*.csv\n";
      out << std::setprecision(p.summary_precision) << statistics;
      stream.summary(out, time);
    }
  } // namespace

  int run_dem_scene(const SceneParameters &p, MPI_Comm comm, DemSceneExtension *extension)
  {
    if (p.validation == ValidationCase::mesh_plane_equivalence)
      return run_mesh_plane_equivalence(p, comm);
    if (p.validation == ValidationCase::energy_balance)
      return run_energy_balance_validation(p, comm);
    const auto    wall_start = std::chrono::steady_clock::now();
    std::ostream &out        = std::cout;

    ParticleFieldRegistry fields = extension ? extension->fields() : ParticleFieldRegistry();
    WearAndBreakage::declare_fields(p, fields);
    DemSystem       dem(p, comm, fields);
    WearAndBreakage wear(p, dem);
    ParticleStream  stream(p, dem);
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
    const double dt = dem.dt;

    // ---- Output files: only now that the scene is known to be valid ----
    const bool checkpoints = p.checkpoint_step_interval > 0 || p.checkpoint_time_interval > 0.;
    const bool any_output  = p.vtu_interval > 0. || p.csv_interval > 0. ||
                            p.particle_csv_interval > 0. || checkpoints || p.wear.collect;
    const std::string output_directory =
      any_output ? prepare_output_directory(p.output_directory, {p.base_name}, p.if_output_exists,
                                            restart, p.file_name, comm) :
                   p.output_directory;
    SceneSeries series(p, dem, output_directory, restart, records, wear, stream);
    print_header(out, p, dem, output_directory, series.csv_name(), extension);

    ValidationProbe probe(p, dem.properties, dem.walls, comm);
    probe.set_state(records.numbers("probe"));
    ClumpValidation clump_check(p);
    clump_check.set_state(records.numbers("clump_probe"));

    const unsigned long long n_steps =
      static_cast<unsigned long long>(std::ceil(p.end_time / dt - 1e-9));
    double             time = dem.time();
    CheckpointSchedule checkpoint(p, time);
    unsigned long long n_particle_steps = 0;
    ProgressLine       progress(p.progress && dem.rank == 0, p.end_time);

    // The scene's records a checkpoint keeps, so that the series and probes
    // continue after a restart.
    const auto scene_records = [&]() {
      SceneRecords r;
      series.add_records(r, dem);
      r.set_numbers("probe", probe.state());
      if (clump_check.active())
        r.set_numbers("clump_probe", clump_check.state());
      if (stream.active())
        r.set_numbers("stream", stream.state());
      if (extension)
        r.set_numbers("extension", extension->state());
      const std::vector<double> impact_statistics = wear.state(comm);
      if (!impact_statistics.empty())
        r.set_numbers("impact_statistics", impact_statistics);
      return r.lines();
    };

    // A restarted run resumes where the checkpoint was written, just before
    // the stream's turn in that step; it has observed and written its start.
    if (restart)
      stream.after_step(dem);
    else
      {
        if (probe.active())
          probe.observe(time, dt, dem.particles);
        clump_check.observe(dem);
        series.write(time, false, dem);
      }

    const auto        loop_start = std::chrono::steady_clock::now();
    dem.clock.start();
    const GravityKick kick{p.gravity};
    try
      {
        for (unsigned long long step = dem.step + 1; step <= n_steps; ++step)
          {
            if (extension)
              extension->advance(dem);
            else if (dem.clumps)
              dem.advance_clumps(kick);
            else
              dem.advance(kick);
            time = dem.time();
            wear.after_step(dem);
            wear.attach_when_due(dem);
            n_particle_steps += dem.particles.n_local;

            if (probe.active())
              probe.observe(time, dt, dem.particles);
            clump_check.observe(dem);
            series.write(time, false, dem);
            if (checkpoint.due(dem.step, time, dt))
              save_dem_checkpoint(dem, checkpoint_path(output_directory, p.base_name, dem.step),
                                  scene_records(), p.checkpoints_kept);
            // After the checkpoint: a batch it schedules is the next step's, and
            // a restart plans it again from the same counters.
            stream.after_step(dem);
            // Only rank 0 draws the line, so nothing collective may happen here.
            if (progress.due())
              progress.update(time, step, dem.n_inserted - dem.n_lost);
          }
      }
    catch (RunStopped &stop)
      {
        // The state that failed, for a look in ParaView (every rank stops together).
        progress.finish();
        stop.written_at_stop = stop_note(dem.time(), series.write_at_stop(dem.time(), dem));
        throw;
      }
    progress.finish();
    series.dump_final(time, dem);
    LoopTiming timing;
    timing.loop_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
    timing.n_steps = n_steps;
    timing.local_particle_steps = n_particle_steps;
    MPI_Allreduce(&n_particle_steps, &timing.particle_steps, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM,
                  comm);

    // ---- Summary ----
    ValidationResult result;
    if (clump_check.active())
      result = clump_check.finish(dem);
    else if (probe.active())
      result = probe.finish(dem.particles, dem.n_lost, dem.n_inserted);
    std::ostringstream statistics;
    statistics << std::setprecision(p.summary_precision);
    wear.finish(statistics, dem, output_directory, p.base_name);
    if (extension)
      statistics << extension->summary(dem);
    timing.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    print_summary(out, p, dem, time, timing, series, output_directory, statistics.str(), stream);
    if (dem.rank == 0)
      {
        if (probe.active())
          {
            for (const auto &c : result.checks)
              out << c << "\n";
            write_result_line(out, result.name, result.value, result.reference, result.error,
                              timing.wall_s);
          }
        out << std::flush;
      }
    if (probe.active() && !result.failure.empty())
      {
        if (dem.rank == 0)
          std::cerr << "sluice: validation failed: " << result.failure << "\n";
        return 3;
      }
    if (probe.active() && p.validation_tolerance > 0. && result.error > p.validation_tolerance)
      {
        if (dem.rank == 0)
          std::cerr << "sluice: validation error " << result.error << " exceeds the tolerance "
                    << p.validation_tolerance << " set in 'validation/tolerance'\n";
        return 3;
      }
    return extension ? extension->exit_code() : 0;
  }
} // namespace sluice
