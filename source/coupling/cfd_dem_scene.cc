// The coupled time loop (Zhou et al. 2010, coupling scheme 3; doc/coupling.md):
//
//   for each fluid step t^n -> t^n+1 = t^n + dt_f:
//     1. the DEM takes n_sub steps of dt_f / n_sub: velocity Verlet whose kicks
//        integrate the drag exactly for the frozen k and u (fluid_kick.h), so
//        tau_p << dt needs no smaller step; each particle adds up the impulse
//        the fluid gave it (the exchanged part);
//     2. the particles go to the fluid, which takes, with one set of weights,
//        their volume (porosity at t^n+1) and minus that impulse / dt_f (its
//        momentum source): the field's integral is the particles' total to
//        round-off, so momentum is conserved exactly;
//     3. the fluid advances to t^n+1 (BDF, with d eps/dt from the porosity);
//     4. the fluid is sampled at the particles and each particle's drag
//        coefficient and other forces are frozen for the next step.
// One-way coupling skips step 2: the fluid sees neither porosity nor reaction.
// The fluid is reached only through FluidBackend (the VANS solver, or the SPH
// fluid with 'cfd-dem/fluid backend = sph'; make_fluid_backend.h), and
// the validation cases are probes (coupling_probe.h). A checkpoint, at the
// end of a fluid step, is the DEM's (dem_checkpoint.h) with the fluid's files,
// the self-induced histories and the exchange's and output's records added.
// In a clump scene the coupling's particles are the bodies (fluid_shapes.h):
// each deposits its union volume and feels the drag at its centroid.

