// The fluid a coupled scene asks for (see the header).

#include <sluice/core/names.h>
#include <sluice/coupling/make_fluid_backend.h>
#include <sluice/coupling/sph_backend.h>
#include <sluice/coupling/vans_backend.h>
#include <sluice/sph/sph_fluid_trim.h>
#include <sluice/sph/sph_setup.h>

#include <iomanip>
#include <sstream>

namespace sluice
{
  namespace
  {
    [[noreturn]] void fail(const SceneParameters &p, const std::string &entry,
                           const std::string &what)
    {
      throw InputError("error in '" + p.file_name + "': entry '" + entry + "' " + what);
    }

    double coupling_length(const SceneParameters &p)
    {
      return p.coupling.sph_coupling_length > 0. ? p.coupling.sph_coupling_length :
                                                    p.sph.smoothing_factor * p.sph.spacing;
    }
  } // namespace

  SceneParameters with_fluid_backend(const SceneParameters &p)
  {
    const CouplingParameters &c = p.coupling;
    if (c.fluid_backend != FluidBackendKind::sph && c.particles_above_fluid)
      fail(p, "cfd-dem/particles above sph fluid",
           "is 'true', but the fluid is the finite-element one, whose mesh must hold every "
           "particle: leave it 'false'");
    if (c.fluid_backend != FluidBackendKind::sph && !c.sph_start_at_rest)
      fail(p, "cfd-dem/sph start at rest",
           "is 'false', but the fluid is the finite-element one, which starts from a steady "
           "solve: leave it 'true'");
    if (c.fluid_backend != FluidBackendKind::sph)
      return p;
    if (c.two_way && !c.pressure_gradient_force && c.formulation != CouplingFormulation::set_ii)
      fail(p, "cfd-dem/pressure gradient force",
           "is 'false', but in two-way coupling the particles' reactions to it hold the SPH "
           "fluid at rest among them (without them rho_hat g is no pressure gradient where "
           "eps varies): leave it 'true', use 'formulation = set_ii' (whose fluid has -eps "
           "grad p) or 'coupling = one-way'");
    if (c.validation == CouplingValidationCase::packed_bed ||
        c.validation == CouplingValidationCase::fluidized_bed)
      fail(p, "cfd-dem validation/case",
           "is '" + name_of(c.validation) + "', which measures the pressure drop between the "
           "fluid mesh's boundaries; the SPH fluid has none: use 'fluid backend = fe'");
    if (p.sph.time_step > 0.)
      fail(p, "sph/time step",
           "is set, but in a coupled scene the SPH steps fill 'fluid time/time step', each "
           "at most 'sph/time step fraction' of the stable step: leave it at 0");
    SceneParameters q = p;
    q.fluid.density   = p.sph.density;
    q.fluid.viscosity = p.sph.viscosity;
    return q;
  }

  std::unique_ptr<FluidBackend> make_fluid_backend(const SceneParameters &p,
                                                   const FluidParameters &fp,
                                                   const double d_max, MPI_Comm comm)
  {
    const CouplingParameters &c = p.coupling;
    if (c.fluid_backend == FluidBackendKind::fe)
      return std::make_unique<VansBackend>(fp, c, p.gravity, d_max, p.file_name, comm);
    SphBackendSettings s;
    s.coupling_length    = coupling_length(p);
    s.max_solid_fraction = c.max_solid_fraction;
    s.step_fraction      = p.sph.time_step_fraction;
    s.fluid_step         = fp.time_step;
    s.start_at_rest      = c.sph_start_at_rest;
    s.weight_by_immersion = c.particles_above_fluid;
    SphSetup setup       = make_sph_setup(p);
    // Set II: the fluid's -eps grad p + eps div tau (sph_forces.h).
    setup.settings.forces.stress_times_fluid_fraction =
      c.formulation == CouplingFormulation::set_ii;
    if (!p.sph.solid_walls)
      return std::make_unique<SphBackend>(std::move(setup), s, nullptr, SolidWallLaw(), comm);
    // The DEM's walls, a copy of the fluid's own (sph_backend.h).
    auto walls = std::make_unique<WallSet>(p.walls, p.meshes, setup.box, p.file_name);
    if (walls->n_walls() == 0)
      fail(p, "sph/solid walls",
           "is 'true', but the scene has no walls: set 'walls/box', 'walls/planes' or a mesh "
           "('walls/number of meshes')");
    const SolidWallLaw law = solid_wall_law(p, setup);
    remove_fluid_beyond_walls(setup, *walls, law.radius);
    return std::make_unique<SphBackend>(std::move(setup), s, std::move(walls), law, comm);
  }

  std::string describe_exchange(const SceneParameters &p, const FluidBackend &fluid,
                                const double d_max, const bool clumps)
  {
    const CouplingParameters &c = p.coupling;
    std::ostringstream        out;
    out << std::setprecision(4);
    const char *unit = clumps ? " body diameters)" : " d)";
    if (const auto *vans = dynamic_cast<const VansBackend *>(&fluid))
      out << "projection: " << name_of(c.projection) << ", kernel radius = "
          << vans->kernel_radius() << " m (" << vans->kernel_radius() / d_max << unit;
    else
      out << "SPH coupling length h_c = " << coupling_length(p) << " m ("
          << coupling_length(p) / d_max << unit;
    return out.str();
  }
} // namespace sluice
