// An SPH fluid scene (see the header).
//
//   set-up (sph_setup.h) -> header -> loop: step, health checks, output,
//   checkpoint -> final dump, summary, validation.
//
// A checkpoint is a directory '<base>-checkpoint-<step>' holding 'sph.bin'
// (the solver's whole state, sph_solver.h) and 'state' (the scene entries it
// depends on and the output records), written as '<name>.writing' and
// renamed when complete.

#include <sluice/core/binary_io.h>
#include <sluice/core/output_files.h>
#include <sluice/core/progress.h>
#include <sluice/core/result_line.h>
#include <sluice/core/scene_records.h>
#include <sluice/core/series_files.h>
#include <sluice/dem/dem_checkpoint.h>
#include <sluice/dem/particle_fields.h>
#include <sluice/dem/particle_output.h>
#include <sluice/dem/wall_set.h>
#include <sluice/sph/sph_dam_break.h>
#include <sluice/sph/sph_fluid_trim.h>
#include <sluice/sph/sph_health.h>
#include <sluice/sph/sph_output.h>
#include <sluice/sph/sph_scene.h>
#include <sluice/sph/sph_setup.h>
#include <sluice/sph/sph_solver.h>
#include <sluice/sph/sph_validation.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <utility>

namespace sluice
{
  namespace
  {
    namespace fs = std::filesystem;

    const std::string state_header = "sluice sph checkpoint 1";

    /// The entries a checkpoint's state depends on, one line each.
    std::vector<std::string> signature(const SceneParameters &p, const SphSetup &setup)
    {
      const SphParameters &s = p.sph;
      std::ostringstream   o;
      o << "sph " << s.kernel << " spacing " << exact_text(s.spacing) << " smoothing "
        << exact_text(s.smoothing_factor) << " density " << exact_text(s.density)
        << " viscosity " << exact_text(s.viscosity)
        << (s.viscosity_form == "morris" ? "" : " " + s.viscosity_form) << " alpha "
        << exact_text(s.artificial_viscosity) << " epsilon " << exact_text(s.artificial_pressure)
        << " delta " << exact_text(s.density_diffusion)
        << (s.summation_density ? " summation" : " continuity") << " xsph "
        << exact_text(s.xsph) << " sound speed "
        << exact_text(setup.settings.forces.state.sound_speed) << " particles "
        << setup.particles.size();
      if (s.time_integration != "leap_frog") // (absent from earlier checkpoints)
        o << " " << s.time_integration;
      if (s.fixed_smoothing_length)
        o << " fixed_h";
      if (!setup.settings.repulsive_walls.empty())
        o << " lennard_jones " << exact_text(setup.settings.repulsive_walls.law().strength);
      if (s.solid_walls)
        o << " solid_walls " << p.walls.size() << " planes " << p.meshes.size() << " meshes k "
          << exact_text(s.solid_wall_stiffness) << " e " << exact_text(s.solid_wall_restitution);
      return {o.str()};
    }

    /// Global quantities of the fluid particles: kinetic energy, mean density,
    /// largest speed and largest density deviation from rho_0.
    struct FluidSummary
    {
      double kinetic_energy = 0., mean_density = 0., max_speed = 0., max_density_deviation = 0.;
    };
    /// Collective.
    FluidSummary summarise(const SphParticles &P, const double rho_0, MPI_Comm comm)
    {
      FluidSummary s;
      double       n = 0.;
      for (unsigned int a = 0; a < P.n_local; ++a)
        if (!P.wall[a])
          {
            s.kinetic_energy += 0.5 * P.mass[a] * norm_square(P.velocity[a]);
            s.mean_density += P.density[a];
            s.max_speed = std::max(s.max_speed, norm(P.velocity[a]));
            s.max_density_deviation =
              std::max(s.max_density_deviation, std::abs(P.density[a] / rho_0 - 1.));
            ++n;
          }
      double sums[3] = {s.kinetic_energy, s.mean_density, n};
      double maxima[2] = {s.max_speed, s.max_density_deviation};
      MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_DOUBLE, MPI_SUM, comm);
      MPI_Allreduce(MPI_IN_PLACE, maxima, 2, MPI_DOUBLE, MPI_MAX, comm);
      s.kinetic_energy        = sums[0];
      s.mean_density          = sums[1] / std::max(sums[2], 1.);
      s.max_speed             = maxima[0];
      s.max_density_deviation = maxima[1];
      return s;
    }