#include <sluice/core/binary_io.h>
#include <sluice/core/names.h>
#include <sluice/core/output_files.h>
#include <sluice/core/progress.h>
#include <sluice/core/result_line.h>
#include <sluice/core/scene_records.h>
#include <sluice/core/stage_clock.h>
#include <sluice/core/series_files.h>
#include <sluice/coupling/cfd_dem_scene.h>
#include <sluice/coupling/coupling_probe.h>
#include <sluice/coupling/fluid_kick.h>
#include <sluice/coupling/fluid_shapes.h>
#include <sluice/coupling/make_fluid_backend.h>
#include <sluice/coupling/particle_fluid_forces.h>
#include <sluice/coupling/self_induced_velocity.h>
#include <sluice/coupling/vans_backend.h>
#include <sluice/dem/dem_checkpoint.h>
#include <sluice/dem/dem_system.h>
#include <sluice/dem/mesh_load_columns.h>
#include <sluice/dem/particle_csv.h>
#include <sluice/dem/particle_output.h>
#include <sluice/dem/scene_series.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// The largest fluid step times the exchange's wave rate
    /// (check_exchange_waves): a porous block stayed calm at 0.31 and its
    /// layers' velocities grew at 0.62 (doc/sph.md, step 5).
    constexpr double exchange_wave_limit = 1. / 3.;

    [[noreturn]] void fail(const SceneParameters &p, const std::string &entry,
                           const std::string &what)
    {
      throw InputError("error in '" + p.file_name + "': entry '" + entry + "' " + what);
    }

    /// A coupled scene checkpoints fluid, DEM and coupling together, with the
    /// 'checkpoint' subsection: the fluid scene's own entries would save half.
    void refuse_fluid_checkpoint_entries(const SceneParameters &p)
    {
      for (const auto &[set, entry] :
           {std::pair{p.fluid.checkpoint_interval > 0, "fluid output/checkpoint interval"},
            {!p.fluid.restart_from.empty(), "fluid time/restart from"}})
        if (set)
          fail(p, entry, "is set, but a cfd-dem scene checkpoints its fluid with its particles: "
                         "use the 'checkpoint' subsection and leave this entry at its default");
    }

    /// Not in a scene that compares with an equation starting at once, and
    /// in a validation scene ending before the scene does (its measurement
    /// is of the released particles). A scene without one may end inside the
    /// ramp: the first part of a run continued from its checkpoint.
    void check_weight_ramp(const SceneParameters &p)
    {
      const CouplingParameters &c = p.coupling;
      if (!(c.weight_ramp_time > 0.))
        return;
      if (c.validation == CouplingValidationCase::sedimentation)
        fail(p, "cfd-dem/weight ramp time",
             "is set, but 'cfd-dem validation/case = sedimentation' compares with the single-"
             "particle equation from a release at once: leave it at 0");
      if (c.validation != CouplingValidationCase::none && !(c.weight_ramp_time < p.end_time))
        fail(p, "cfd-dem/weight ramp time",
             "= " + exact_text(c.weight_ramp_time) + " s does not end before 'simulation/end "
             "time' = " + exact_text(p.end_time) + " s, and 'cfd-dem validation/case' measures "
             "the released particles");
    }

    /// The porous block's average is taken over the released block only.
    void check_averaging_start(const SceneParameters &p)
    {
      const CouplingParameters &c = p.coupling;
      if (!(c.averaging_start > 0.))
        return;
      if (c.validation != CouplingValidationCase::porous_block)
        fail(p, "cfd-dem validation/averaging start",
             "is set, but only 'cfd-dem validation/case = porous_block' averages: leave it "
             "at 0");
      if (c.averaging_start < c.weight_ramp_time)
        fail(p, "cfd-dem validation/averaging start",
             "= " + exact_text(c.averaging_start) + " s is inside the weight ramp ('cfd-dem/"
             "weight ramp time' = " + exact_text(c.weight_ramp_time) + " s): the block is "
             "measured once released");
      if (!(c.averaging_start < p.end_time))
        fail(p, "cfd-dem validation/averaging start",
             "= " + exact_text(c.averaging_start) + " s is not before 'simulation/end time' = " +
             exact_text(p.end_time) + " s");
    }

    /// 'cfd-dem/semi-implicit drag' needs a finite-element fluid that feels
    /// the particles, on one mesh (the term a step returns is the one the
    /// step before applied), and no self-induced correction (whose measured
    /// response is of the explicit exchange).
    void check_semi_implicit_drag(const SceneParameters &p)
    {
      const CouplingParameters &c = p.coupling;
      if (!c.semi_implicit_drag)
        return;
      const std::string entry = "cfd-dem/semi-implicit drag";
      if (!c.two_way)
        fail(p, entry, "is 'true' in a one-way scene, where the fluid never feels the particles");
      if (c.fluid_backend == FluidBackendKind::sph)
        fail(p, entry, "is 'true' with 'cfd-dem/fluid backend = sph': only the finite-element "
                       "fluid takes the drag into its matrix");
      if (p.fluid.adaptive)
        fail(p, entry, "needs a fixed fluid mesh ('fluid refinement/adaptive = false'): each "
                       "step returns the drag term the step before applied on the same mesh");
      if (c.self_induced_correction)
        fail(p, entry, "is 'true' with 'cfd-dem/self-induced velocity correction', whose "
                       "measured response is the explicit exchange's: use one or the other");
    }

    /// The fluid and coupling entries a coupled checkpoint depends on (the
    /// DEM's own are checked by the DEM; the fluid's mesh by the fluid).
    std::vector<std::string> coupled_signature(const SceneParameters &p,
                                               const FluidParameters &fp)
    {
      const CouplingParameters &c = p.coupling;
      const auto                x = [](const double v) { return exact_text(v); };
      std::ostringstream        fluid, coupling;
      fluid << "density " << x(fp.density) << " viscosity " << x(fp.viscosity) << " time step "
            << x(fp.time_step) << " integration " << name_of(fp.time_integration) << " degrees "
            << fp.velocity_degree << " " << fp.pressure_degree << " subdivisions "
            << fp.subdivisions[0] << " " << fp.subdivisions[1] << " " << fp.subdivisions[2]
            << " refinement " << fp.initial_refinement << (fp.adaptive ? " adaptive" : " fixed");
      coupling << name_of(c.formulation) << (c.two_way ? " two-way" : " one-way") << " drag "
               << name_of(c.drag) << " projection " << name_of(c.projection) << " kernel radius "
               << x(c.kernel_radius) << " smoothing " << x(c.smoothing_bandwidth)
               << " self-induced " << c.self_induced_correction << " memory "
               << x(c.self_induced_memory) << " fixed particles " << c.fixed_particles;
      if (c.weight_ramp_time > 0.)
        coupling << " weight ramp " << x(c.weight_ramp_time);
      if (c.averaging_start > 0.) // the probe's running average belongs to its window
        coupling << " averaging start " << x(c.averaging_start);
      if (c.semi_implicit_drag)
        coupling << " semi-implicit drag";
      if (c.fluid_backend == FluidBackendKind::sph)
        {
          const SphParameters &s = p.sph;
          fluid << " sph spacing " << x(s.spacing) << " smoothing " << x(s.smoothing_factor)
                << " kernel " << s.kernel << " coupling length " << x(c.sph_coupling_length);
          if (s.viscosity_form != "morris")
            fluid << " viscosity form " << s.viscosity_form;
          if (s.time_integration != "leap_frog")
            fluid << " " << s.time_integration;
          if (s.fixed_smoothing_length)
            fluid << " fixed_h";
          if (s.solid_walls)
            fluid << " solid walls k " << x(s.solid_wall_stiffness) << " e "
                  << x(s.solid_wall_restitution);
        }
      return {"fluid = " + fluid.str(), "cfd-dem = " + coupling.str()};
    }

    /// The fluid entries as the coupling formulation needs them.
    FluidParameters coupled_fluid_parameters(const SceneParameters &p)
    {
      const CouplingParameters &c  = p.coupling;
      FluidParameters           fp = p.fluid;
      // (The SPH fluid integrates in time by its own scheme, sph_solver.h.)
      if (fp.time_integration == TimeIntegration::steady &&
          c.fluid_backend == FluidBackendKind::fe)
        fail(p, "fluid time/integration", "is 'steady'; a coupled scene needs 'bdf1' or 'bdf2'");
      if (fp.drag != PorousDrag::none)
        fail(p, "fluid/porous drag", "must be 'none' in a coupled scene: the particles are the drag");
      fp.formulation = c.formulation == CouplingFormulation::set_ii ? VansFormulation::model_a :
                                                                      VansFormulation::model_b;
      fp.porosity_as_field        = c.two_way;
      fp.momentum_source_as_field = c.two_way;
      fp.exchange_drag_as_field   = c.two_way && c.semi_implicit_drag;
      fp.use_gravity              = true;
      return fp;
    }

    /// Newton's absolute tolerance is a force [N]: above the particles' forces
    /// the fluid's first residual already meets it and the fluid never moves
    /// (a silent one-way coupling). Require 1e-3 of the smallest buoyant weight.
    void check_newton_tolerance(const SceneParameters &p, const FluidParameters &fp,
                                const DemSystem &dem, const FluidShapes &shapes, MPI_Comm comm)
    {
      // The SPH fluid solves no nonlinear system.
      if (!p.coupling.two_way || !(norm(p.gravity) > 0.) ||
          p.coupling.fluid_backend == FluidBackendKind::sph)
        return;
      const ParticleStorage &P               = dem.handler_particles();
      double                 smallest_weight = std::numeric_limits<double>::max();
      for (unsigned int i = 0; i < P.n_local; ++i)
        smallest_weight =
          std::min(smallest_weight,
                   std::abs(P.mass[i] - fp.density * shapes.volume(i)) * norm(p.gravity));
      MPI_Allreduce(MPI_IN_PLACE, &smallest_weight, 1, MPI_DOUBLE, MPI_MIN, comm);
      if (smallest_weight > 0. && fp.newton_tolerance > 1e-3 * smallest_weight)
        fail(p, "fluid solver/newton tolerance",
             "= " + to_text(fp.newton_tolerance) +
               " N is above 1e-3 of the smallest particle's buoyant weight (" +
               to_text(smallest_weight) +
               " N): the fluid's first residual would meet it and the fluid would not feel "
               "the particles; use at most " + to_text(1e-3 * smallest_weight) + " N");
    }

    /// The two directions of the exchange, and what they record.
    class Exchange
    {
    public:
      Exchange(const SceneParameters &p, const FluidParameters &fp, const CouplingFields &fields,
               DemSystem &dem, const FluidShapes &shapes, FluidBackend &fluid,
               std::unique_ptr<SelfInducedVelocity> self_induced, MPI_Comm comm)
        : p(p), c(p.coupling), fp(fp), fields(fields), dem(dem), shapes(shapes), fluid(fluid)
        , comm(comm)
        , self_induced(std::move(self_induced))
      {
        properties.density   = fp.density;
        properties.viscosity = fp.viscosity;
        properties.gravity   = p.gravity;
      }

      /// The particles to the fluid, with the reaction they owe it
      /// (-impulse / dt_f) when asked; the impulses start again from zero.
      void give_particles(const bool with_reaction)
      {
        ParticleStorage &P = dem.handler_particles();
        handed.resize(P.n_local);
        for (unsigned int i = 0; i < P.n_local; ++i)
          {
            auto &h    = handed[i];
            h.position = dem.box.wrap(P.position[i]);
            h.velocity = P.velocity[i];
            h.volume   = shapes.volume(i);
            double *e  = P.extra_of(i);
            h.drag_coefficient = e[fields.drag_coefficient]; // frozen for this step
            h.reaction_force = Vec3();
            if (with_reaction)
              for (unsigned int d = 0; d < 3; ++d)
                h.reaction_force[d] = -e[fields.fluid_impulse + d] / fp.time_step;
            for (unsigned int d = 0; d < 3; ++d)
              e[fields.fluid_impulse + d] = 0.;
          }
        n_outside = fluid.receive(handed);
        if (self_induced && with_reaction)
          record_self_induced();
      }

      /// Porosity (and with it the reaction) from the particles to the fluid.
      void deposit(const bool initial)
      {
        if (!c.two_way)
          return;
        report             = fluid.deposit(initial);
        const double scale = std::max(norm(report.particle_force), 1e-300);
        if (norm(report.particle_force) > 0.)
          max_imbalance = std::max(max_imbalance,
                                   norm(report.field_force - report.particle_force) / scale);
        // The semi-implicit exchange's drag coefficients are conserved alike.
        if (report.particle_drag > 0.)
          max_imbalance =
            std::max(max_imbalance,
                     std::abs(report.field_drag - report.particle_drag) / report.particle_drag);
      }

      /// The fluid at the particles at 'time', and the forces frozen for the
      /// next step. Throws SolverFailure when the explicit reaction would be
      /// unstable.
      void sample(const double time)
      {
        ParticleStorage &P = dem.handler_particles();
        keep_samples();
        double rate = 0.;
        for (unsigned int i = 0; i < P.n_local; ++i)
          {
            double             *e      = P.extra_of(i);
            ParticleFluidSample sample = samples[i];
            if (self_induced && sample.found)
              remove_self_induced(i, sample);
            const FluidShape shape = shapes.shape(i, sample.velocity - P.velocity[i]);
            particle_fluid_forces(c, properties, sample, shape, P.velocity[i],
                                  P.angular_velocity[i], fp.time_step, first_sample, fields, e);
            if (sample.found)
              hold_weight(i, shape.volume, time, e);
            // The explicit reaction relaxes the fluid at the rate
            // beta / (eps rho_f), beta ~ k (1 - eps) / V_p.
            if (c.two_way && sample.found)
              {
                const double eps = std::max(sample.porosity, 1. - c.max_solid_fraction);
                rate = std::max(rate, e[fields.drag_coefficient] * (1. - eps) /
                                        (shape.volume * eps * fp.density));
              }
          }
        first_sample = false;
        check_exchange_waves(samples, false);
        MPI_Allreduce(MPI_IN_PLACE, &rate, 1, MPI_DOUBLE, MPI_MAX, comm);
        max_fluid_rate = std::max(max_fluid_rate, rate);
        // (The semi-implicit exchange has no such limit: doc/coupling.md.)
        if (rate * fp.time_step > 1. && !c.semi_implicit_drag)
          {
            std::ostringstream msg;
            msg << "entry 'fluid time/time step' = " << fp.time_step
                << " s is above the limit of the explicit particle reaction in the fluid: "
                   "dt_f beta / (eps rho_f) = "
                << rate * fp.time_step << " > 1; use a fluid step <= " << 1. / rate << " s";
            throw SolverFailure(msg.str());
          }
      }

      /// 'cfd-dem/weight ramp time': until the ramp ends, a support force the
      /// fluid does not get holds the part (1 - r) of the particle's weight
      /// beyond its buoyancy, r = (1 - cos(pi t / T)) / 2 at the middle of the
      /// coming fluid step. Smooth, so that a weakly compressible column takes
      /// the suspension's weight without ringing at its acoustic period.
      void hold_weight(const unsigned int i, const double volume, const double time, double *e)
      {
        const double T = c.weight_ramp_time, t = time + 0.5 * fp.time_step;
        if (!(T > 0.) || t >= T)
          return;
        const ParticleStorage &P       = dem.handler_particles();
        const double           r       = 0.5 * (1. - std::cos(M_PI * t / T));
        const double           excess  = P.mass[i] - fp.density * volume; // [kg]
        const Vec3             support = (-(1. - r) * excess) * p.gravity;
        for (unsigned int d = 0; d < 3; ++d)
          e[fields.other_force + d] += support[d];
      }

      /// Two-way with a compressible fluid: the fluid step must resolve the
      /// pressure wave the exchange carries through the fluid fraction
      /// (FluidBackend::exchange_wave_rate); throws InputError 'at_start',
      /// SolverFailure later, naming the entry and the largest step.
      void check_exchange_waves(const std::vector<ParticleFluidSample> &samples,
                                const bool                               at_start) const
      {
        if (!c.two_way || c.fluid_backend != FluidBackendKind::sph)
          return;
        const ParticleStorage &P = dem.handler_particles();
        double                 rate = 0., eps_at = 1.;
        for (unsigned int i = 0; i < P.n_local; ++i)
          if (samples[i].found)
            {
              const double eps = std::max(samples[i].porosity, 1. - c.max_solid_fraction);
              const double r   = fluid.exchange_wave_rate(eps, P.mass[i] / shapes.volume(i));
              if (r > rate)
                {
                  rate   = r;
                  eps_at = eps;
                }
            }
        // (eps_at is this rank's: the SPH fluid runs on one rank.)
        MPI_Allreduce(MPI_IN_PLACE, &rate, 1, MPI_DOUBLE, MPI_MAX, comm);
        if (!(rate * fp.time_step > exchange_wave_limit))
          return;
        std::ostringstream msg;
        msg << std::setprecision(4) << "entry 'fluid time/time step' = " << fp.time_step
            << " s is above the limit of the explicit exchange with the weakly compressible "
               "SPH fluid: dt_f c_s / h_c sqrt(rho_f (1 - eps) / (rho_p eps)) = "
            << rate * fp.time_step << " > " << exchange_wave_limit << " (at eps = " << eps_at
            << "; the particles and the fluid pass a pressure wave through the fluid fraction, "
               "which grows at longer steps); use a fluid step <= "
            << exchange_wave_limit / rate << " s";
        if (at_start)
          throw InputError("error in '" + p.file_name + "': " + msg.str());
        throw SolverFailure(msg.str());
      }

      /// The fluid at the particles where they are now, kept for the probes
      /// (as the fluid gives it: without the self-induced correction).
      void keep_samples() { samples = fluid.sample(); }
      const std::vector<ParticleFluidSample> &kept_samples() const { return samples; }

      bool corrects_self_induced() const { return self_induced != nullptr; }
      /// The correction measured after the start (the SPH fluid's).
      void set_self_induced(std::unique_ptr<SelfInducedVelocity> correction)
      {
        self_induced = std::move(correction);
      }

      /// Collective. The 'coupling:' lines of the summary.
      void summarise(std::ostream &out, const NewtonReport &newton) const
      {
        out << std::setprecision(3) << "coupling: momentum_exchange_imbalance=" << max_imbalance
            << " max_fluid_relaxation_rate_x_dt=" << max_fluid_rate * fp.time_step
            << " clipped_nodes=" << report.clipped_nodes;
        // The SPH fluid reports its steps as iterations (sph_backend.h).
        if (c.fluid_backend == FluidBackendKind::sph)
          out << " sph_steps=" << newton.iterations << "\n";
        else
          {
            out << " newton_iterations=" << newton.iterations
                << " gmres_iterations=" << newton.linear_iterations;
            if (newton.picard_starts > 0)
              out << " picard_starts=" << newton.picard_starts;
            out << "\n";
          }
        if (self_induced)
          {
            double largest = max_self_induced;
            MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, comm);
            out << "coupling: self_induced_velocity_max_fraction_of_slip=" << largest << "\n";
          }
      }

      /// Collective. What a checkpoint keeps of the exchange; and back.
      void save(SceneRecords &r) const
      {
        double largest = max_self_induced;
        MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, comm);
        r.set_numbers("exchange", {double(first_sample), double(n_outside), max_imbalance,
                                   max_fluid_rate, largest});
        const Vec3 &f = report.particle_force, &g = report.field_force;
        r.set_numbers("deposit", {f.x, f.y, f.z, g.x, g.y, g.z, double(report.clipped_nodes)});
      }
      void restore(const SceneRecords &r)
      {
        const std::vector<double> e = r.numbers("exchange"), d = r.numbers("deposit");
        if (e.size() != 5 || d.size() != 7)
          throw InputError("error in '" + p.file_name + "': entry 'checkpoint/restart from': "
                           "the checkpoint's exchange records are missing or damaged");
        first_sample          = e[0] != 0.;
        n_outside             = static_cast<unsigned long long>(e[1]);
        max_imbalance         = e[2];
        max_fluid_rate        = e[3];
        max_self_induced      = e[4];
        report.particle_force = Vec3(d[0], d[1], d[2]);
        report.field_force    = Vec3(d[3], d[4], d[5]);
        report.clipped_nodes  = static_cast<unsigned int>(d[6]);
      }
      /// Rank 0 writes the self-induced histories (every rank has them all).
      void save_self_induced(const std::string &file) const
      {
        if (self_induced && dem.rank == 0)
          write_file_atomically(file, self_induced->serialize());
      }

      DepositReport      report;
      unsigned long long n_outside     = 0;
      double             max_imbalance = 0., max_fluid_rate = 0.;
      double             max_self_induced = 0.; // largest |u_self| / |v_p - u_undisturbed|

    private:
      void record_self_induced()
      {
        const ParticleStorage     &P = dem.handler_particles();
        std::vector<std::uint64_t> ids(P.n_local);
        std::vector<Vec3>          forces(P.n_local), deposits(P.n_local);
        for (unsigned int i = 0; i < P.n_local; ++i)
          {
            const double *e = P.extra_of(i);
            ids[i]          = P.id[i];
            // The part of the reaction that the particle's fluid fraction
            // balances (the displaced fluid's weight and pressure forces, set
            // I and III) moves no fluid; the rest (drag, lift, added mass) does.
            forces[i] = handed[i].reaction_force + Vec3(e[fields.self_balanced],
                                                        e[fields.self_balanced + 1],
                                                        e[fields.self_balanced + 2]);
            deposits[i]     = P.position[i] - Vec3(e[fields.self_drift], e[fields.self_drift + 1],
                                               e[fields.self_drift + 2]);
          }
        self_induced->record(ids, forces, deposits, comm);
      }

      /// The drag law wants the fluid without this particle's own disturbance;
      /// the deposits then drift with that fluid.
      void remove_self_induced(const unsigned int i, ParticleFluidSample &sample)
      {
        ParticleStorage &P = dem.handler_particles();
        double          *e = P.extra_of(i);
        Vec3       drift(e[fields.self_drift], e[fields.self_drift + 1], e[fields.self_drift + 2]);
        const Vec3 u_self = self_induced->velocity(P.id[i], P.position[i] - drift);
        for (unsigned int d = 0; d < 3; ++d)
          sample.velocity[d] -= u_self[d];
        const Vec3 u = sample.velocity;
        drift += fp.time_step * u;
        for (unsigned int d = 0; d < 3; ++d)
          e[fields.self_drift + d] = drift[d];
        if (norm(P.velocity[i] - u) > 0.)
          max_self_induced = std::max(max_self_induced, norm(u_self) / norm(P.velocity[i] - u));
      }

      const SceneParameters                &p;
      const CouplingParameters             &c;
      const FluidParameters                &fp;
      const CouplingFields                 &fields;
      DemSystem                            &dem;
      const FluidShapes                    &shapes;
      FluidBackend                         &fluid;
      MPI_Comm                              comm;
      std::unique_ptr<SelfInducedVelocity>  self_induced;
      FluidProperties                       properties;
      std::vector<ExchangeParticle>         handed;
      std::vector<ParticleFluidSample>      samples; // the fluid at the particles, last kept
      bool                                  first_sample = true;
    };

    /// The scene's files: particle snapshots and dumps, fluid snapshots, and
    /// the .csv of mean particle velocity, fluid energy and exchange. After a
    /// restart (records from the checkpoint) every series continues.
    class CoupledOutput
    {
    public:
      CoupledOutput(const SceneParameters &p, const FluidParameters &fp, const DemSystem &dem,
                    FluidBackend &fluid, const bool restart, const double time,
                    const SceneRecords &records, const bool probe_writes_files, MPI_Comm comm)
        : p(p), fp(fp), dem(dem), fluid(fluid), comm(comm)
        , directory(p.vtu_interval > 0. || p.csv_interval > 0. || fp.vtu_interval > 0. ||
                        p.particle_csv_interval > 0. || p.checkpoint_step_interval > 0 ||
                        p.checkpoint_time_interval > 0. || probe_writes_files ?
                      prepare_output_directory(p.output_directory, {p.base_name, fp.base_name},
                                               p.if_output_exists, restart, p.file_name, comm) :
                      p.output_directory)
        , vtu(directory, p.base_name, dem.rank, dem.n_ranks, snapshot_fields(dem))
        , fluid_snapshots(directory + "/" + fp.base_name + ".pvd", dem.rank == 0)
        , next_vtu(records.number("next_vtu", 0.)), next_csv(records.number("next_csv", 0.))
        , next_fluid_vtu(records.number("next_fluid_vtu", 0.))
        , next_dump(records.number("next_dump", 0.)), last_dump(records.number("last_dump", -1.))
        , n_dumps(records.number("dumps", 0.))
      {
        vtu.index().restore(records.all("snapshot"));
        fluid_snapshots.restore(records.all("fluid_snapshot"));
        if (p.csv_interval > 0.)
          csv.open(directory + "/" + p.base_name + ".csv", csv_header(), dem.rank == 0,
                   restart, time);
      }

      const std::string &output_directory() const { return directory; }

      /// What a checkpoint keeps, so that the series continue.
      void save(SceneRecords &r) const
      {
        r.set("next_vtu", next_vtu);
        r.set("next_csv", next_csv);
        r.set("next_fluid_vtu", next_fluid_vtu);
        r.set("next_dump", next_dump);
        r.set("last_dump", last_dump);
        r.set("dumps", n_dumps);
        r.add_all("snapshot", vtu.index().to_text());
        r.add_all("fluid_snapshot", fluid_snapshots.to_text());
      }

      /// What is due at time t (everything, with 'force').
      void write(const double t, const bool force, const DepositReport &report)
      {
        const double dt_fluid = fp.time_step;
        if (p.particle_csv_interval > 0. && (t >= next_dump - 0.5 * dt_fluid || force))
          {
            dump(t);
            next_dump += p.particle_csv_interval;
          }
        if (p.vtu_interval > 0. && (t >= next_vtu - 0.5 * dem.dt || force))
          {
            write_snapshot(vtu, dem, t);
            next_vtu += p.vtu_interval;
          }
        if (fp.vtu_interval > 0. && (t >= next_fluid_vtu - 0.5 * dt_fluid || force))
          {
            fluid_snapshots.add(t, fluid.write_snapshot(directory, fp.base_name,
                                                        fluid_snapshots.size()));
            next_fluid_vtu += fp.vtu_interval;
          }
        if (p.csv_interval > 0. && (t >= next_csv - 0.5 * dt_fluid || force))
          {
            const Vec3           v = global_mean_velocity(dem.handler_particles(), comm);
            const FluidIntegrals I = fluid.integrals();
            const std::string    meshes = mesh_load_columns();
            if (csv.is_open())
              {
                csv.row() << t << "," << v.x << "," << v.y << "," << v.z << ","
                          << I.kinetic_energy << "," << I.pressure_drop << ","
                          << report.particle_force[0] << "," << report.particle_force[1] << ","
                          << report.particle_force[2] << "," << report.clipped_nodes;
                csv.row() << meshes;
                csv.end_row();
              }
            next_csv += p.csv_interval;
          }
      }

      /// Collective, when a run stops (RunStopped): one more entry of every
      /// series the scene writes, at t; returns those files' names.
      std::vector<std::string> write_at_stop(const double t, const DepositReport &report)
      {
        write(t, true, report);
        std::vector<std::string> written;
        if (p.vtu_interval > 0.)
          written.push_back(directory + "/" + p.base_name + ".pvd");
        if (fp.vtu_interval > 0.)
          written.push_back(directory + "/" + fp.base_name + ".pvd");
        if (p.csv_interval > 0.)
          written.push_back(directory + "/" + p.base_name + ".csv");
        if (p.particle_csv_interval > 0.)
          written.push_back(particle_csv_path(directory, p.base_name, n_dumps - 1));
        return written;
      }

      /// The final state is always dumped.
      void finish(const double t)
      {
        if (p.particle_csv_interval > 0. && last_dump < t)
          dump(t);
      }

      void summarise(std::ostream &out) const
      {
        if (vtu.n_written() > 0)
          out << "output: " << vtu.n_written() << " particle snapshots in " << directory << "/"
              << p.base_name << ".pvd\n";
        if (n_dumps > 0)
          out << "output: " << n_dumps << " particle dumps in " << directory << "/"
              << p.base_name << "_state_*.csv\n";
      }

    private:
      /// With mesh walls, each mesh's torque about its motion origin and the
      /// power it puts in, from the particles and, when the fluid meets the
      /// walls, from the fluid (so a mill's draw is their sum).
      std::string csv_header() const
      {
        std::string header = "time,mean_vx,mean_vy,mean_vz,fluid_kinetic_energy,pressure_drop,"
                             "reaction_fx,reaction_fy,reaction_fz,clipped_nodes";
        const bool fluid_loads = !fluid.wall_loads().power.empty();
        for (const MeshWall &m : dem.walls.meshes())
          {
            header += mesh_load_header(m.name());
            if (fluid_loads)
              header += mesh_load_header(m.name(), "fluid");
          }
        return header;
      }

      /// Collective: the mesh columns of csv_header() at the last step.
      std::string mesh_load_columns() const
      {
        if (dem.walls.n_meshes() == 0)
          return {};
        std::ostringstream   row;
        row << std::setprecision(10);
        const GlobalState    g           = reduce_state(dem, comm);
        const FluidWallLoads fluid_loads = fluid.wall_loads();
        for (unsigned int m = 0; m < dem.walls.n_meshes(); ++m)
          {
            write_mesh_load(row, g.mesh_loads.torque[m], g.mesh_loads.power[m]);
            if (fluid_loads.power.empty())
              continue;
            const unsigned int w = dem.walls.n_planes() + m;
            write_mesh_load(row, fluid_loads.torque[w], fluid_loads.power[w]);
          }
        return row.str();
      }

      void dump(const double t)
      {
        write_particle_dump(dem, t, directory, p.base_name, n_dumps++);
        last_dump = t;
      }

      const SceneParameters &p;
      const FluidParameters &fp;
      const DemSystem       &dem;
      FluidBackend          &fluid;
      MPI_Comm               comm;
      const std::string      directory;
      ParticleOutput         vtu;
      PvdSeries              fluid_snapshots;
      CsvSeries              csv;
      double                 next_vtu, next_csv, next_fluid_vtu, next_dump, last_dump;
      unsigned int           n_dumps;
    };

    /// The fluid's response to one particle's force, measured over the
    /// correction's memory along gravity (self_induced_velocity.h).
    std::unique_ptr<SelfInducedVelocity> measure_self_induced(const SceneParameters &p,
                                                              const FluidParameters &fp,
                                                              const DemSystem       &dem,
                                                              const double           d_max,
                                                              const FluidBackend    &fluid,
                                                              std::string           &summary)
    {
      const CouplingParameters &c = p.coupling;
      const double memory   = c.self_induced_memory > 0. ? c.self_induced_memory : p.end_time;
      const auto   n_memory = static_cast<unsigned int>(
        std::max(1., std::ceil(memory / fp.time_step - 1e-9)));
      const Vec3 direction = norm(p.gravity) > 0. ? p.gravity : Vec3(0., 0., 1.);
      return fluid.self_induced_velocity(direction, n_memory, dem.box, d_max, summary);
    }

    /// The self-induced velocity correction (self_induced_velocity.h): the
    /// fluid's response to one particle's force, measured on this mesh, or,
    /// after a restart, the response and the force histories the checkpoint
    /// kept (so the correction goes on as if uninterrupted).
    std::unique_ptr<SelfInducedVelocity> self_induced_correction(const SceneParameters &p,
                                                                 const FluidParameters &fp,
                                                                 const DemSystem       &dem,
                                                                 const double           d_max,
                                                                 const FluidBackend    &fluid,
                                                                 const std::string &checkpoint,
                                                                 std::string       &summary)
    {
      const CouplingParameters &c = p.coupling;
      if (!c.self_induced_correction)
        return nullptr;
      const std::string entry = "cfd-dem/self-induced velocity correction";
      if (!c.two_way)
        fail(p, entry, "is 'true' in a one-way scene, where the fluid never feels the particles");
      if (fp.adaptive)
        fail(p, entry, "needs a fixed fluid mesh ('fluid refinement/adaptive = false'): the "
                       "measured response belongs to one mesh");
      if (!checkpoint.empty())
        {
          const std::string file = checkpoint + "/self_induced.bin";
          std::ifstream     in(file, std::ios::binary);
          std::string       bytes((std::istreambuf_iterator<char>(in)), {});
          try
            {
              auto correction = SelfInducedVelocity::deserialize(bytes, dem.box);
              summary = "  self-induced velocity correction: response and force histories "
                        "from the checkpoint (" +
                        std::to_string(correction->table().steps()) + " fluid steps)\n";
              return correction;
            }
          catch (const BinaryFormatError &e)
            {
              fail(p, "checkpoint/restart from", "names a checkpoint whose '" + file +
                                                   "' cannot be used: " + e.what());
            }
        }
      // The SPH fluid is measured as it is after the start's relaxation
      // (measure_self_induced, below).
      if (c.fluid_backend == FluidBackendKind::sph)
        return nullptr;
      return measure_self_induced(p, fp, dem, d_max, fluid, summary);
    }

    /// When the fluid meets the DEM's walls: its force on them and the power
    /// they give it at the last step, the deepest a fluid particle came into
    /// one against the contact's radius dx/2, and the fluid's momentum
    /// balance: its weight W and the particles' reactions R (the last
    /// deposit's) less the force on the walls F is the rate of change of its
    /// momentum, zero at rest or in a steady flow; out_of_balance is
    /// |W + R - F| / |W + R|. (Only the walls' force is counted: with wall
    /// particles beside them, theirs is missing.)
    void summarise_fluid_on_walls(std::ostream &out, const FluidBackend &fluid,
                                  const DepositReport &reactions, const double spacing)
    {
      const FluidWallLoads L = fluid.wall_loads();
      if (L.power.empty())
        return;
      Vec3   force;
      double power = 0.;
      for (std::size_t w = 0; w < L.power.size(); ++w)
        force += L.force[w], power += L.power[w];
      const Vec3   held = L.weight + reactions.particle_force;
      const double out_of_balance =
        norm(held) > 0. ? norm(held - force) / norm(held) : norm(held - force);
      out << "check: fluid_on_walls force=(" << force.x << ", " << force.y << ", " << force.z
          << ") weight_and_reactions=(" << held.x << ", " << held.y << ", " << held.z
          << ") out_of_balance=" << out_of_balance << " power=" << power
          << " max_overlap_over_dx=" << L.max_overlap / spacing << "\n";
    }

    /// The scene's header (rank 0): particles, fluid, coupling, steps, and
    /// where a restart started from.
    void print_header(std::ostream &out, const SceneParameters &p, const FluidParameters &fp,
                      const DemSystem &dem, const double d_max, const FluidBackend &fluid,
                      const unsigned int n_sub,
                      const std::string &self_induced_summary, const std::string &checkpoint,
                      const unsigned long long first_step)
    {
      const CouplingParameters &c = p.coupling;
      out << "Sluice CFD-DEM - scene " << p.file_name << "\n"
          << "  " << (dem.clumps ? "clumps" : "particles") << ": " << dem.n_inserted
          << ", MPI ranks: " << dem.n_ranks << ", ";
      fluid.describe(out);
      out << "\n"
          << "  formulation: " << name_of(c.formulation)
          << ", coupling: " << (c.two_way ? "two-way" : "one-way") << ", drag: " << name_of(c.drag)
          << ", " << describe_exchange(p, fluid, d_max, dem.clumps != nullptr) << "\n"
          << std::setprecision(4) << "  fluid step = " << fp.time_step << " s, DEM step = " << dem.dt << " s (" << n_sub
          << " per fluid step), contact time t_c = " << dem.t_contact << " s\n"
          << self_induced_summary;
      if (!checkpoint.empty())
        out << "  restarted from " << checkpoint << " at t = " << first_step * fp.time_step
            << " s (fluid step " << first_step << ")\n";
      out << std::flush;
    }

  } // namespace

  int run_cfd_dem_scene(const SceneParameters &scene, MPI_Comm comm)
  {
    const SceneParameters p = with_fluid_backend(scene);
    const auto wall_start = std::chrono::steady_clock::now();
    const auto seconds    = [&]() {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    };
    const CouplingParameters &c = p.coupling;

    // ---- Set-up: every input check (and a restart's reading) before any output ----
    refuse_fluid_checkpoint_entries(p);
    check_weight_ramp(p);
    check_averaging_start(p);
    check_semi_implicit_drag(p);
    const FluidParameters fp       = coupled_fluid_parameters(p);
    const double          dt_fluid = fp.time_step;
    const CouplingFields  fields(c.self_induced_correction);
    DemSystem             dem(p, comm, fields.registry);
    ParticleStorage      &P     = dem.handler_particles(); // the bodies in a clump scene
    const unsigned int    n_sub = std::max(1., std::ceil(dt_fluid / dem.dt - 1e-9));
    dem.dt                      = dt_fluid / n_sub;
    const FluidShapes     shapes(dem);
    // What the kernel must cover: the largest sphere's or body's extent.
    const double d_max = shapes.largest_extent();
    check_newton_tolerance(p, fp, dem, shapes, comm);
    const bool  restart = !p.restart_from.empty();
    std::string checkpoint;
    if (restart)
      checkpoint = find_checkpoint(p.restart_from, p.output_directory, p.base_name, p.file_name);
    const SceneRecords records(
      restart ? load_dem_checkpoint(dem, checkpoint, coupled_signature(p, fp)) :
                std::vector<std::string>());
    const std::unique_ptr<FluidBackend> backend = make_fluid_backend(p, fp, d_max, comm);
    FluidBackend                       &fluid   = *backend;
    if (restart)
      fluid.load_checkpoint(checkpoint + "/fluid");
    std::string self_induced_summary;
    Exchange    exchange(p, fp, fields, dem, shapes, fluid,
                      self_induced_correction(p, fp, dem, d_max, fluid, checkpoint,
                                              self_induced_summary),
                      comm);
    const std::unique_ptr<CouplingProbe> probe = make_coupling_probe(c.validation);
    ProbeView view{p, fp, dem, shapes, fluid, exchange.kept_samples(), comm};
    const auto first_step = static_cast<unsigned long long>(records.number("fluid_step", 0.));
    NewtonReport newton_total;
    if (restart)
      {
        exchange.restore(records);
        if (probe)
          probe->set_state(records.numbers("probe"));
        newton_total.iterations        = records.number("newton_iterations", 0.);
        newton_total.linear_iterations = records.number("gmres_iterations", 0.);
        newton_total.picard_starts     = records.number("picard_starts", 0.);
      }
    else if (probe)
      // Before any output is prepared: a probe may place the particles, or
      // refuse the scene.
      probe->prepare(view);

    CoupledOutput output(p, fp, dem, fluid, restart, first_step * dt_fluid, records,
                         probe && probe->writes_files(), comm);
    view.output_directory = output.output_directory();
    if (dem.rank == 0)
      print_header(std::cout, p, fp, dem, d_max, fluid, n_sub, self_induced_summary, checkpoint,
                   first_step);

    // A stop (every rank stops together) adds the state that failed to every
    // series, for a look in ParaView, and names the files in its message.
    const auto write_state_at_stop = [&](RunStopped &stop) {
      stop.written_at_stop =
        stop_note(dem.time(), output.write_at_stop(dem.time(), exchange.report));
    };

    if (restart)
      // The particles on the fluid mesh again, for the samples the probes
      // take (nothing else changes: the impulses owed are zero here).
      {
        exchange.give_particles(false);
        if (probe)
          exchange.keep_samples();
      }
    else
      {
        // ---- The start: the particles' porosity, and the fluid at rest in it
        // with its hydrostatic pressure (a steady solve without reaction), so
        // that buoyancy acts from the first step ----
        exchange.give_particles(false);
        // A particle outside the fluid mesh would fall freely, unseen by the fluid.
        if (exchange.n_outside > 0 &&
            !(c.fluid_backend == FluidBackendKind::sph && c.particles_above_fluid))
          throw InputError(
            "error in '" + p.file_name + "': " + std::to_string(exchange.n_outside) +
            (c.fluid_backend == FluidBackendKind::fe ?
               " particle(s) lie outside the fluid mesh at the start ('insertion' against "
               "'fluid mesh'); insert them inside it, or enlarge the mesh" :
               " particle(s) have no SPH fluid particle within reach at the start "
               "('insertion' against 'sph/fluid lower corner' and 'upper corner'); insert "
               "them inside the fluid, or enlarge it"));
        exchange.deposit(true);
        if (c.two_way)
          fluid.clear_momentum_source();
        if (c.two_way && c.fluid_backend == FluidBackendKind::sph)
          exchange.check_exchange_waves(fluid.sample(), true);
        const NewtonReport start = fluid.solve_steady();
        newton_total.picard_starts += start.picard_starts;
        if (c.fluid_backend == FluidBackendKind::sph && dem.rank == 0)
          std::cout << std::setprecision(4) << "  SPH start: relaxed "
                    << (c.sph_start_at_rest ? "to rest " : "") << "in " << start.iterations
                    << " SPH steps (largest speed left " << start.residual << " m/s"
                    << (c.sph_start_at_rest ? "" : "; rest not required") << ")\n";
        if (c.self_induced_correction && c.fluid_backend == FluidBackendKind::sph)
          {
            std::string text;
            exchange.set_self_induced(measure_self_induced(p, fp, dem, d_max, fluid, text));
            if (dem.rank == 0)
              std::cout << text << std::flush;
          }
        try
          {
            exchange.sample(0.);
          }
        catch (RunStopped &stop)
          {
            write_state_at_stop(stop);
            throw;
          }
        if (probe)
          probe->start(view);
        output.write(0., false, exchange.report);
      }

    // What a checkpoint adds to the DEM's: the fluid's files, the self-induced
    // histories, and the records of the exchange, the output and the probe.
    const CheckpointAddition addition{
      coupled_signature(p, fp), [&](const std::string &directory) {
        fluid.save_checkpoint(directory + "/fluid");
        exchange.save_self_induced(directory + "/self_induced.bin");
      }};
    const auto scene_records = [&](const unsigned long long step) {
      SceneRecords r;
      r.set("fluid_step", double(step));
      r.set("newton_iterations", newton_total.iterations);
      r.set("gmres_iterations", newton_total.linear_iterations);
      r.set("picard_starts", newton_total.picard_starts);
      exchange.save(r);
      output.save(r);
      if (probe)
        r.set_numbers("probe", probe->state());
      return r.lines();
    };

    // ---- The loop ----
    const unsigned long long n_steps =
      static_cast<unsigned long long>(std::ceil(p.end_time / dt_fluid - 1e-9));
    ProgressLine          progress(p.progress && dem.rank == 0, p.end_time);
    double                time = first_step * dt_fluid;
    CheckpointSchedule    checkpoints(p, time);
    const FluidForcesKick kick{p.gravity, fields};
    // Where a fluid step's time goes (issue 16, target 4): printed as 'cost:'.
    enum Stage : unsigned int { dem_steps, gather, deposit, solve, sampling, rest };
    StageClock clock({"dem", "gather", "deposit", "solve", "sample", "other"});
    try
      {
        for (unsigned long long step = first_step + 1; step <= n_steps; ++step)
          {
            clock.start();
            // 1. DEM sub-steps with the frozen fluid forces.
            if (c.fixed_particles)
              kick.hold(P, dt_fluid);
            else
              for (unsigned int s = 0; s < n_sub; ++s)
                if (dem.clumps)
                  dem.advance_clumps(kick);
                else
                  dem.advance(kick);
            time = step * dt_fluid;
            clock.lap(dem_steps);

            // 2.-4. Porosity and reaction to the fluid, fluid step, fluid to the particles.
            exchange.give_particles(true);
            clock.lap(gather);
            exchange.deposit(false);
            clock.lap(deposit);
            const NewtonReport r = fluid.advance(dt_fluid);
            newton_total.iterations += r.iterations;
            newton_total.linear_iterations += r.linear_iterations;
            newton_total.picard_starts += r.picard_starts;
            clock.lap(solve);
            exchange.sample(time);
            clock.lap(sampling);

            if (probe)
              probe->observe(time, view);
            output.write(time, false, exchange.report);
            if (checkpoints.due(step, time, dt_fluid))
              save_dem_checkpoint(dem,
                                  checkpoint_path(output.output_directory(), p.base_name, step),
                                  scene_records(step), p.checkpoints_kept, addition);
            if (progress.due())
              progress.update(time, step, dem.n_inserted - dem.n_lost);
            clock.lap(rest);
          }
      }
    catch (RunStopped &stop)
      {
        progress.finish();
        write_state_at_stop(stop);
        throw;
      }
    progress.finish();
    output.finish(time);

    // ---- Summary and validation ----
    std::ostringstream summary;
    summary << std::setprecision(p.summary_precision);
    const Vec3           v_end = global_mean_velocity(P, comm);
    const FluidIntegrals I     = fluid.integrals();
    summary << "final: time=" << time << " fluid_steps=" << n_steps << " dem_steps_per_fluid_step="
            << n_sub << " particles=" << dem.n_inserted - dem.n_lost << " outside_fluid="
            << exchange.n_outside << " mean_velocity=(" << v_end.x << ", " << v_end.y << ", "
            << v_end.z << ") fluid_kinetic_energy=" << I.kinetic_energy << "\n";
    exchange.summarise(summary, newton_total);
    fluid.summarise_layout(summary);
    summary << std::setprecision(p.summary_precision);

    ProbeResult result;
    if (probe)
      result = probe->finish(view);
    for (const std::string &check : result.checks)
      summary << check << "\n";
    summarise_fluid_on_walls(summary, fluid, exchange.report, p.sph.spacing);
    // Coupling scheme 3: the fluid's momentum source integrates to minus the
    // particles' exchanged forces, to round-off.
    bool extra_failed = false;
    if (c.two_way && exchange.max_imbalance > 1e-10)
      {
        summary << "check: momentum exchange imbalance " << exchange.max_imbalance
                << " > 1e-10 FAILED\n";
        extra_failed = true;
      }
    const double wall_s = seconds();
    summary << std::setprecision(4) << "timing: wall_s=" << wall_s << "\n"
            << "cost: ms per fluid step: " << clock.line(n_steps - first_step, 1e3) << "\n"
            << std::setprecision(p.summary_precision);
    output.summarise(summary);
    if (!result.name.empty())
      write_result_line(summary, result.name, result.value, result.reference, result.error,
                        wall_s);
    if (dem.rank == 0)
      std::cout << summary.str() << std::flush;
    if (extra_failed || (c.tolerance > 0. && !result.name.empty() && result.error > c.tolerance))
      {
        if (dem.rank == 0)
          std::cerr << "sluice: validation error " << result.error << " exceeds the tolerance "
                    << c.tolerance << " set in 'cfd-dem validation/tolerance'\n";
        return 3;
      }
    return 0;
  }
} // namespace sluice
