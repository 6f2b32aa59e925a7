// The fluid's .prm entries: declared with default, unit and range, read, checked.
// Nothing is written to disk here, so a bad file leaves no trace.

#include <sluice/core/parameter_declaration.h>
#include <sluice/core/scene_parameters.h>
#include <sluice/core/fluid_parameters.h>
#include <sluice/core/names.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/lac/vector.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <sstream>

namespace sluice
{
  using dealii::ParameterHandler;
  namespace Patterns = dealii::Patterns;

  namespace
  {
    Patterns::List vector_pattern()
    {
      return Patterns::List(Patterns::Double(), 3, 3, ",");
    }

    [[noreturn]] void fail(const std::string &file, const std::string &entry,
                           const std::string &what)
    {
      throw InputError("error in '" + file + "': entry '" + entry + "' " + what);
    }

    /// Checks that an expression with n components parses with x, y, z, t and the
    /// scene's constants, so that a typo stops the run before anything is written.
    void check_expression(const std::string &file, const std::string &entry,
                          const std::string &expression, const unsigned int n_components,
                          const std::string &constants)
    {
      const auto parts = dealii::Utilities::split_string_list(expression, ';');
      if (parts.size() != n_components)
        fail(file, entry,
             "= '" + expression + "' has " + std::to_string(parts.size()) +
               " component(s); it needs " + std::to_string(n_components) +
               (n_components > 1 ? ", separated by ';'" : ""));
      std::map<std::string, double> c;
      for (const auto &pair : dealii::Utilities::split_string_list(constants, ','))
        {
          if (pair.empty())
            continue;
          const auto kv = dealii::Utilities::split_string_list(pair, '=');
          if (kv.size() != 2)
            fail(file, "fluid/constants", "has '" + pair + "'; expected 'name = number'");
          char *end = nullptr;
          const double value = std::strtod(kv[1].c_str(), &end);
          if (end == kv[1].c_str() || *end != '\0')
            fail(file, "fluid/constants", "has '" + pair + "', whose value is not a number");
          c[kv[0]] = value;
        }
      try
        {
          dealii::FunctionParser<3> f(n_components);
          f.initialize("x,y,z,t", expression, c, true);
          dealii::Vector<double> values(n_components);
          f.vector_value(dealii::Point<3>(0.1, 0.2, 0.3), values);
        }
      catch (const dealii::ExceptionBase &e)
        {
          std::ostringstream info;
          e.print_info(info);
          fail(file, entry, "= '" + expression + "' cannot be evaluated:\n" + info.str());
        }
    }
  } // namespace

  bool FluidParameters::pure_fluid() const
  {
    return dealii::Utilities::trim(porosity) == "1" && drag == PorousDrag::none &&
           !porosity_as_field;
  }

  std::map<std::string, double> FluidParameters::constant_map() const
  {
    std::map<std::string, double> c;
    for (const auto &pair : dealii::Utilities::split_string_list(constants, ','))
      {
        const auto kv = dealii::Utilities::split_string_list(pair, '=');
        if (kv.size() == 2)
          c[kv[0]] = std::strtod(kv[1].c_str(), nullptr);
      }
    return c;
  }

  int FluidParameters::boundary_index(const std::string &name) const
  {
    for (unsigned int b = 0; b < boundaries.size(); ++b)
      if (boundaries[b].name == name)
        return b;
    return -1;
  }