    /// The walls' load along gravity and the fluid's weight [N]. Collective.
    std::pair<double, double> solid_wall_load(const SphSolver &solver, const Vec3 &gravity,
                                              MPI_Comm comm)
    {
      const SphParticles &P    = solver.particles();
      double              load = 0., mass = 0.;
      const double        g    = norm(gravity);
      for (const Vec3 &F : solver.solid_walls().wall_forces())
        load += g > 0. ? dot(F, gravity) / g : 0.;
      for (unsigned int a = 0; a < P.n_local; ++a)
        if (!P.wall[a])
          mass += P.mass[a];
      double sums[2] = {load, mass};
      MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, comm);
      return {sums[0], sums[1] * g};
    }

    /// The walls' load against the fluid's weight, the power the walls give
    /// the fluid, and the deepest overlap. Collective.
    std::string solid_walls_check(const SphSolver &solver, const SceneParameters &p,
                                  const double spacing, MPI_Comm comm)
    {
      const SphSolidWalls &W = solver.solid_walls();
      Vec3                 load;
      double               power = 0.;
      for (unsigned int w = 0; w < W.wall_forces().size(); ++w)
        load += W.wall_forces()[w], power += W.wall_powers()[w];
      double sums[4] = {load.x, load.y, load.z, power}, max_overlap = W.max_overlap();
      MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, comm);
      MPI_Allreduce(MPI_IN_PLACE, &max_overlap, 1, MPI_DOUBLE, MPI_MAX, comm);
      load  = Vec3(sums[0], sums[1], sums[2]);
      power = sums[3];
      const auto [load_along_gravity, weight] = solid_wall_load(solver, p.gravity, comm);
      std::ostringstream o;
      o << std::setprecision(p.summary_precision) << "check: solid_walls load=(" << load.x
        << ", " << load.y << ", " << load.z << ") fluid_weight=" << weight
        << " load_over_weight=" << (weight > 0. ? load_along_gravity / weight : 0.)
        << " power=" << power << " max_overlap_over_dx=" << max_overlap / spacing;
      return o.str();
    }

    /// Collective; rank 0 writes.
    void save_checkpoint(const SphSolver &solver, const std::string &path,
                         const std::vector<std::string> &lines, const unsigned int keep,
                         const bool root)
    {
      BinaryWriter out("sluice sph state");
      solver.save(out);
      if (!root)
        return;
      const std::string tmp = path + ".writing";
      std::error_code   error;
      fs::remove_all(tmp, error);
      fs::create_directories(tmp, error);
      if (error)
        throw OutputError("sluice: cannot create the checkpoint directory '" + tmp + "'");
      write_file_atomically(tmp + "/sph.bin", out.finish());
      std::ostringstream state;
      state << state_header << "\n";
      for (const std::string &l : lines)
        state << l << "\n";
      state << "end\n";
      write_file_atomically(tmp + "/state", state.str());
      fs::remove_all(path, error);
      fs::rename(tmp, path, error);
      if (error)
        throw OutputError("sluice: cannot rename the checkpoint '" + tmp + "' to '" + path + "'");
      prune_checkpoints(path, keep);
    }

    std::string read_whole(const std::string &path)
    {
      std::ifstream in(path, std::ios::binary);
      return std::string((std::istreambuf_iterator<char>(in)), {});
    }

    /// Restores the solver from a checkpoint and returns its records.
    /// Throws InputError naming the file and the fault; changes nothing then.
    SceneRecords load_checkpoint(SphSolver &solver, const std::string &path,
                                 const std::vector<std::string> &expected,
                                 const std::string &file_name)
    {
      const std::string where = "error in '" + file_name +
                                "': entry 'checkpoint/restart from': checkpoint '" + path + "': ";
      std::vector<std::string> lines;
      {
        std::istringstream in(read_whole(path + "/state"));
        for (std::string line; std::getline(in, line);)
          lines.push_back(line);
      }
      if (lines.size() < 2 || lines.front() != state_header || lines.back() != "end")
        throw InputError(where + "its 'state' is missing, cut short or not an SPH checkpoint");
      for (std::size_t k = 0; k < expected.size(); ++k)
        if (k + 1 >= lines.size() || lines[k + 1] != expected[k])
          throw InputError(where + "it was written by another scene: '" +
                           (k + 1 < lines.size() ? lines[k + 1] : std::string()) +
                           "', this scene has '" + expected[k] + "'");
      try
        {
          BinaryReader in(read_whole(path + "/sph.bin"), "sluice sph state");
          solver.load(in);
        }
      catch (const BinaryFormatError &e)
        {
          throw InputError(where + "'sph.bin' cannot be used: " + e.what());
        }
      return SceneRecords(
        std::vector<std::string>(lines.begin() + 1 + expected.size(), lines.end() - 1));
    }

    void print_header(std::ostream &out, const SceneParameters &p, const SphSetup &setup,
                      const double dt, const std::string &checkpoint, const double time,
                      const std::string &ranks)
    {
      const SphSettings &s = setup.settings;
      out << std::setprecision(4) << "Sluice SPH - scene " << p.file_name << "\n"
          << "  particles: " << setup.n_fluid << " fluid, " << setup.n_walls
          << " wall; spacing " << p.sph.spacing << " m, h = " << s.smoothing_factor
          << (s.fixed_smoothing_length ? " dx (fixed)" : " dx") << ", kernel " << p.sph.kernel
          << "\n";
      if (!s.repulsive_walls.empty())
        out << "  walls: Lennard-Jones boundary particles, D = " << s.repulsive_walls.law().strength
            << " m^2/s^2, r_0 = " << s.repulsive_walls.law().range << " m\n";
      if (p.sph.solid_walls)
        out << "  solid walls: " << p.walls.size() << " planes, " << p.meshes.size()
            << " meshes; spring-dashpot k = " << solid_wall_law(p, setup).stiffness
            << " N/m, e = " << p.sph.solid_wall_restitution << ", R = dx/2"
            << (setup.n_cut_by_walls > 0 ?
                  "; " + std::to_string(setup.n_cut_by_walls) + " lattice points beyond them "
                  "left out" : std::string())
            << "\n";
      out << "  rho_0 = " << s.forces.state.reference_density
          << " kg/m^3, mu = " << s.forces.viscosity << " Pa s"
          << (s.forces.viscosity_form == SphViscosityForm::signal_velocity ?
                " (signal-velocity form)" :
                "")
          << ", alpha = "
          << s.forces.artificial_viscosity << ", delta = " << s.diffusion.delta
          << ", c_s = " << s.forces.state.sound_speed
          << " m/s (" << setup.sound_speed_origin << "), step " << dt << " s"
          << (s.integrator == SphIntegrator::predictor_corrector ? " (predictor-corrector)" : "")
          << "\n";
      if (!ranks.empty())
        out << "  " << ranks << "\n";
      if (!checkpoint.empty())
        out << "  restarted from " << checkpoint << " at t = " << time << " s\n";
      out << std::flush;
    }
  } // namespace

  int run_sph_scene(const SceneParameters &p, MPI_Comm comm)
  {
    const auto wall_start = std::chrono::steady_clock::now();
    int        rank       = 0;
    MPI_Comm_rank(comm, &rank);
    const bool root = rank == 0;

    // ---- Set-up: every input check (and a restart's reading) before any output ----
    if (p.sph.validation == SphValidationCase::solid_wall_load && !(norm(p.gravity) > 0.))
      throw InputError("error in '" + p.file_name + "': entry 'sph/validation' is "
                       "'solid_wall_load', which weighs the fluid: set 'simulation/gravity'");
    SphSetup               setup    = make_sph_setup(p);
    SphSettings            settings = setup.settings;
    std::optional<WallSet> solid_walls; // the DEM's walls, when they hold the fluid
    if (p.sph.solid_walls)
      {
        solid_walls.emplace(p.walls, p.meshes, setup.box, p.file_name);
        if (solid_walls->n_walls() == 0)
          throw InputError("error in '" + p.file_name + "': entry 'sph/solid walls' is true, "
                           "but the scene has no walls: set 'walls/box', 'walls/planes' or a "
                           "mesh ('walls/number of meshes')");
        remove_fluid_beyond_walls(setup, *solid_walls, solid_wall_law(p, setup).radius);
        settings.solid_walls =
          SphSolidWalls(*solid_walls, solid_wall_law(p, setup), setup.box.lower, setup.box.upper);
      }
    SphSolver solver(setup.particles, setup.box, settings, comm);
    // Calls f with every rank's particles (collective; on one rank, this rank's).
    const auto with_all_particles = [&](const auto &f) {
      if (solver.distributed())
        f(solver.all_particles());
      else
        f(solver.particles());
    };
    const double   dt = p.sph.time_step > 0. ? p.sph.time_step :
                                              p.sph.time_step_fraction * solver.stable_time_step();
    const std::vector<std::string> entries = signature(p, setup);
    std::string                    checkpoint;
    SceneRecords                   records;
    if (!p.restart_from.empty())
      {
        checkpoint = find_checkpoint(p.restart_from, p.output_directory, p.base_name, p.file_name);
        records    = load_checkpoint(solver, checkpoint, entries, p.file_name);
        if (solid_walls)
          {
            const std::vector<double> pose = records.numbers("solid_walls");
            if (pose.size() != solid_walls->state().size())
              throw InputError("error in '" + p.file_name + "': entry 'checkpoint/restart "
                               "from': checkpoint '" + checkpoint + "': its 'state' lacks the "
                               "solid walls' poses or holds the wrong number of them");
            solid_walls->set_state(pose);
          }
      }
    const unsigned long long first_step = records.number("step", 0.);
    const double             rho_0      = p.sph.density;
    const double mean_density_start = records.number(
      "mean_density_start", summarise(solver.particles(), rho_0, comm).mean_density);

    std::optional<PoiseuilleProbe> poiseuille;
    if (p.sph.validation == SphValidationCase::poiseuille)
      {
        poiseuille.emplace(p, p.end_time);
        poiseuille->restore(records);
      }
    std::optional<DamBreakProbe> dam_break;
    if (p.sph.validation == SphValidationCase::dam_break)
      {
        dam_break.emplace(p, p.end_time);
        dam_break->restore(records);
      }

    const bool        writes = p.vtu_interval > 0. || p.csv_interval > 0. ||
                        p.checkpoint_step_interval > 0 || p.checkpoint_time_interval > 0.;
    const std::string directory =
      writes ? prepare_output_directory(p.output_directory, {p.base_name}, p.if_output_exists,
                                        !checkpoint.empty(), p.file_name, comm) :
               p.output_directory;
    const std::string ranks = solver.distributed() ? solver.decomposition() : std::string();
    if (root)
      print_header(std::cout, p, setup, dt, checkpoint, first_step * dt, ranks);

    SphOutput output(directory, p.base_name);
    output.vtu.index().restore(records.all("snapshot"));
    CsvSeries csv;
    if (p.csv_interval > 0. && root)
      csv.open(directory + "/" + p.base_name + ".csv",
               std::string("time,kinetic_energy,mean_density,max_speed,max_density_deviation") +
                 (dam_break ? ",front_over_a" : ""),
               true,
               !checkpoint.empty(), first_step * dt);
    double next_vtu = records.number("next_vtu", 0.), next_csv = records.number("next_csv", 0.);
    // What is due at 'time' (everything, with 'force').
    const auto write_output = [&](const double time, const bool force = false) {
      if (p.vtu_interval > 0. && (time >= next_vtu - 0.5 * dt || force))
        {
          with_all_particles([&](const SphParticles &all) {
            if (root)
              output.write(all, p.sph.spacing, time);
          });
          next_vtu += p.vtu_interval;
        }
      if (p.csv_interval > 0. && (time >= next_csv - 0.5 * dt || force))
        {
          const FluidSummary f     = summarise(solver.particles(), rho_0, comm);
          double             front = 0.;
          if (dam_break)
            with_all_particles([&](const SphParticles &all) { front = dam_break->front(all); });
          if (root)
            {
              csv.row() << std::setprecision(10) << time << "," << f.kinetic_energy << ","
                        << f.mean_density << "," << f.max_speed << ","
                        << f.max_density_deviation;
              if (dam_break)
                csv.row() << "," << front;
              csv.end_row();
            }
          next_csv += p.csv_interval;
        }
    };
    if (checkpoint.empty())
      write_output(0.);

    // ---- The loop ----
    const unsigned long long n_steps =
      static_cast<unsigned long long>(std::ceil(p.end_time / dt - 1e-9));
    CheckpointSchedule schedule(p, first_step * dt);
    ProgressLine       progress(p.progress && root, p.end_time);
    const auto         loop_start = std::chrono::steady_clock::now();
    double             time       = first_step * dt;
    try
      {
        for (unsigned long long step = first_step + 1; step <= n_steps; ++step)
          {
            if (solid_walls)
              solid_walls->move((step - 1) * dt, dt);
            solver.step(dt);
            time = step * dt;
            check_on_all_ranks(comm, [&]() { check_sph_health(solver.particles(), setup, time); });
            if (solver.stable_time_step() < dt * (1. - 1e-12))
              {
                std::ostringstream msg;
                msg << std::setprecision(6) << "at t = " << time
                    << " s the stable SPH step fell to " << solver.stable_time_step() << " s, below the step " << dt
                    << " s, set by " << solver.stable_step_limit()
                    << " (entry 'sph/time step' or 'sph/time step fraction'): lower it";
                throw SimulationFailure(msg.str());
              }
            if (solid_walls)
              check_on_all_ranks(comm, [&]() {
                check_solid_wall_overlap(solver.solid_walls(), setup.spacing, time);
              });
            write_output(time);
            if (poiseuille && poiseuille->due(time, dt))
              with_all_particles(
                [&](const SphParticles &all) { poiseuille->measure_if_due(all, time, dt); });
            if (dam_break && dam_break->due(time, dt))
              with_all_particles(
                [&](const SphParticles &all) { dam_break->measure_if_due(all, time, dt); });
            if (schedule.due(step, time, dt))
              {
                SceneRecords r(entries);
                r.set("step", step);
                r.set("mean_density_start", mean_density_start);
                r.set("next_vtu", next_vtu);
                r.set("next_csv", next_csv);
                r.add_all("snapshot", output.vtu.index().to_text());
                if (solid_walls)
                  r.set_numbers("solid_walls", solid_walls->state());
                if (poiseuille)
                  poiseuille->save(r);
                if (dam_break)
                  dam_break->save(r);
                save_checkpoint(solver, checkpoint_path(directory, p.base_name, step), r.lines(),
                                p.checkpoints_kept, root);
              }
            if (progress.due())
              progress.update(time, step, setup.n_fluid);
          }
      }
    catch (RunStopped &stop)
      {
        // The state that failed, for a look in ParaView (every rank stops together).
        progress.finish();
        write_output(time, true);
        std::vector<std::string> written;
        if (p.vtu_interval > 0.)
          written.push_back(directory + "/" + p.base_name + ".pvd");
        if (p.csv_interval > 0.)
          written.push_back(directory + "/" + p.base_name + ".csv");
        stop.written_at_stop = stop_note(time, written);
        throw;
      }
    progress.finish();
    const double loop_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();

    // ---- Summary and validation ----
    const FluidSummary end = summarise(solver.particles(), rho_0, comm);
    std::ostringstream summary;
    summary << std::setprecision(p.summary_precision) << "final: time=" << time
            << " steps=" << n_steps << " fluid_particles=" << setup.n_fluid
            << " wall_particles=" << setup.n_walls << " kinetic_energy=" << end.kinetic_energy
            << " mean_density=" << end.mean_density << " max_speed=" << end.max_speed
            << " max_density_deviation=" << end.max_density_deviation << "\n";
    SphResult result;
    if (p.sph.validation == SphValidationCase::hydrostatic)
      with_all_particles([&](const SphParticles &all) {
        result = hydrostatic_result(all, p, setup, mean_density_start, end.mean_density,
                                    end.max_speed);
      });
    else if (poiseuille)
      result = poiseuille->result(p.summary_precision);
    else if (dam_break)
      result = dam_break->result(p.summary_precision);
    else if (p.sph.validation == SphValidationCase::solid_wall_load)
      {
        const auto [load, weight] = solid_wall_load(solver, p.gravity, comm);
        result.name      = "sph_solid_wall_load";
        result.value     = load;
        result.reference = weight;
        result.error     = std::abs(load - weight) / weight;
      }
    for (const std::string &c : result.checks)
      summary << c << "\n";
    if (solid_walls)
      summary << solid_walls_check(solver, p, setup.spacing, comm) << "\n";
    const double steps_run = std::max<double>(1., n_steps - first_step);
    const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    summary << std::setprecision(4) << "timing: wall_s=" << wall_s << " loop_s=" << loop_s
            << " us_per_particle_step=" << 1e6 * loop_s / (steps_run * setup.n_fluid)
            << " pair_builds=" << solver.n_pair_builds()
            << " repartitions=" << solver.n_repartitions() << "\n"
            << std::setprecision(p.summary_precision);
    if (output.vtu.n_written() > 0)
      summary << "output: " << output.vtu.n_written() << " particle snapshots in " << directory
              << "/" << p.base_name << ".pvd\n";
    if (!result.name.empty())
      write_result_line(summary, result.name, result.value, result.reference, result.error,
                        wall_s);
    if (root)
      std::cout << summary.str() << std::flush;
    if (p.sph.tolerance > 0. && !result.name.empty() && result.error > p.sph.tolerance)
      {
        if (root)
          std::cerr << "sluice: validation error " << result.error << " exceeds the tolerance "
                  << p.sph.tolerance << " set in 'sph/tolerance'\n";
        return 3;
      }
    return 0;
  }
} // namespace sluice
