#pragma once
// What a scene file says about the fluid: the 'fluid', 'fluid mesh', 'fluid
// boundaries', 'fluid solver', 'fluid refinement' and 'fluid output' subsections.
// Plain data; filled and checked in fluid_parameters.cc. All quantities are SI.

#include <sluice/core/vector3.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace sluice
{
  /// Which of the consistent averaged momentum equations is solved
  /// (Zhou et al. 2010, Table 1).
  enum class VansFormulation
  {
    model_a, // set II: -eps grad p + eps div tau in the fluid momentum equation
    model_b  // set III: -grad p + div tau; the exchanged force is drag / eps
  };

  enum class TimeIntegration
  {
    steady, // Newton on the steady equations
    bdf1,   // backward Euler
    bdf2    // second-order backward differences, variable step
  };

  enum class FluidMeshType
  {
    box,                   // GridGenerator::subdivided_hyper_rectangle, colorized ids 0..5
    cylinder,              // GridGenerator::cylinder along x: ids 0 hull, 1 x = -L/2, 2 x = +L/2
    channel_with_cylinder, // GridGenerator::channel_with_cylinder: 0 inlet, 1 outlet, 2 cylinder, 3 walls
    gmsh                   // a .msh file; physical tags become boundary ids
  };

  enum class BoundaryType
  {
    no_slip,       // u = 0
    slip,          // u . n = 0, no tangential stress
    velocity,      // u = a function of x, y, z, t
    traction_free, // (-p I + tau) n = 0: an outlet, p = 0 there on average
    periodic       // paired with the next id in the list, along a direction
  };

  /// One named boundary: its type and the mesh boundary ids it covers.
  struct BoundaryCondition
  {
    std::string                name;
    BoundaryType               type = BoundaryType::no_slip;
    std::vector<unsigned int>  ids;
    std::string                velocity;      // three ';'-separated expressions (velocity)
    unsigned int               direction = 0; // periodic: 0 = x, 1 = y, 2 = z
  };

  enum class PorousDrag
  {
    none,
    ergun // beta = 150 (1-eps)^2 mu / (eps d^2) + 1.75 (1-eps) rho |u - u_s| / d
  };

  enum class LinearPreconditioner
  {
    ilu, // Trilinos Ifpack ILU(k), one block per rank
    amg, // Trilinos ML algebraic multigrid
    lu   // Trilinos Amesos KLU: a complete factorisation, reused like the others
  };

  enum class RefinementIndicator
  {
    velocity, // Kelly estimator on the velocity
    porosity, // Kelly estimator on the porosity field
    both      // the sum of the two, each normalised by its largest cell value
  };

  enum class FluidValidationCase
  {
    none,
    poiseuille,            // pressure drop of plane Poiseuille flow, Delta p = 8 mu U L / H^2
    packed_bed_ergun,      // pressure drop per length of a packed bed against Ergun
    manufactured_solution, // built-in exact solution: observed L2 convergence rates
    reference_value        // pressure drop or flow rate against a number given in the .prm
  };

  struct FluidParameters
  {
    // subsection fluid
    double          density   = 1000.;
    double          viscosity = 1e-3;
    VansFormulation formulation = VansFormulation::model_a;
    unsigned int    velocity_degree = 1;
    unsigned int    pressure_degree = 1;
    std::string     porosity        = "1";
    bool            porosity_as_field = false;
    std::string     solid_velocity  = "0; 0; 0";
    std::string     momentum_source = "0; 0; 0";
    bool            momentum_source_as_field = false;
    // The particles' drag coefficient per volume as a field, whose drag on the
    // fluid's own velocity the assembly takes implicitly (set by a coupled
    // scene with 'cfd-dem/semi-implicit drag'; no entry of its own).
    bool            exchange_drag_as_field = false;
    std::string     mass_source     = "0";
    std::string     initial_velocity = "0; 0; 0";
    std::string     constants;
    PorousDrag      drag = PorousDrag::none;
    double          particle_diameter = 1e-3;
    Vec3            driving_pressure_gradient;
    bool            use_gravity = false;

    // subsection fluid mesh
    FluidMeshType               mesh_type = FluidMeshType::box;
    Vec3                        lower_corner{0., 0., 0.};
    Vec3                        upper_corner{1., 1., 1.};
    std::array<unsigned int, 3> subdivisions{{1, 1, 1}};
    double                      cylinder_radius      = 0.5;
    double                      cylinder_half_length = 1.;
    std::string                 mesh_file;
    unsigned int                initial_refinement = 0;

    // subsection fluid boundaries
    std::vector<BoundaryCondition> boundaries;
    Vec3                           pressure_reference_point;

    // subsection fluid time
    TimeIntegration time_integration = TimeIntegration::steady;
    double          time_step        = 1e-3;
    double          end_time         = 1.;
    std::string     restart_from; // a checkpoint base name, relative to the working directory

    // subsection fluid solver
    double               newton_tolerance       = 1e-10;
    double               newton_relative_tolerance = 1e-9;
    unsigned int         newton_max_iterations  = 20;
    LinearPreconditioner preconditioner         = LinearPreconditioner::ilu;
    unsigned int         ilu_fill               = 0;
    double               linear_tolerance       = 1e-4;
    unsigned int         linear_max_iterations  = 1000;
    double               grad_div               = 0.;
    bool                 stabilization          = true;

    // subsection fluid refinement
    bool                adaptive            = false;
    RefinementIndicator indicator           = RefinementIndicator::velocity;
    double              refine_fraction     = 0.3;
    double              coarsen_fraction    = 0.05;
    unsigned int        min_level           = 0;
    unsigned int        max_level           = 10;
    unsigned int        refinement_interval = 10;
    unsigned int        steady_cycles       = 1;

    // subsection fluid output
    std::string              output_directory = "output";
    std::string              base_name        = "fluid";
    double                   vtu_interval     = 0.;
    double                   csv_interval     = 0.;
    std::array<std::string, 2> pressure_drop_between;
    std::vector<std::string> flow_rate_through;
    bool                     progress         = true;
    unsigned int             checkpoint_interval = 0; // time steps; 0: none

    // subsection fluid validation
    FluidValidationCase      validation = FluidValidationCase::none;
    double                   tolerance  = 0.;
    double                   poiseuille_maximum_velocity = 0.;
    std::vector<double>      superficial_velocities;
    unsigned int             mms_refinements = 3;
    bool                     mms_polynomial  = false; // quadratic u, linear p
    bool                     mms_refine_time_only = false; // fixed mesh, dt halves
    bool                     mms_uneven_steps = false; // alternate 1.25 dt and 0.75 dt
    double                   reference_value = 0.;
    bool                     reference_is_flow_rate = false; // else the pressure drop

    /// The pure-fluid case: porosity identically 1 and no porous drag, so the
    /// assembly skips every porosity term.
    bool pure_fluid() const;
    /// The 'constants' entry as a map (checked when read).
    std::map<std::string, double> constant_map() const;
    /// Index into 'boundaries' of the condition with this name, or -1.
    int boundary_index(const std::string &name) const;
  };

  /// Declares the fluid subsections in a ParameterHandler.
  void declare_fluid_parameters(dealii::ParameterHandler &prm);

  /// Reads and checks them; throws InputError naming file, entry and range.
  void read_fluid_parameters(dealii::ParameterHandler &prm, const std::string &file_name,
                             FluidParameters &p);
} // namespace sluice