  void declare_fluid_parameters(ParameterHandler &prm)
  {
    using Patterns::Bool;
    using Patterns::Double;
    using Patterns::Integer;
    using Patterns::Selection;
    const double inf = unbounded();

    prm.enter_subsection("fluid");
    {
      declare(prm, "density", "1000", Double(1e-12, inf), "[kg/m^3] Fluid density, > 0.",
              "a number > 0");
      declare(prm, "viscosity", "1e-3", Double(1e-12, inf),
              "[Pa s] Dynamic viscosity, > 0.", "a number > 0");
      declare(prm, "formulation", "model A", Selection(names<VansFormulation>().selection()),
              "Averaged momentum equation (Zhou et al. 2010, Table 1): 'model A' (set II, "
              "-eps grad p + eps div tau) or 'model B' (set III, -grad p + div tau, drag "
              "divided by eps).");
      declare(prm, "velocity degree", "1", Integer(1, 3),
              "[-] Polynomial degree of the velocity (FE_Q).");
      declare(prm, "pressure degree", "1", Integer(1, 3),
              "[-] Polynomial degree of the pressure (FE_Q), at most the velocity degree.");
      declare(prm, "porosity", "1", Patterns::Anything(),
              "[-] Fluid volume fraction eps(x, y, z, t), an expression with the constants "
              "below. '1' is a pure fluid: the porosity terms are not assembled at all.",
              "an expression with values in (0, 1]");
      declare(prm, "porosity as field", "false", Bool(),
              "Interpolate the porosity into a finite-element field (as the particle "
              "coupling does) instead of evaluating the expression at quadrature points.");
      declare(prm, "solid velocity", "0; 0; 0", Patterns::Anything(),
              "[m/s] Velocity of the fixed or moving solid in the porous drag, three "
              "';'-separated expressions.",
              "three expressions");
      declare(prm, "momentum source", "0; 0; 0", Patterns::Anything(),
              "[N/m^3] Extra force per volume on the fluid, three expressions.",
              "three expressions");
      declare(prm, "momentum source as field", "false", Bool(),
              "Interpolate the momentum source into a finite-element field (FE_Q^3 of the "
              "velocity degree), the path the particles' reaction force takes.");
      declare(prm, "mass source", "0", Patterns::Anything(),
              "[1/s] Right-hand side of the continuity equation (normally 0).",
              "an expression");
      declare(prm, "initial velocity", "0; 0; 0", Patterns::Anything(),
              "[m/s] Interstitial velocity at t = 0 (time-dependent runs) or Newton's "
              "first guess (steady runs).",
              "three expressions");
      declare(prm, "constants", "", Patterns::Anything(),
              "Named numbers usable in every fluid expression, 'U = 0.1, H = 0.02'.",
              "comma-separated 'name = number' pairs");
      declare(prm, "porous drag", "none", Selection(names<PorousDrag>().selection()),
              "Drag of a fixed porous medium on the fluid: 'ergun' uses beta = 150 (1-eps)^2 "
              "mu / (eps d^2) + 1.75 (1-eps) rho |u - u_s| / d (Ergun 1952, Gidaspow form).");
      declare(prm, "particle diameter", "1e-3", Double(1e-12, inf),
              "[m] Grain diameter d of the porous medium in the drag closure, > 0.",
              "a number > 0");
      declare(prm, "driving pressure gradient", "0, 0, 0", vector_pattern(),
              "[Pa/m] Mean pressure gradient G imposed on periodic flows: the fluid feels "
              "-eps G (model A) or -G (model B).");
      declare(prm, "gravity", "false", Bool(),
              "Apply 'simulation/gravity' to the fluid as rho eps g.");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid mesh");
    {
      declare(prm, "type", "box", Selection(names<FluidMeshType>().selection()),
              "'box' (boundary ids 0/1 at x min/max, 2/3 y, 4/5 z), 'cylinder' along x "
              "(0 hull, 1 x = -L/2, 2 x = +L/2), 'channel_with_cylinder' (deal.II's "
              "benchmark channel: 0 inlet, 1 outlet, 2 cylinder, 3 walls), 'gmsh' (.msh "
              "file, physical tags become boundary ids).");
      declare(prm, "lower corner", "0, 0, 0", vector_pattern(), "[m] Box: lower corner.");
      declare(prm, "upper corner", "1, 1, 1", vector_pattern(), "[m] Box: upper corner.");
      declare(prm, "subdivisions", "1, 1, 1", Patterns::List(Integer(1, 10000), 3, 3, ","),
              "[-] Box: coarse cells per direction before refinement.");
      declare(prm, "radius", "0.5", Double(1e-12, inf), "[m] Cylinder: radius.",
              "a number > 0");
      declare(prm, "length", "2", Double(1e-12, inf), "[m] Cylinder: length along x.",
              "a number > 0");
      declare(prm, "file", "", Patterns::Anything(),
              "Gmsh: the .msh file (relative to the .prm).", "a file name");
      declare(prm, "initial refinement", "0", Integer(0, 12),
              "[-] Global refinements of the coarse mesh.");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid boundaries");
    {
      declare(prm, "conditions", "walls: no-slip: 0 1 2 3 4 5", Patterns::Anything(),
              "Boundary conditions, separated by '|', each 'name: type: ids[: data]'. "
              "Types: no-slip; slip; velocity (data: three ';'-separated expressions of x, "
              "y, z, t); traction-free (an outlet); periodic (two ids, data: x, y or z). "
              "Example: 'inlet: velocity: 0: U; 0; 0 | outlet: traction-free: 1 | walls: "
              "no-slip: 2 3 4 5'.",
              "a '|'-separated list; every boundary id of the mesh must appear once");
      declare(prm, "pressure reference point", "0, 0, 0", vector_pattern(),
              "[m] Without a traction-free boundary the pressure is fixed to 0 at the "
              "pressure node nearest this point.");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid time");
    {
      declare(prm, "integration", "steady", Selection(names<TimeIntegration>().selection()),
              "'steady' (Newton on the steady equations), 'bdf1' (backward Euler) or "
              "'bdf2' (second-order backward differences; the first step is BDF1).");
      declare(prm, "time step", "1e-3", Double(1e-15, inf), "[s] Fluid time step, > 0.",
              "a number > 0");
      declare(prm, "end time", "1", Double(0, inf), "[s] Time-dependent runs stop here.");
      declare(prm, "restart from", "", Patterns::Anything(),
              "Continue a time-dependent run from a checkpoint: its base name, as written "
              "by 'fluid output/checkpoint interval' (<directory>/<base name>-checkpoint), "
              "relative to the working directory. Empty: start at t = 0.",
              "empty or a checkpoint base name");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid solver");
    {
      declare(prm, "newton tolerance", "1e-10", Double(0, inf),
              "[N, m^3/s] Newton stops when the l2 norm of the assembled residual vector "
              "(momentum rows in N, continuity rows in m^3/s) is below this ...");
      declare(prm, "newton relative tolerance", "1e-9", Double(0, 1),
              "[-] ... or below this times the first residual of the step.");
      declare(prm, "newton max iterations", "20", Integer(1, 1000),
              "[-] A step that has not converged after this many iterations stops the run "
              "with a message.");
      declare(prm, "preconditioner", "ilu", Selection(names<LinearPreconditioner>().selection()),
              "GMRES preconditioner: 'ilu' (Trilinos Ifpack ILU(k), one block per rank), "
              "'amg' (Trilinos ML) or 'lu' (Trilinos Amesos KLU, a complete factorisation "
              "with pivoting, gathered on one rank: for the small systems on which ILU meets "
              "zero pivots even after the Picard start, such as Taylor-Hood elements without "
              "stabilisation; doc/fluid.md says up to what size). Rebuilt only when GMRES "
              "needs many more iterations than after the last build, or the mesh changes.");
      declare(prm, "ilu fill", "0", Integer(0, 10), "[-] ILU fill level k.");
      declare(prm, "linear tolerance", "1e-4", Double(1e-14, 1),
              "[-] GMRES stops at this residual reduction (inexact Newton).");
      declare(prm, "linear max iterations", "1000", Integer(1, 100000),
              "[-] GMRES iteration limit.");
      declare(prm, "grad-div", "0", Double(0, inf),
              "[-] Grad-div stabilisation factor gamma_0: gamma = gamma_0 (mu + rho |u| h).");
      declare(prm, "stabilization", "true", Bool(),
              "SUPG/PSPG (GLS) stabilisation; needed for equal-order elements and "
              "convection. Off only for Taylor-Hood elements at low Reynolds number, and "
              "then with 'preconditioner = lu': the pressure block is zero, and ILU and "
              "ML meet zero pivots.");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid refinement");
    {
      declare(prm, "adaptive", "false", Bool(),
              "Adapt the mesh with the Kelly estimator (refine and coarsen).");
      declare(prm, "indicator", "velocity", Selection(names<RefinementIndicator>().selection()),
              "What the Kelly estimator looks at.");
      declare(prm, "refine fraction", "0.3", Double(0, 1),
              "[-] Fraction of cells (by number) refined at each adaptation.");
      declare(prm, "coarsen fraction", "0.05", Double(0, 1),
              "[-] Fraction of cells (by number) coarsened at each adaptation.");
      declare(prm, "min level", "0", Integer(0, 20), "[-] Cells are never coarser.");
      declare(prm, "max level", "10", Integer(0, 20), "[-] Cells are never finer.");
      declare(prm, "interval", "10", Integer(1, 1000000),
              "[-] Time-dependent runs adapt every this many time steps.");
      declare(prm, "steady cycles", "1", Integer(1, 50),
              "[-] Steady runs: solve, adapt, solve again this many times.");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid output");
    {
      declare(prm, "directory", "output", Patterns::Anything(),
              "Where .pvd/.vtu and .csv files go.", "a directory name; created if missing");
      declare(prm, "base name", "fluid", Patterns::Anything(), "Prefix of the output files.",
              "a file name prefix");
      declare(prm, "vtu interval", "0", Double(0, inf),
              "[s] Time between snapshots of velocity, pressure and porosity; 0 writes "
              "only the final state.");
      declare(prm, "csv interval", "0", Double(0, inf),
              "[s] Time between rows of the integral .csv; 0 writes a row per time step.");
      declare(prm, "pressure drop between", "", Patterns::Anything(),
              "Two boundary names 'a, b': the .csv and the summary report mean pressure on "
              "a minus mean pressure on b.",
              "two names from 'fluid boundaries/conditions', or empty");
      declare(prm, "flow rate through", "", Patterns::Anything(),
              "Boundary names whose flow rate integral(eps u . n) is reported.",
              "names from 'fluid boundaries/conditions'");
      declare(prm, "progress", "true", Bool(), "Show one line per time step on stderr.");
      declare(prm, "checkpoint interval", "0", Integer(0, 100000000),
              "[steps] Time-dependent runs write <directory>/<base name>-checkpoint every "
              "this many time steps (replacing the previous one); 0 writes none.");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid validation");
    {
      declare(prm, "case", "none",
              Selection(names<FluidValidationCase>().selection()),
              "'poiseuille': pressure drop against 8 mu U L / H^2 (x flow between walls at "
              "y min/max); 'packed_bed_ergun': pressure drop per length against Ergun, once "
              "per superficial velocity; 'manufactured_solution': built-in exact solution "
              "with variable porosity on successive refinements (value: observed velocity "
              "L2 rate); 'reference_value': pressure drop against 'reference value'.");
      declare(prm, "tolerance", "0", Double(0, inf),
              "[-] If > 0, exit with code 3 when the relative error exceeds it.");
      declare(prm, "maximum velocity", "0", Double(0, inf),
              "[m/s] Poiseuille: centre-line velocity U of the inlet profile.");
      declare(prm, "superficial velocities", "", Patterns::List(Double(0, inf), 0),
              "[m/s] Packed bed: superficial velocities U = eps u to solve for; the inlet "
              "velocity is U / eps.",
              "a comma-separated list of numbers >= 0");
      declare(prm, "refinements", "3", Integer(2, 8),
              "[-] Manufactured solution: number of meshes, each refined once more.");
      declare(prm, "manufactured solution", "trigonometric",
              Patterns::Selection("trigonometric|polynomial"),
              "'trigonometric' (errors from space and time), or 'polynomial' (quadratic "
              "velocity, linear pressure: exact in space for Q2-Q1, so a time-dependent run "
              "measures the BDF error alone).");
      declare(prm, "refine", "space", Patterns::Selection("space|time"),
              "Manufactured solution: 'space' refines the mesh once per run (and halves "
              "the time step with it); 'time' keeps the mesh and halves the time step.");
      declare(prm, "uneven steps", "false", Bool(),
              "Manufactured solution: alternate steps of 1.25 dt and 0.75 dt (an even "
              "number of them), which exercises the variable-step BDF2 coefficients.");
      declare(prm, "reference value", "0", Double(-inf, inf),
              "[Pa or m^3/s] reference_value: the expected value of 'quantity'.");
      declare(prm, "quantity", "pressure drop", Selection("pressure drop|flow rate"),
              "reference_value: compare the pressure drop or the flow rate through the "
              "first boundary of 'fluid output/flow rate through'.");
    }
    prm.leave_subsection();
  }

  void read_fluid_parameters(ParameterHandler &prm, const std::string &file,
                             FluidParameters &p)
  {
    prm.enter_subsection("fluid");
    p.density     = prm.get_double("density");
    p.viscosity   = prm.get_double("viscosity");
    p.formulation = value_of<VansFormulation>(prm.get("formulation"));
    p.velocity_degree   = prm.get_integer("velocity degree");
    p.pressure_degree   = prm.get_integer("pressure degree");
    p.porosity          = prm.get("porosity");
    p.porosity_as_field = prm.get_bool("porosity as field");
    p.solid_velocity    = prm.get("solid velocity");
    p.momentum_source   = prm.get("momentum source");
    p.momentum_source_as_field = prm.get_bool("momentum source as field");
    p.mass_source       = prm.get("mass source");
    p.initial_velocity  = prm.get("initial velocity");
    p.constants         = prm.get("constants");
    p.drag = value_of<PorousDrag>(prm.get("porous drag"));
    p.particle_diameter         = prm.get_double("particle diameter");
    p.driving_pressure_gradient = get_vector(prm, "driving pressure gradient");
    p.use_gravity               = prm.get_bool("gravity");
    prm.leave_subsection();
    if (p.pressure_degree > p.velocity_degree)
      fail(file, "fluid/pressure degree",
           "= " + std::to_string(p.pressure_degree) + " is above the velocity degree " +
             std::to_string(p.velocity_degree) + "; allowed: 1 .. velocity degree");
    check_expression(file, "fluid/porosity", p.porosity, 1, p.constants);
    check_expression(file, "fluid/solid velocity", p.solid_velocity, 3, p.constants);
    check_expression(file, "fluid/momentum source", p.momentum_source, 3, p.constants);
    check_expression(file, "fluid/mass source", p.mass_source, 1, p.constants);
    check_expression(file, "fluid/initial velocity", p.initial_velocity, 3, p.constants);

    prm.enter_subsection("fluid mesh");
    {
      p.mesh_type         = value_of<FluidMeshType>(prm.get("type"));
      p.lower_corner      = get_vector(prm, "lower corner");
      p.upper_corner      = get_vector(prm, "upper corner");
      const auto s        = dealii::Utilities::string_to_int(
        dealii::Utilities::split_string_list(prm.get("subdivisions"), ','));
      for (unsigned int d = 0; d < 3; ++d)
        p.subdivisions[d] = s[d];
      p.cylinder_radius      = prm.get_double("radius");
      p.cylinder_half_length = 0.5 * prm.get_double("length");
      p.mesh_file            = prm.get("file");
      p.initial_refinement   = prm.get_integer("initial refinement");
    }
    prm.leave_subsection();
    if (p.mesh_type == FluidMeshType::box)
      for (unsigned int d = 0; d < 3; ++d)
        if (!(p.upper_corner[d] > p.lower_corner[d]))
          fail(file, "fluid mesh/upper corner",
               "must be above 'lower corner' in every direction");
    if (p.mesh_type == FluidMeshType::gmsh && p.mesh_file.empty())
      fail(file, "fluid mesh/file", "is empty; 'type = gmsh' needs a .msh file");

    prm.enter_subsection("fluid boundaries");
    {
      const std::string entry = "fluid boundaries/conditions";
      for (const auto &text : dealii::Utilities::split_string_list(prm.get("conditions"), '|'))
        {
          if (text.empty())
            continue;
          const auto f = dealii::Utilities::split_string_list(text, ':');
          if (f.size() < 3)
            fail(file, entry, "has '" + text + "'; expected 'name: type: ids[: data]'");
          BoundaryCondition bc;
          bc.name = f[0];
          const std::string &type = f[1];
          try
            {
              bc.type = value_of<BoundaryType>(type);
            }
          catch (const std::invalid_argument &)
            {
              throw InputError("error in '" + file + "': entry '" + entry +
                               "' has the unknown type '" + type + "' in '" + text +
                               "'; allowed: no-slip, slip, velocity, traction-free, periodic");
            }
          for (const auto &id : dealii::Utilities::split_string_list(f[2], ' '))
            {
              if (id.empty())
                continue;
              char *end   = nullptr;
              const long v = std::strtol(id.c_str(), &end, 10);
              if (end == id.c_str() || *end != '\0' || v < 0 || v > 255)
                fail(file, entry,
                     "has the boundary id '" + id + "' in '" + text +
                       "'; ids are integers 0..255 separated by spaces");
              bc.ids.push_back(v);
            }
          if (bc.ids.empty())
            fail(file, entry, "has no boundary id in '" + text + "'");
          const std::string data = f.size() > 3 ? f[3] : "";
          if (bc.type == BoundaryType::velocity)
            {
              if (data.empty())
                fail(file, entry, "has no velocity in '" + text + "'");
              check_expression(file, entry + " (" + bc.name + ")", data, 3, p.constants);
              bc.velocity = data;
            }
          if (bc.type == BoundaryType::periodic)
            {
              if (bc.ids.size() != 2 || (data != "x" && data != "y" && data != "z"))
                fail(file, entry,
                     "has '" + text + "'; a periodic pair is 'name: periodic: id1 id2: x|y|z'");
              bc.direction = data[0] - 'x';
            }
          if (p.boundary_index(bc.name) >= 0)
            fail(file, entry, "names the boundary '" + bc.name + "' twice");
          for (const auto &other : p.boundaries)
            for (const auto id : other.ids)
              for (const auto mine : bc.ids)
                if (id == mine)
                  fail(file, entry,
                       "gives boundary id " + std::to_string(id) + " to both '" + other.name +
                         "' and '" + bc.name + "'");
          p.boundaries.push_back(bc);
        }
      p.pressure_reference_point = get_vector(prm, "pressure reference point");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid time");
    {
      p.time_integration  = value_of<TimeIntegration>(prm.get("integration"));
      p.time_step         = prm.get_double("time step");
      p.end_time          = prm.get_double("end time");
      p.restart_from      = prm.get("restart from");
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid solver");
    p.newton_tolerance          = prm.get_double("newton tolerance");
    p.newton_relative_tolerance = prm.get_double("newton relative tolerance");
    p.newton_max_iterations     = prm.get_integer("newton max iterations");
    p.preconditioner = value_of<LinearPreconditioner>(prm.get("preconditioner"));
    p.ilu_fill              = prm.get_integer("ilu fill");
    p.linear_tolerance      = prm.get_double("linear tolerance");
    p.linear_max_iterations = prm.get_integer("linear max iterations");
    p.grad_div              = prm.get_double("grad-div");
    p.stabilization         = prm.get_bool("stabilization");
    prm.leave_subsection();
    if (!p.stabilization && p.velocity_degree == p.pressure_degree)
      fail(file, "fluid solver/stabilization",
           "= false with equal velocity and pressure degrees: that pair is not inf-sup "
           "stable; allowed: true, or velocity degree = pressure degree + 1");

    prm.enter_subsection("fluid refinement");
    {
      p.adaptive = prm.get_bool("adaptive");
      p.indicator = value_of<RefinementIndicator>(prm.get("indicator"));
      p.refine_fraction     = prm.get_double("refine fraction");
      p.coarsen_fraction    = prm.get_double("coarsen fraction");
      p.min_level           = prm.get_integer("min level");
      p.max_level           = prm.get_integer("max level");
      p.refinement_interval = prm.get_integer("interval");
      p.steady_cycles       = prm.get_integer("steady cycles");
    }
    prm.leave_subsection();
    if (p.min_level > p.max_level)
      fail(file, "fluid refinement/min level", "is above 'max level'");
    if (p.refine_fraction + p.coarsen_fraction > 1.)
      fail(file, "fluid refinement/refine fraction",
           "plus 'coarsen fraction' is above 1; allowed: a sum <= 1");

    prm.enter_subsection("fluid output");
    {
      p.output_directory = prm.get("directory");
      p.base_name        = prm.get("base name");
      p.vtu_interval     = prm.get_double("vtu interval");
      p.csv_interval     = prm.get_double("csv interval");
      p.progress         = prm.get_bool("progress");
      p.checkpoint_interval = prm.get_integer("checkpoint interval");
      const auto pair = dealii::Utilities::split_string_list(prm.get("pressure drop between"), ',');
      if (!(pair.size() == 0 || pair.size() == 2))
        fail(file, "fluid output/pressure drop between",
             "needs two boundary names separated by ','");
      for (unsigned int k = 0; k < pair.size(); ++k)
        {
          if (p.boundary_index(pair[k]) < 0)
            fail(file, "fluid output/pressure drop between",
                 "names '" + pair[k] + "', which is not in 'fluid boundaries/conditions'");
          p.pressure_drop_between[k] = pair[k];
        }
      for (const auto &name :
           dealii::Utilities::split_string_list(prm.get("flow rate through"), ','))
        {
          if (p.boundary_index(name) < 0)
            fail(file, "fluid output/flow rate through",
                 "names '" + name + "', which is not in 'fluid boundaries/conditions'");
          p.flow_rate_through.push_back(name);
        }
    }
    prm.leave_subsection();

    prm.enter_subsection("fluid validation");
    {
      p.validation = value_of<FluidValidationCase>(prm.get("case"));
      p.tolerance                   = prm.get_double("tolerance");
      p.poiseuille_maximum_velocity = prm.get_double("maximum velocity");
      p.superficial_velocities      = dealii::Utilities::string_to_double(
        dealii::Utilities::split_string_list(prm.get("superficial velocities"), ','));
      p.mms_refinements = prm.get_integer("refinements");
      p.reference_value = prm.get_double("reference value");
      p.mms_polynomial  = prm.get("manufactured solution") == "polynomial";
      p.reference_is_flow_rate = prm.get("quantity") == "flow rate";
      p.mms_refine_time_only = prm.get("refine") == "time";
      p.mms_uneven_steps     = prm.get_bool("uneven steps");
    }
    prm.leave_subsection();
    const bool needs_drop = p.validation == FluidValidationCase::poiseuille ||
                            p.validation == FluidValidationCase::packed_bed_ergun ||
                            (p.validation == FluidValidationCase::reference_value &&
                             !p.reference_is_flow_rate);
    if (p.validation == FluidValidationCase::reference_value && p.reference_is_flow_rate &&
        p.flow_rate_through.empty())
      fail(file, "fluid output/flow rate through",
           "is empty, but 'fluid validation/quantity' is the flow rate");
    if (p.mms_refine_time_only && p.time_integration == TimeIntegration::steady)
      fail(file, "fluid validation/refine",
           "= time with 'fluid time/integration = steady'; allowed: space, or a BDF scheme");
    if (!p.restart_from.empty() &&
        (p.time_integration == TimeIntegration::steady || p.validation != FluidValidationCase::none))
      fail(file, "fluid time/restart from",
           "is set, but only a time-dependent run without a validation case can restart");
    if (p.validation == FluidValidationCase::packed_bed_ergun)
      {
        // The scene sets the constant U to each superficial velocity in turn; an
        // inlet that does not use it would solve the same flow every time.
        bool uses_u = false;
        for (const auto &bc : p.boundaries)
          if (bc.type == BoundaryType::velocity)
            for (const auto &part : dealii::Utilities::split_string_list(bc.velocity, ';'))
              uses_u = uses_u || part.find('U') != std::string::npos;
        if (!uses_u)
          fail(file, "fluid boundaries/conditions",
               "has no velocity inlet that uses the constant U; packed_bed_ergun sets U to "
               "each superficial velocity (write the inlet as U/eps0; 0; 0)");
      }
    if (p.validation == FluidValidationCase::poiseuille && p.mesh_type != FluidMeshType::box)
      fail(file, "fluid validation/case",
           "= poiseuille needs 'fluid mesh/type = box' (flow along x, walls at y min and max)");
    if (needs_drop && p.pressure_drop_between[0].empty())
      fail(file, "fluid output/pressure drop between",
           "is empty, but the validation case compares the pressure drop");
    if (p.validation == FluidValidationCase::packed_bed_ergun &&
        (p.superficial_velocities.empty() || p.drag != PorousDrag::ergun))
      fail(file, "fluid validation/superficial velocities",
           "is empty or 'fluid/porous drag' is not 'ergun'; packed_bed_ergun needs both");
  }
} // namespace sluice
