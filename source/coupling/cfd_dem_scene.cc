// The coupled time loop (Zhou et al. 2010, coupling scheme 3; doc/coupling.md):
//
//   for each fluid step t^n -> t^n+1 = t^n + dt_f:
//     1. the DEM takes n_sub steps of dt_f / n_sub: velocity Verlet whose kicks
//        integrate the drag exactly for the frozen k and u (implicit_drag.h), so
//        tau_p << dt needs no smaller step; each particle adds up the impulse
//        the fluid gave it (the exchanged part);
//     2. the particles go to the fluid mesh's ParticleHandler and deposit, with
//        one set of weights, their volume (porosity at t^n+1) and minus that
//        impulse / dt_f (the fluid's momentum source): the field's integral is
//        the particles' total to round-off, so momentum is conserved exactly;
//     3. the fluid advances to t^n+1 (BDF, with d eps/dt from the porosity);
//     4. the fluid is sampled at the particles and each particle's drag
//        coefficient and other forces are frozen for the next step.
// One-way coupling skips step 2: the fluid sees neither porosity nor reaction.

#include <sluice/core/result_line.h>
#include <sluice/core/names.h>
#include <sluice/core/output_files.h>
#include <sluice/dem/particle_output.h>
#include <sluice/core/progress.h>
#include <sluice/core/series_files.h>
#include <sluice/coupling/cfd_dem_scene.h>
#include <sluice/coupling/fluid_kick.h>
#include <sluice/coupling/particle_fluid_exchange.h>
#include <sluice/coupling/particle_fluid_forces.h>
#include <sluice/coupling/rayleigh_taylor.h>
#include <sluice/coupling/self_induced_velocity.h>
#include <sluice/dem/dem_system.h>
#include <sluice/dem/particle_csv.h>
#include <sluice/fluid/fluid_coefficients.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace sluice
{
  using namespace dealii;
  namespace cd = coupling_data;

  namespace
  {
    /// The single-particle equation of motion along the scene's gravity,
    /// (m + m_a) dv/dt = (m - rho_f V b) g + k(|u - v|) (u - v) with u = 0
    /// (b = 1 when buoyancy is part of the model), by RK4 with steps of
    /// tau / 2000; returns v(t) at the requested times.
    std::vector<Vec3> single_particle_velocity(const SceneParameters &p, const double radius,
                                               const double density, const Vec3 &v0,
                                               const std::vector<double> &times)
    {
      const auto  &c   = p.coupling;
      const double d   = 2. * radius, V = M_PI / 6. * d * d * d, m = density * V;
      const double rho = p.fluid.density;
      const bool   buoyancy =
        c.formulation == CouplingFormulation::set_iii || c.pressure_gradient_force;
      const double m_eff = m + c.virtual_mass_coefficient * rho * V;
      const Vec3   weight = (m - (buoyancy ? rho * V : 0.)) * p.gravity;
      const auto   accel  = [&](const Vec3 &v) {
        DragState s;
        s.eps       = 1.;
        s.density   = rho;
        s.viscosity = p.fluid.viscosity;
        s.diameter  = d;
        s.slip      = norm(v);
        return (1. / m_eff) * (weight - particle_drag_coefficient(c.drag, s) * v);
      };
      DragState s0;
      s0.density = rho, s0.viscosity = p.fluid.viscosity, s0.diameter = d, s0.slip = 1e-12;
      const double tau = m_eff / particle_drag_coefficient(DragClosure::stokes, s0);
      std::vector<Vec3> out;
      Vec3   v = v0;
      double t = 0.;
      for (const double target : times)
        {
          while (t < target)
            {
              const double h  = std::min(tau / 2000., target - t);
              const Vec3   k1 = accel(v), k2 = accel(v + 0.5 * h * k1),
                         k3 = accel(v + 0.5 * h * k2), k4 = accel(v + h * k3);
              v += (h / 6.) * (k1 + 2. * k2 + 2. * k3 + k4);
              t += h;
            }
          out.push_back(v);
        }
      return out;
    }

    /// The slip speed w with k(eps, w) w = target (the drag force grows with w).
    double slip_for_force(const SceneParameters &p, const double d, const double eps,
                          const double target)
    {
      DragState s;
      s.eps       = eps;
      s.density   = p.fluid.density;
      s.viscosity = p.fluid.viscosity;
      s.diameter  = d;
      double lo = 0., hi = 1.;
      const auto force = [&](const double w) {
        s.slip = w;
        return particle_drag_coefficient(p.coupling.drag, s) * w;
      };
      while (force(hi) < target)
        hi *= 2.;
      for (unsigned int it = 0; it < 200; ++it)
        {
          const double mid = 0.5 * (lo + hi);
          (force(mid) < target ? lo : hi) = mid;
        }
      return 0.5 * (lo + hi);
    }

    /// Whether a particle lies in the middle half, along the direction e, of
    /// the span of all particles (all ranks): where a bed's or a block's
    /// projected porosity is its own, away from the smoothed edges.
    std::function<bool(const Vec3 &)> in_middle_half(const ParticleStorage &P, const Vec3 &e,
                                                     MPI_Comm comm)
    {
      double lo = std::numeric_limits<double>::max(), hi = -lo;
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          lo = std::min(lo, dot(P.position[i], e));
          hi = std::max(hi, dot(P.position[i], e));
        }
      lo = Utilities::MPI::min(lo, comm);
      hi = Utilities::MPI::max(hi, comm);
      return [=](const Vec3 &x) { return std::abs(dot(x, e) - 0.5 * (lo + hi)) < 0.25 * (hi - lo); };
    }

    Vec3 global_mean_velocity(const ParticleStorage &P, MPI_Comm comm)
    {
      double s[4] = {0., 0., 0., static_cast<double>(P.n_local)};
      for (unsigned int i = 0; i < P.n_local; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          s[d] += P.velocity[i][d];
      MPI_Allreduce(MPI_IN_PLACE, s, 4, MPI_DOUBLE, MPI_SUM, comm);
      return s[3] > 0. ? Vec3(s[0] / s[3], s[1] / s[3], s[2] / s[3]) : Vec3();
    }
  } // namespace

  int run_cfd_dem_scene(const SceneParameters &p, MPI_Comm comm)
  {
    const auto wall_start = std::chrono::steady_clock::now();
    const auto seconds    = [&]() {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    };
    const int  rank = Utilities::MPI::this_mpi_process(comm);
    const auto &c   = p.coupling;
    const auto fail = [&](const std::string &entry, const std::string &what) {
      throw InputError("error in '" + p.file_name + "': entry '" + entry + "' " + what);
    };

    // Checkpoints of coupled scenes (fluid, DEM and coupling state together)
    // are not written yet: refuse the entries rather than ignore them.
    for (const auto &[set, entry] :
         {std::pair{p.checkpoint_step_interval > 0, "checkpoint/step interval"},
          {p.checkpoint_time_interval > 0., "checkpoint/time interval"},
          {!p.restart_from.empty(), "checkpoint/restart from"},
          {p.fluid.checkpoint_interval > 0, "fluid output/checkpoint interval"},
          {!p.fluid.restart_from.empty(), "fluid time/restart from"}})
      if (set)
        fail(entry, "is set, but cfd-dem scenes cannot write or read checkpoints yet "
                    "(DEM and fluid scenes can); leave it at its default");

    // ---- The fluid as the formulation needs it ----
    FluidParameters fp = p.fluid;
    if (fp.time_integration == TimeIntegration::steady)
      fail("fluid time/integration", "is 'steady'; a coupled scene needs 'bdf1' or 'bdf2'");
    if (fp.drag != PorousDrag::none)
      fail("fluid/porous drag", "must be 'none' in a coupled scene: the particles are the drag");
    fp.formulation = c.formulation == CouplingFormulation::set_ii ? VansFormulation::model_a :
                                                                    VansFormulation::model_b;
    fp.porosity_as_field        = c.two_way;
    fp.momentum_source_as_field = c.two_way;
    fp.use_gravity              = true;
    const double dt_fluid       = fp.time_step;

    // ---- The DEM (checks its own input first) ----
    DemSystem        dem(p, comm, cd::n_slots);
    ParticleStorage &P = dem.particles;
    const unsigned int n_sub = std::max(1., std::ceil(dt_fluid / dem.dt - 1e-9));
    dem.dt                   = dt_fluid / n_sub;
    const double d_max       = 2. * dem.r_max;

    // Newton's absolute tolerance is a force [N]: above the particles' forces
    // the fluid's first residual already meets it and the fluid never moves
    // (a silent one-way coupling). Require 1e-3 of the smallest buoyant weight.
    if (c.two_way && norm(p.gravity) > 0.)
      {
        double smallest_weight = std::numeric_limits<double>::max();
        for (unsigned int i = 0; i < P.n_local; ++i)
          smallest_weight =
            std::min(smallest_weight, std::abs(P.mass[i] - fp.density * 4. / 3. * M_PI *
                                                               std::pow(P.radius[i], 3)) *
                                        norm(p.gravity));
        smallest_weight = Utilities::MPI::min(smallest_weight, comm);
        if (smallest_weight > 0. && fp.newton_tolerance > 1e-3 * smallest_weight)
          fail("fluid solver/newton tolerance",
               "= " + to_text(fp.newton_tolerance) +
                 " N is above 1e-3 of the smallest particle's buoyant weight (" +
                 to_text(smallest_weight) +
                 " N): the fluid's first residual would meet it and the fluid would not feel "
                 "the particles; use at most " + to_text(1e-3 * smallest_weight) + " N");
      }

    const Tensor<1, 3> gravity({p.gravity.x, p.gravity.y, p.gravity.z});
    VansSolver         fluid(fp, coefficients_from_prm(fp), gravity, p.file_name, comm);
    fluid.initialize(0.);

    double smallest_cell = std::numeric_limits<double>::max();
    for (const auto &cell : fluid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        smallest_cell = std::min(smallest_cell, cell->minimum_vertex_distance());
    smallest_cell = Utilities::MPI::min(smallest_cell, comm);
    const double radius = c.kernel_radius > 0. ? c.kernel_radius : smallest_cell;
    if (c.two_way && c.projection == ProjectionScheme::kernel)
      {
        if (radius < 2. * d_max * (1. - 1e-12))
          fail("cfd-dem/kernel radius",
               "= " + to_text(radius) + " m" + (c.kernel_radius > 0. ? "" : " (the smallest fluid cell)") +
                 " is below two particle diameters (" + to_text(2. * d_max) +
                 " m); allowed: 2 d <= R_s <= smallest fluid cell (" + to_text(smallest_cell) +
                 " m): use a coarser fluid mesh or the 'centroid' projection");
        if (radius > smallest_cell * (1. + 1e-10))
          fail("cfd-dem/kernel radius", "= " + to_text(radius) +
                                          " m exceeds the smallest fluid cell (" +
                                          to_text(smallest_cell) + " m)");
      }
    ParticleFluidExchange exchange(fluid.porosity_dofs(), fluid.get_mapping(), c.projection, radius);
    exchange.set_smoothing_bandwidth(c.smoothing_bandwidth);
    for (const auto &bc : fp.boundaries)
      if (bc.type == BoundaryType::periodic)
        exchange.add_periodic_pair(bc.ids[0], bc.ids[1], bc.direction);

    // ---- The self-induced velocity (self_induced_velocity.h): the fluid's
    // response to one particle's force, measured on this mesh ----
    std::unique_ptr<SelfInducedVelocity> self_induced;
    std::string                          self_induced_summary;
    if (c.self_induced_correction)
      {
        const std::string entry = "cfd-dem/self-induced velocity correction";
        if (!c.two_way)
          fail(entry, "is 'true' in a one-way scene, where the fluid never feels the particles");
        if (fp.adaptive)
          fail(entry, "needs a fixed fluid mesh ('fluid refinement/adaptive = false'): the "
                      "measured response belongs to one mesh");
        Vec3 lo(1e300, 1e300, 1e300), hi = -lo;
        for (const auto &cell : fluid.get_triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              for (unsigned int d = 0; d < 3; ++d)
                {
                  lo[d] = std::min(lo[d], cell->vertex(v)[d]);
                  hi[d] = std::max(hi[d], cell->vertex(v)[d]);
                }
        for (unsigned int d = 0; d < 3; ++d)
          {
            lo[d] = Utilities::MPI::min(lo[d], comm);
            hi[d] = Utilities::MPI::max(hi[d], comm);
          }
        const double memory   = c.self_induced_memory > 0. ? c.self_induced_memory : p.end_time;
        const auto   n_memory = static_cast<unsigned int>(
          std::max(1., std::ceil(memory / dt_fluid - 1e-9)));
        const Vec3 direction = norm(p.gravity) > 0. ? p.gravity : Vec3(0., 0., 1.);
        // Small enough to stay linear (a disturbance far below nu / R_s).
        const double probe_force = 1e-5 * fp.viscosity * fp.viscosity / fp.density;
        const double reach = 0.45 * std::min({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
        const double started = seconds();
        self_induced = std::make_unique<SelfInducedVelocity>(
          measure_self_response(fp, c.projection, radius, c.smoothing_bandwidth, 0.5 * (lo + hi),
                                direction, probe_force, n_memory,
                                std::min(smallest_cell, radius) / 8., reach, comm),
          dem.box);
        // The velocity a steady force induces at its deposit by the end of the
        // memory, against the particle's own Stokes mobility 1 / (3 pi mu d).
        double mobility = 0.;
        for (const auto &row : self_induced->table().along)
          mobility += row[0];
        std::ostringstream text;
        text << std::setprecision(4)
             << "  self-induced velocity correction: response measured over " << n_memory << " fluid steps (" << n_memory * dt_fluid << " s) in "
             << seconds() - started << " s; steady-force self mobility = "
             << mobility * 3. * M_PI * fp.viscosity * d_max << " of the Stokes mobility\n";
        self_induced_summary = text.str();
      }
    double max_self_induced = 0.; // largest |u_self| / |v_p - u_undisturbed| seen

    FluidProperties fluid_properties;
    fluid_properties.density   = fp.density;
    fluid_properties.viscosity = fp.viscosity;
    fluid_properties.gravity   = p.gravity;

    // ---- Output (the scene is valid) ----
    const bool any_output = p.vtu_interval > 0. || p.csv_interval > 0. || fp.vtu_interval > 0. ||
                            p.particle_csv_interval > 0.;
    const std::string output_directory =
      any_output ? prepare_output_directory(p.output_directory, {p.base_name, fp.base_name},
                                            p.if_output_exists, false, p.file_name, comm) :
                   p.output_directory;
    ParticleOutput vtu(output_directory, p.base_name, rank, dem.n_ranks);
    PvdSeries fluid_snapshots(output_directory + "/" + fp.base_name + ".pvd", rank == 0);
    CsvSeries csv;
    if (p.csv_interval > 0.)
      csv.open(output_directory + "/" + p.base_name + ".csv",
               "time,mean_vx,mean_vy,mean_vz,fluid_kinetic_energy,pressure_drop,"
               "reaction_fx,reaction_fy,reaction_fz,clipped_nodes",
               rank == 0);

    std::ostringstream summary;
    summary << std::setprecision(p.summary_precision);
    if (rank == 0)
      {
        std::cout << "Sluice CFD-DEM - scene " << p.file_name << "\n"
                  << "  particles: " << dem.n_inserted << ", MPI ranks: " << dem.n_ranks
                  << ", fluid cells: " << fluid.n_active_cells() << ", fluid dofs: "
                  << fluid.n_dofs() << "\n"
                  << "  formulation: " << name_of(c.formulation)
                  << ", coupling: " << (c.two_way ? "two-way" : "one-way")
                  << ", drag: " << name_of(c.drag) << ", projection: "
                  << name_of(c.projection)
                  << std::setprecision(4) << ", kernel radius = " << radius << " m ("
                  << radius / d_max << " d)\n"
                  << "  fluid step = " << dt_fluid << " s, DEM step = " << dem.dt << " s ("
                  << n_sub << " per fluid step), contact time t_c = " << dem.t_contact << " s\n"
                  << self_induced_summary << std::flush;
      }

    // ---- The exchange in both directions ----
    std::vector<ExchangeParticle> handed(P.n_local);
    TrilinosWrappers::MPI::Vector solid_fraction, force_density;
    ProjectionReport              report;
    double                        max_imbalance = 0., max_fluid_rate = 0.;
    unsigned long long            n_outside     = 0;
    const auto give_particles = [&](const bool with_reaction) {
      handed.resize(P.n_local);
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          auto &h    = handed[i];
          h.position = dem.box.wrap(P.position[i]);
          h.velocity = P.velocity[i];
          h.volume   = 4. / 3. * M_PI * std::pow(P.radius[i], 3);
          double *e  = P.extra_of(i);
          h.reaction_force = Vec3();
          if (with_reaction)
            for (unsigned int d = 0; d < 3; ++d)
              h.reaction_force[d] = -e[cd::fluid_impulse + d] / dt_fluid;
          for (unsigned int d = 0; d < 3; ++d)
            e[cd::fluid_impulse + d] = 0.;
        }
      n_outside = exchange.gather(handed);
      if (self_induced && with_reaction)
        {
          std::vector<std::uint64_t> ids(P.n_local);
          std::vector<Vec3>          forces(P.n_local), deposits(P.n_local);
          for (unsigned int i = 0; i < P.n_local; ++i)
            {
              const double *e = P.extra_of(i);
              ids[i]          = P.id[i];
              forces[i]       = handed[i].reaction_force;
              deposits[i]     = P.position[i] - Vec3(e[cd::self_drift], e[cd::self_drift + 1],
                                                     e[cd::self_drift + 2]);
            }
          self_induced->record(ids, forces, deposits, comm);
        }
    };
    // Porosity (and with it the reaction) from the particles to the fluid.
    const auto project = [&](const bool initial) {
      if (!c.two_way)
        return;
      report = exchange.project(solid_fraction, c.max_solid_fraction, nullptr,
                                &fluid.momentum_source_dofs(), &force_density);
      TrilinosWrappers::MPI::Vector porosity(solid_fraction);
      porosity = 1.;
      porosity -= solid_fraction;
      if (initial)
        fluid.set_initial_porosity(porosity);
      else
        fluid.set_porosity(porosity);
      fluid.set_momentum_source(force_density);
      const double scale = std::max(norm(to_vec(report.particle_force)), 1e-300);
      if (norm(to_vec(report.particle_force)) > 0.)
        max_imbalance =
          std::max(max_imbalance, norm(to_vec(report.field_force - report.particle_force)) / scale);
    };
    // The fluid at the particles, and the forces frozen for the next step.
    bool       first_sample = true;
    const auto sample = [&]() {
      std::vector<FluidSample> samples = exchange.sample(fluid);
      double rate = 0.;
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          double *e = P.extra_of(i);
          if (self_induced && samples[i].found)
            {
              // The drag law wants the fluid without this particle's own
              // disturbance; the deposits then drift with that fluid.
              Vec3 drift(e[cd::self_drift], e[cd::self_drift + 1], e[cd::self_drift + 2]);
              const Vec3 u_self = self_induced->velocity(P.id[i], P.position[i] - drift);
              for (unsigned int d = 0; d < 3; ++d)
                samples[i].velocity[d] -= u_self[d];
              const Vec3 u = to_vec(samples[i].velocity);
              drift += dt_fluid * u;
              for (unsigned int d = 0; d < 3; ++d)
                e[cd::self_drift + d] = drift[d];
              if (norm(P.velocity[i] - u) > 0.)
                max_self_induced =
                  std::max(max_self_induced, norm(u_self) / norm(P.velocity[i] - u));
            }
          particle_fluid_forces(c, fluid_properties, samples[i], P.radius[i], P.velocity[i],
                                P.angular_velocity[i], dt_fluid, first_sample, e);
          // The explicit reaction relaxes the fluid at the rate beta / (eps rho_f),
          // beta ~ k (1 - eps) / V_p.
          if (c.two_way && samples[i].found)
            {
              const double eps = std::max(samples[i].porosity, 1. - c.max_solid_fraction);
              const double V   = 4. / 3. * M_PI * std::pow(P.radius[i], 3);
              rate = std::max(rate, e[cd::drag_coefficient] * (1. - eps) / (V * eps * fp.density));
            }
        }
      first_sample = false;
      rate = Utilities::MPI::max(rate, comm);
      max_fluid_rate = std::max(max_fluid_rate, rate);
      if (rate * dt_fluid > 1.)
        {
          std::ostringstream msg;
          msg << "entry 'fluid time/time step' = " << dt_fluid
              << " s is above the limit of the explicit particle reaction in the fluid: "
                 "dt_f beta / (eps rho_f) = "
              << rate * dt_fluid << " > 1; use a fluid step <= " << 1. / rate << " s";
          throw SolverFailure(msg.str());
        }
    };

    // Rayleigh-Taylor: the layer starts in the mode of wavenumber sqrt(2) 2 pi / L,
    // its lowest particle d/2 below the rest (Robinson et al. 2014, Eq. 40).
    const double rt_length = fp.upper_corner.x - fp.lower_corner.x;
    if (c.validation == CouplingValidationCase::rayleigh_taylor)
      {
        for (unsigned int i = 0; i < P.n_local; ++i)
          {
            const double X = 2. * M_PI * (P.position[i].x - fp.lower_corner.x) / rt_length;
            const double Y = 2. * M_PI * (P.position[i].y - fp.lower_corner.y) / rt_length;
            P.position[i].z -= 0.25 * P.radius[i] * (1. - std::cos(X)) * (1. - std::cos(Y));
          }
        dem.update_neighbours();
      }

    // The start: the particles' porosity, and the fluid at rest in it with its
    // hydrostatic pressure (a steady solve without reaction), so that buoyancy
    // acts from the first step.
    give_particles(false);
    // A particle outside the fluid mesh would fall freely, unseen by the fluid.
    if (n_outside > 0)
      throw InputError("error in '" + p.file_name + "': " + std::to_string(n_outside) +
                       " particle(s) lie outside the fluid mesh at the start ('insertion' "
                       "against 'fluid mesh'); insert them inside it, or enlarge the mesh");
    project(true);
    if (c.two_way)
      {
        TrilinosWrappers::MPI::Vector no_source(force_density);
        no_source = 0.;
        fluid.set_momentum_source(no_source);
      }
    fluid.solve_steady();
    sample();

    // ---- Validation probes ----
    const auto               &vc = c.validation;
    std::vector<double>       probe_times;
    std::vector<Vec3>         probe_velocities;
    const Vec3                v0 = global_mean_velocity(P, comm);
    double                    pressure_drop_sum = 0.;
    unsigned int              pressure_drop_samples = 0;
    // Rayleigh-Taylor: the lowest and the mean particle height per fluid step.
    std::vector<std::pair<double, double>> layer_heights;
    const auto lowest_and_mean_height = [&]() {
      double low = std::numeric_limits<double>::max(), sum = 0.;
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          low = std::min(low, P.position[i].z);
          sum += P.position[i].z;
        }
      low = Utilities::MPI::min(low, comm);
      sum = Utilities::MPI::sum(sum, comm);
      return std::make_pair(low, sum / std::max<double>(1., dem.n_inserted - dem.n_lost));
    };
    if (vc == CouplingValidationCase::rayleigh_taylor)
      {
        probe_times.push_back(0.);
        layer_heights.push_back(lowest_and_mean_height());
      }
    // Fluidized bed: (superficial velocity, bed pressure drop) per fluid step.
    std::vector<std::pair<double, double>> ramp;
    const double cross_section =
      (fp.upper_corner.x - fp.lower_corner.x) * (fp.upper_corner.y - fp.lower_corner.y);

    double       next_vtu = 0., next_csv = 0., next_fluid_vtu = 0., next_dump = 0.;
    double       last_dump = -1.;
    unsigned int n_dumps   = 0;
    const auto   dump_particles = [&](const double t) {
      write_particle_csv(P, t, output_directory, p.base_name, n_dumps++, comm);
      last_dump = t;
    };
    const auto write_output = [&](const double t, const bool force) {
      if (p.particle_csv_interval > 0. && (t >= next_dump - 0.5 * dt_fluid || force))
        {
          dump_particles(t);
          next_dump += p.particle_csv_interval;
        }
      if (p.vtu_interval > 0. && (t >= next_vtu - 0.5 * dem.dt || force))
        {
          vtu.write(P, t);
          next_vtu += p.vtu_interval;
        }
      if (fp.vtu_interval > 0. && (t >= next_fluid_vtu - 0.5 * dt_fluid || force))
        {
          fluid_snapshots.add(
            t, fluid.write_vtu(output_directory, fp.base_name, fluid_snapshots.size()));
          next_fluid_vtu += fp.vtu_interval;
        }
      if (p.csv_interval > 0. && (t >= next_csv - 0.5 * dt_fluid || force))
        {
          const Vec3           v = global_mean_velocity(P, comm);
          const FluidIntegrals I = fluid.integrals();
          if (csv.is_open())
            {
              csv.row() << t << "," << v.x << "," << v.y << "," << v.z << ","
                        << I.kinetic_energy << "," << I.pressure_drop << ","
                        << report.particle_force[0] << "," << report.particle_force[1] << ","
                        << report.particle_force[2] << "," << report.clipped_nodes;
              csv.end_row();
            }
          next_csv += p.csv_interval;
        }
    };
    write_output(0., false);

    const unsigned long long n_steps =
      static_cast<unsigned long long>(std::ceil(p.end_time / dt_fluid - 1e-9));
    ProgressLine progress(p.progress && rank == 0, p.end_time);
    NewtonReport newton_total;
    double       time = 0.;
    const FluidForcesKick kick{p.gravity};
    for (unsigned long long step = 1; step <= n_steps; ++step)
      {
        // 1. DEM sub-steps with the frozen fluid forces.
        if (c.fixed_particles)
          kick.hold(P, dt_fluid);
        else
          for (unsigned int s = 0; s < n_sub; ++s)
            dem.advance(kick);
        time = step * dt_fluid;

        // 2.-4. Porosity and reaction to the fluid, fluid step, fluid to the particles.
        give_particles(true);
        project(false);
        const NewtonReport r = fluid.advance(dt_fluid);
        newton_total.iterations += r.iterations;
        newton_total.linear_iterations += r.linear_iterations;
        if (fp.adaptive && step % fp.refinement_interval == 0)
          fluid.adapt_mesh();
        sample();

        // Probes.
        if (vc == CouplingValidationCase::rayleigh_taylor)
          {
            const auto [z_low, z_mean] = lowest_and_mean_height();
            probe_times.push_back(time);
            layer_heights.emplace_back(z_low, z_mean);
          }
        if (vc == CouplingValidationCase::sedimentation)
          {
            probe_times.push_back(time);
            probe_velocities.push_back(global_mean_velocity(P, comm));
          }
        if (vc == CouplingValidationCase::fluidized_bed)
          {
            const FluidIntegrals fi = fluid.integrals();
            if (time > 0.5 * p.end_time)
              {
                pressure_drop_sum += fi.pressure_drop;
                ++pressure_drop_samples;
              }
            if (!fi.flow_rates.empty())
              ramp.emplace_back(std::abs(fi.flow_rates[0]) / cross_section,
                                fi.pressure_drop - fp.density * norm(p.gravity) * fi.drop_distance);
          }
        write_output(time, false);
        if (progress.due())
          progress.update(time, step, dem.n_inserted - dem.n_lost);
      }
    progress.finish();
    if (p.particle_csv_interval > 0. && last_dump < time)
      dump_particles(time);

    // ---- Summary and validation ----
    const Vec3           v_end = global_mean_velocity(P, comm);
    const FluidIntegrals I     = fluid.integrals();
    summary << "final: time=" << time << " fluid_steps=" << n_steps << " dem_steps_per_fluid_step="
            << n_sub << " particles=" << dem.n_inserted - dem.n_lost << " outside_fluid="
            << n_outside << " mean_velocity=(" << v_end.x << ", " << v_end.y << ", " << v_end.z
            << ") fluid_kinetic_energy=" << I.kinetic_energy << "\n";
    summary << std::setprecision(3) << "coupling: momentum_exchange_imbalance=" << max_imbalance
            << " max_fluid_relaxation_rate_x_dt=" << max_fluid_rate * dt_fluid
            << " clipped_nodes=" << report.clipped_nodes
            << " newton_iterations=" << newton_total.iterations
            << " gmres_iterations=" << newton_total.linear_iterations << "\n";
    if (self_induced)
      summary << "coupling: self_induced_velocity_max_fraction_of_slip="
              << Utilities::MPI::max(max_self_induced, comm) << "\n";
    summary
            << std::setprecision(p.summary_precision);

    std::string name;
    double      value = 0., reference = 0., error = 0.;
    bool        extra_failed = false;
    const double rho_p = p.density[P.n_local > 0 ? P.type[0] : 0];
    if (vc == CouplingValidationCase::sedimentation)
      {
        // Against the single-particle equation through the whole history.
        const std::vector<Vec3> exact =
          single_particle_velocity(p, dem.r_max, rho_p, v0, probe_times);
        const Vec3   g_hat = (1. / norm(p.gravity)) * p.gravity;
        double       history = 0.;
        const double scale   = std::abs(dot(exact.back(), g_hat));
        for (unsigned int k = 0; k < exact.size(); ++k)
          history = std::max(history, std::abs(dot(probe_velocities[k] - exact[k], g_hat)) / scale);
        name      = "sedimentation";
        value     = dot(v_end, g_hat);
        reference = dot(exact.back(), g_hat);
        error     = std::abs(value - reference) / std::abs(reference);
        // The porosity the particle sees includes its own volume, spread over the kernel.
        double lowest_porosity = 1.;
        for (const FluidSample &sample : exchange.sample(fluid))
          if (sample.found)
            lowest_porosity = std::min(lowest_porosity, sample.porosity);
        summary << "check: sedimentation velocity_history_max_relative_deviation=" << history
                << " porosity_at_particle=" << Utilities::MPI::min(lowest_porosity, comm) << "\n";
      }
    else if (vc == CouplingValidationCase::porous_block)
      {
        // Steady block in a closed column: k(eps, w) w = eps (rho_p - rho_f) V g per
        // particle (every formulation), and the block settles at eps w, since
        // the volume flux through a horizontal plane is zero. The block's top
        // and bottom layers see the kernel-smoothed porosity edge and drift
        // away, so the value is the velocity of the particles in the middle
        // half of the block, where the projected porosity is the block's; the
        // spread of their velocities shows that they move as one block.
        const double d   = 2. * dem.r_max, V = M_PI / 6. * d * d * d;
        const double eps = c.block_porosity;
        const double w   = slip_for_force(p, d, eps, eps * (rho_p - fp.density) * V * norm(p.gravity));
        const Vec3   g_hat = (1. / norm(p.gravity)) * p.gravity;
        const auto   in_block_middle = in_middle_half(P, g_hat, comm);
        const std::vector<FluidSample> samples = exchange.sample(fluid);
        double sums[4] = {0., 0., 0., 0.};
        double slowest = std::numeric_limits<double>::max(), fastest = -slowest;
        for (unsigned int i = 0; i < P.n_local; ++i)
          if (samples[i].found && in_block_middle(P.position[i]))
            {
              const double v = dot(P.velocity[i], g_hat);
              sums[0] += 1.;
              sums[1] += v;
              sums[2] += samples[i].porosity;
              sums[3] += dot(P.velocity[i] - to_vec(samples[i].velocity), g_hat);
              slowest = std::min(slowest, v);
              fastest = std::max(fastest, v);
            }
        MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, comm);
        slowest          = Utilities::MPI::min(slowest, comm);
        fastest          = Utilities::MPI::max(fastest, comm);
        const double n   = std::max(sums[0], 1.);
        name             = "porous_block";
        value            = sums[1] / n;
        reference        = eps * w;
        error            = std::abs(value - reference) / reference;
        summary << "check: porous_block middle_particles=" << sums[0]
                << " mean_porosity=" << sums[2] / n << " mean_slip=" << sums[3] / n
                << " slip_from_drag_law=" << w << " velocity_spread=" << (fastest - slowest) / reference
                << " whole_block_velocity=" << dot(v_end, g_hat) << "\n";
      }
    else if (vc == CouplingValidationCase::packed_bed)
      {
        // Mean pressure gradient at the particles in the middle half of the bed
        // against Ergun at the bed porosity and superficial velocity.
        const auto in_bed_middle = in_middle_half(P, Vec3(0., 0., 1.), comm);
        const std::vector<FluidSample> samples = exchange.sample(fluid);
        double sums[4] = {0., 0., 0., 0.};
        for (unsigned int i = 0; i < P.n_local; ++i)
          if (samples[i].found && in_bed_middle(P.position[i]))
            {
              sums[0] += -samples[i].pressure_gradient[2];
              sums[1] += 1.;
              sums[2] += samples[i].porosity;
              sums[3] += samples[i].velocity[2];
            }
        MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, comm);
        const double U = I.flow_rates.empty() ? 0. : std::abs(I.flow_rates[0]) / cross_section;
        const double eps = c.block_porosity, d = 2. * dem.r_max, mu = fp.viscosity;
        name      = "packed_bed";
        value     = sums[0] / std::max(sums[1], 1.);
        reference = 150. * mu * (1. - eps) * (1. - eps) * U / (eps * eps * eps * d * d) +
                    1.75 * fp.density * (1. - eps) * U * U / (eps * eps * eps * d);
        error     = std::abs(value - reference) / reference;
        summary << "check: packed_bed superficial_velocity=" << U << " bed_particles_sampled=" << sums[1]
                << " mean_porosity=" << sums[2] / std::max(sums[1], 1.)
                << " mean_fluid_velocity=" << sums[3] / std::max(sums[1], 1.) << "\n";
      }
    else if (vc == CouplingValidationCase::fluidized_bed)
      {
        // Bed pressure drop: measured drop minus the fluid's own hydrostatics,
        // averaged over the second half, against the buoyant weight per area.
        double weight = 0.;
        for (unsigned int i = 0; i < P.n_local; ++i)
          weight += P.mass[i] * (1. - fp.density / p.density[P.type[i]]) * norm(p.gravity);
        weight = Utilities::MPI::sum(weight, comm);
        name      = "fluidized_bed";
        value     = pressure_drop_sum / std::max(1u, pressure_drop_samples) -
                fp.density * norm(p.gravity) * I.drop_distance;
        reference = weight / cross_section;
        error     = std::abs(value - reference) / reference;

        // Minimum fluidization from the inlet ramp (Kunii & Levenspiel): the
        // fixed-bed branch, dp = a U + b U^2 fitted by least squares to the
        // ramp's points (inlet flow started) between 10% and 80% of the weight
        // per area, before the bed first carries 80%, meets the weight per
        // area at U_mf.
        double s22 = 0., s23 = 0., s33 = 0., s2p = 0., s3p = 0.; // sums of U^2, U^3, U^4, U p, U^2 p
        unsigned int n_fit = 0;
        for (const auto &[U, dp] : ramp)
          {
            if (U <= 1e-12) // before the ramp: the bed settles
              continue;
            if (dp > 0.8 * reference)
              break;
            if (dp < 0.1 * reference)
              continue;
            s22 += U * U, s23 += U * U * U, s33 += U * U * U * U;
            s2p += U * dp, s3p += U * U * dp;
            ++n_fit;
          }
        const double det = s22 * s33 - s23 * s23;
        if (n_fit >= 3 && det > 0.)
          {
            const double a = (s2p * s33 - s3p * s23) / det, b = (s22 * s3p - s23 * s2p) / det;
            const double U_mf = b != 0. ? (-a + std::sqrt(a * a + 4. * b * reference)) / (2. * b) :
                                          reference / a;
            // Wen & Yu (1966): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7.
            const double d  = 2. * dem.r_max, rho = fp.density, mu = fp.viscosity;
            const double Ar = d * d * d * rho * (rho_p - rho) * norm(p.gravity) / (mu * mu);
            const double wen_yu = (std::sqrt(33.7 * 33.7 + 0.0408 * Ar) - 33.7) * mu / (rho * d);
            summary << "check: fluidized_bed minimum_fluidization_velocity=" << U_mf
                    << " wen_yu=" << wen_yu << " ratio=" << U_mf / wen_yu
                    << " fit_points=" << n_fit << " archimedes=" << Ar << "\n";
          }
        else
          summary << "check: fluidized_bed minimum_fluidization_velocity=none (the inlet ramp "
                     "has fewer than three points between 10% and 80% of the bed weight)\n";
      }

    else if (vc == CouplingValidationCase::rayleigh_taylor)
      {
        // The depth of the lowest particle below its undisturbed layer,
        // a = z_low(0) + d/2 - z_low - (zbar(0) - zbar) (the layer's uniform
        // settling removed), grows as a0 cosh(n t) in the linear regime. The fit
        // uses the steps while k a <= 0.5 and the front is in the upper half of
        // the clear fluid below the layer.
        const double d  = 2. * dem.r_max;
        const double k  = std::sqrt(2.) * 2. * M_PI / rt_length;
        const double eps = c.block_porosity, g = norm(p.gravity);
        const double z_front0 = layer_heights[0].first;
        const double clear_depth = z_front0 - fp.lower_corner.z;
        std::vector<double> t_fit, a_fit;
        for (std::size_t i = 0; i < layer_heights.size(); ++i)
          {
            const double a = z_front0 + 0.5 * d - layer_heights[i].first -
                             (layer_heights[0].second - layer_heights[i].second);
            if (k * a > 0.5 || layer_heights[i].first < z_front0 - 0.5 * clear_depth)
              break;
            t_fit.push_back(probe_times[i]);
            a_fit.push_back(a);
          }
        const double rho1 = fp.density, mu1 = fp.viscosity;
        const double rho2 = eps * rho1 + (1. - eps) * rho_p;
        const double lower =
          rayleigh_taylor_growth_rate(rho1, mu1, rho2, krieger_viscosity(mu1, 1. - eps), k, g);
        // The bounds of the two-fluid model: the heavy layer with the Krieger
        // viscosity of the suspension (lower) and without viscosity (upper,
        // sqrt(A g k)); viscosity only slows the growth. The rate with the clear
        // fluid's viscosity in both layers is printed for comparison.
        const double upper       = inviscid_growth_rate(rho1, rho2, k, g);
        const double clear_fluid = rayleigh_taylor_growth_rate(rho1, mu1, rho2, mu1, k, g);
        name      = "rayleigh_taylor";
        value     = fit_growth_rate_from_rest(t_fit, a_fit);
        // The nearer bound; the error is the distance outside [lower, upper].
        reference = std::abs(value - lower) < std::abs(value - upper) ? lower : upper;
        error     = value < lower || value > upper ? std::abs(value - reference) / reference : 0.;
        summary << "check: rayleigh_taylor lower_bound_krieger=" << lower
                << " upper_bound_inviscid=" << upper << " clear_fluid_viscosity=" << clear_fluid
                << " fitted_steps=" << t_fit.size()
                << " fit_end_time=" << (t_fit.empty() ? 0. : t_fit.back())
                << " final_amplitude=" << (a_fit.empty() ? 0. : a_fit.back()) << "\n";
      }

    // Coupling scheme 3: the fluid's momentum source integrates to minus the
    // particles' exchanged forces, to round-off.
    if (c.two_way && max_imbalance > 1e-10)
      {
        summary << "check: momentum exchange imbalance " << max_imbalance << " > 1e-10 FAILED\n";
        extra_failed = true;
      }
    const double wall_s = seconds();
    summary << std::setprecision(4) << "timing: wall_s=" << wall_s << "\n"
            << std::setprecision(p.summary_precision);
    if (vtu.n_written() > 0)
      summary << "output: " << vtu.n_written() << " particle snapshots in " << output_directory
              << "/" << p.base_name << ".pvd\n";
    if (n_dumps > 0)
      summary << "output: " << n_dumps << " particle dumps in " << output_directory << "/"
              << p.base_name << "_state_*.csv\n";
    if (!name.empty())
      write_result_line(summary, name, value, reference, error, wall_s);
    if (rank == 0)
      std::cout << summary.str() << std::flush;
    if (extra_failed || (c.tolerance > 0. && !name.empty() && error > c.tolerance))
      {
        if (rank == 0)
          std::cerr << "sluice: validation error " << error << " exceeds the tolerance "
                    << c.tolerance << " set in 'cfd-dem validation/tolerance'\n";
        return 3;
      }
    return 0;
  }
} // namespace sluice
