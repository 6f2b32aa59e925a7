// A DEM scene in an imported flow field (see the header).

#include <sluice/core/names.h>
#include <sluice/coupling/coupling_fields.h>
#include <sluice/coupling/fluid_kick.h>
#include <sluice/coupling/fluid_shapes.h>
#include <sluice/coupling/imported_field_check.h>
#include <sluice/coupling/imported_field_scene.h>
#include <sluice/coupling/imported_field_series.h>
#include <sluice/coupling/particle_fluid_forces.h>
#include <sluice/dem/dem_simulation.h>
#include <sluice/dem/dem_system.h>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// The forces the imported field gives one particle, as a coupled scene
    /// freezes them (particle_fluid_forces.h, formulation set II: drag and
    /// -V_p grad p), plus the buoyancy when the pressure does not carry it.
    CouplingParameters forces_of(const ImportedFieldParameters &f)
    {
      CouplingParameters c;
      c.formulation             = CouplingFormulation::set_ii;
      c.drag                    = f.drag;
      c.pressure_gradient_force = f.pressure_gradient_force;
      // The closure sees the field's porosity (1 without a porosity array).
      c.two_way            = true;
      c.max_solid_fraction = 1.;
      return c;
    }

    /// The field's files, with a failure put in terms of the scene's entry.
    ImportedFieldSeries open_series(const SceneParameters &p)
    {
      try
        {
          return ImportedFieldSeries(p.imported_field, p.file_name);
        }
      catch (const InputError &e)
        {
          std::string what = e.what();
          if (what.rfind("error: ", 0) == 0)
            what.erase(0, 7);
          if (what.rfind("error in ", 0) == 0)
            throw;
          throw InputError("error in '" + p.file_name + "': entry 'imported field/file': " + what);
        }
    }

    class ImportedFieldForcing : public DemSceneExtension
    {
    public:
      ImportedFieldForcing(const SceneParameters &p, MPI_Comm comm)
        : p(p), f(p.imported_field), comm(comm), coupling(forces_of(f)), coupling_fields(false)
        , series(open_series(p)), check(f, p.gravity), start(std::chrono::steady_clock::now())
      {
        cell_hint = coupling_fields.registry.declare("field_cell", 1, {true, false, true});
        properties.density   = f.density;
        properties.viscosity = f.viscosity;
        properties.gravity   = p.gravity;
        explicit_buoyancy    = !(f.pressure_gradient_force && f.hydrostatic_in_pressure);
      }

      const ParticleFieldRegistry &fields() const override { return coupling_fields.registry; }

      void attach(DemSystem &dem) override
      {
        shapes = std::make_unique<FluidShapes>(dem);
        if (check.active() && dem.step == 0)
          check.start(dem.handler_particles(), comm);
        // The forces the first step starts with (a restart's are the same);
        // only a step's refresh counts towards the particle-steps outside.
        sample(dem.handler_particles(), dem.time(), dem.dt);
      }

      void describe(std::ostream &out) const override
      {
        out << "  imported field: " << f.file << " (" << series.n_snapshots()
            << (series.n_snapshots() == 1 ? " snapshot" : " snapshots");
        if (series.n_snapshots() > 1)
          out << " from t = " << series.first_time() << " to " << series.last_time() << " s"
              << (f.period > 0. ? ", periodic" : "");
        out << "), " << series.n_cells() << " cells, " << series.n_points()
            << " points; drag " << name_of(f.drag)
            << (f.pressure_gradient_force ? ", pressure gradient force" : "")
            << (explicit_buoyancy ? ", buoyancy" : "") << ", one way\n";
      }

      void advance(DemSystem &dem) override
      {
        if (dem.clumps)
          dem.advance_clumps(Kick{*this, dem});
        else
          dem.advance(Kick{*this, dem});
      }

      /// Collective: the count over all ranks (rank 0 takes it back).
      std::vector<double> state() const override
      {
        unsigned long long total = outside_steps;
        MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
        std::vector<double>       s = {static_cast<double>(total)};
        const std::vector<double> c = check.state(comm);
        s.insert(s.end(), c.begin(), c.end());
        return s;
      }
      void set_state(const std::vector<double> &s) override
      {
        if (s.empty())
          return;
        int rank;
        MPI_Comm_rank(comm, &rank);
        outside_steps = rank == 0 ? static_cast<unsigned long long>(s[0]) : 0;
        check.set_state(std::vector<double>(s.begin() + 1, s.end()));
      }

      std::string summary(DemSystem &dem) const override
      {
        unsigned long long counts[2] = {outside_now, outside_steps};
        MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
        std::ostringstream out;
        out << std::setprecision(p.summary_precision) << "field: outside=" << counts[0]
            << " outside_particle_steps=" << counts[1] << "\n";
        if (check.active())
          out << check.finish(dem.handler_particles(), *shapes, dem.time(),
                              std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                                            start)
                                .count(),
                              comm, error);
        return out.str();
      }

      int exit_code() const override
      {
        const bool over = check.active() && p.validation_tolerance > 0. &&
                          error > p.validation_tolerance;
        if (over)
          {
            int rank;
            MPI_Comm_rank(comm, &rank);
            if (rank == 0)
              std::cerr << "sluice: validation error " << error << " exceeds the tolerance "
                        << p.validation_tolerance << " set in 'validation/tolerance'\n";
          }
        return over ? 3 : 0;
      }

    private:
      /// The step's kick: the coupled scene's (contacts, gravity, frozen fluid
      /// forces, exact drag), refreshed after the drift at the new positions.
      struct Kick
      {
        ImportedFieldForcing &owner;
        DemSystem            &dem;
        void kick(ParticleStorage &P, const double h) const
        {
          FluidForcesKick{owner.p.gravity, owner.coupling_fields}.kick(P, h);
        }
        void refresh(ParticleStorage &P, const double t) const
        {
          owner.sample(P, t, dem.dt);
          owner.outside_steps += owner.outside_now;
        }
      };

      void sample(ParticleStorage &P, const double t, const double dt)
      {
        series.set_time(t);
        outside_now = 0;
        for (unsigned int i = 0; i < P.n_local; ++i)
          {
            double                   *e    = P.extra_of(i);
            long                      hint = static_cast<long>(e[cell_hint]);
            const ParticleFluidSample s    = series.sample(P.position[i], hint);
            e[cell_hint]                   = static_cast<double>(hint);
            const FluidShape shape = shapes->shape(i, s.velocity - P.velocity[i]);
            particle_fluid_forces(coupling, properties, s, shape, P.velocity[i],
                                  P.angular_velocity[i], dt, true, coupling_fields, e);
            if (!s.found)
              {
                ++outside_now;
                continue;
              }
            if (explicit_buoyancy)
              for (unsigned int d = 0; d < 3; ++d)
                e[coupling_fields.other_force + d] -= f.density * shape.volume * p.gravity[d];
            if (check.active())
              check.observe(P.position[i], s);
          }
      }

      const SceneParameters         &p;
      const ImportedFieldParameters &f;
      MPI_Comm                       comm;
      const CouplingParameters       coupling;
      CouplingFields                 coupling_fields;
      ImportedFieldSeries            series;
      ImportedFieldCheck             check;
      std::unique_ptr<FluidShapes>   shapes; // the particles' volumes and drag shapes
      FluidProperties                properties;
      unsigned int                   cell_hint = 0;
      bool                           explicit_buoyancy = false;
      unsigned long long             outside_now = 0, outside_steps = 0;
      mutable double                 error = 0.;
      std::chrono::steady_clock::time_point start;
    };
  } // namespace

  int run_imported_field_scene(const SceneParameters &p, MPI_Comm comm)
  {
    const auto refuse = [&](const std::string &entry, const std::string &why) {
      throw InputError("error in '" + p.file_name + "': entry '" + entry + "' " + why);
    };
    if (p.validation != ValidationCase::none)
      refuse("validation/case", "is set in a scene with an imported field; its checks are "
                                "'imported field/check'");
    if (p.wear.energy)
      refuse("wear and breakage/energy balance",
             "is true in a scene with an imported field, whose work on the particles the "
             "energy bookkeeping does not book");
    ImportedFieldForcing forcing(p, comm);
    return run_dem_scene(p, comm, &forcing);
  }
} // namespace sluice
