// The VANS solver's life cycle: degrees of freedom and constraints, Newton's
// method with a backtracking line search (and a Picard start in SUPG's
// advecting velocity where the preconditioner breaks down), GMRES with a
// reused preconditioner, time steps, mesh adaptation, integrals and errors.
// The cell assembly is in vans_assembly.cc, the output in fluid_output.cc.

#include <sluice/core/mpi_extremum.h>
#include <sluice/core/names.h>
#include <sluice/core/scene_parameters.h>
#include <sluice/fluid/factorized_preconditioner.h>
#include <sluice/fluid/fluid_mesh.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <set>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    /// Thrown by solve_linear() when GMRES fails with a freshly built
    /// preconditioner; caught by solve_for_update(). A breakdown is a zero or
    /// tiny pivot (NaN, or factors that amplify without bound), else GMRES
    /// ran to its iteration limit.
    struct LinearSolveFailure
    {
      bool breakdown;
    };
  } // namespace

  VansSolver::VansSolver(const FluidParameters &parameters, const FluidCoefficients &coeffs,
                         const Tensor<1, 3> &gravity, const std::string &file_name,
                         MPI_Comm communicator)
    : prm(parameters)
    , coefficients(coeffs)
    , gravity(gravity)
    , file_name(file_name)
    , comm(communicator)
    , triangulation(communicator,
                    Triangulation<3>::MeshSmoothing(Triangulation<3>::smoothing_on_refinement |
                                                    Triangulation<3>::smoothing_on_coarsening))
    , mapping(parameters.mesh_type == FluidMeshType::box ?
                std::make_unique<MappingQ<3>>(1) :
                std::make_unique<MappingQ<3>>(parameters.velocity_degree))
    , fe(FE_Q<3>(parameters.velocity_degree), 3, FE_Q<3>(parameters.pressure_degree), 1)
    , porosity_fe(parameters.velocity_degree)
    , source_fe(FE_Q<3>(parameters.velocity_degree), 3)
  {}

  VansSolver::~VansSolver()
  {
    // The DoF handlers must let go of the mesh before it goes.
    preconditioner.reset();
    source_dof_handler.clear();
    porosity_dof_handler.clear();
    dof_handler.clear();
  }

  types::global_dof_index VansSolver::n_dofs() const
  {
    return dof_handler.n_dofs();
  }

  types::global_cell_index VansSolver::n_active_cells() const
  {
    return triangulation.n_global_active_cells();
  }

  void VansSolver::initialize(const double t0)
  {
    make_fluid_mesh(triangulation, prm, file_name);
    dof_handler.reinit(triangulation);
    porosity_dof_handler.reinit(triangulation);
    source_dof_handler.reinit(triangulation);
    current_time = t0;
    setup_dofs();

    // Initial velocity (time-dependent runs) or Newton's first guess; p = 0.
    TrilinosWrappers::MPI::Vector owned_solution(owned, comm);
    if (coefficients.initial_velocity)
      {
        coefficients.initial_velocity->set_time(t0);
        // Interpolate the 3-component function into the velocity components.
        class Padded : public Function<3>
        {
        public:
          Padded(const Function<3> &f) : Function<3>(4), f(f) {}
          double value(const Point<3> &x, const unsigned int c) const override
          {
            return c < 3 ? f.value(x, c) : 0.;
          }

        private:
          const Function<3> &f;
        } padded(*coefficients.initial_velocity);
        VectorTools::interpolate(*mapping, dof_handler, padded, owned_solution);
      }
    nonzero_constraints.distribute(owned_solution);
    present_solution = owned_solution;
    for (auto &old : old_solutions)
      old = present_solution;
    set_porosity_field();
    for (unsigned int l = 1; l < porosity_levels.size(); ++l)
      porosity_levels[l] = porosity_levels[0];
    set_momentum_source_field();
  }

  void VansSolver::set_momentum_source_field()
  {
    // With 'momentum source as field' the .prm's source is interpolated into
    // the field, standing in for the particles' reaction force.
    if (!prm.momentum_source_as_field)
      return;
    TrilinosWrappers::MPI::Vector owned_source(source_owned, comm);
    if (coefficients.momentum_source)
      {
        coefficients.momentum_source->set_time(current_time);
        VectorTools::interpolate(*mapping, source_dof_handler, *coefficients.momentum_source,
                                 owned_source);
      }
    momentum_source_field = owned_source;
  }

  void VansSolver::set_porosity(const TrilinosWrappers::MPI::Vector &owned_porosity)
  {
    // Kept for the next advance(), which makes it the porosity at t^{n+1}.
    next_porosity      = owned_porosity;
    porosity_from_caller = true;
  }

  void VansSolver::set_initial_porosity(const TrilinosWrappers::MPI::Vector &owned_porosity)
  {
    for (auto &level : porosity_levels)
      level = owned_porosity;
    porosity_from_caller = false;
  }

  void VansSolver::set_momentum_source(const TrilinosWrappers::MPI::Vector &owned_source)
  {
    momentum_source_field = owned_source;
  }

  void VansSolver::set_exchange_drag(const TrilinosWrappers::MPI::Vector &owned_beta)
  {
    AssertThrow(prm.exchange_drag_as_field,
                ExcMessage("an exchange drag field needs 'exchange_drag_as_field'"));
    exchange_drag = owned_beta;
  }

  void VansSolver::setup_dofs()
  {
    dof_handler.distribute_dofs(fe);
    owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);

    porosity_dof_handler.distribute_dofs(porosity_fe);
    porosity_owned = porosity_dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(porosity_dof_handler, porosity_relevant);
    for (auto &level : porosity_levels)
      level.reinit(porosity_owned, porosity_relevant, comm);
    // A porosity set for the next step on the old mesh no longer fits.
    porosity_from_caller = false;
    if (prm.momentum_source_as_field)
      {
        source_dof_handler.distribute_dofs(source_fe);
        source_owned = source_dof_handler.locally_owned_dofs();
        DoFTools::extract_locally_relevant_dofs(source_dof_handler, source_relevant);
        momentum_source_field.reinit(source_owned, source_relevant, comm);
      }
    // (The coupled scene refuses the semi-implicit exchange on an adaptive
    // mesh: the returned term must be the one applied, on the same mesh.)
    if (prm.exchange_drag_as_field)
      {
        exchange_drag.reinit(porosity_owned, porosity_relevant, comm);
        applied_exchange_drag.reinit(porosity_owned, porosity_relevant, comm);
      }

    make_mesh_constraints();
    make_constraints();

    DynamicSparsityPattern dsp(relevant);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, nonzero_constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
    system_matrix.reinit(owned, owned, dsp, comm);

    present_solution.reinit(owned, relevant, comm);
    evaluation_point.reinit(owned, relevant, comm);
    for (auto &old : old_solutions)
      old.reinit(owned, relevant, comm);
    system_rhs.reinit(owned, comm);
    newton_update.reinit(owned, comm);
    preconditioner.reset(); // the matrix layout changed
  }

  void VansSolver::make_mesh_constraints()
  {
    // The pressure node nearest the reference point, if no boundary fixes p.
    bool has_outlet = false;
    for (const auto &bc : prm.boundaries)
      has_outlet = has_outlet || bc.type == BoundaryType::traction_free;
    pressure_reference_dof = numbers::invalid_dof_index;
    if (!has_outlet)
      {
        const Point<3> target(prm.pressure_reference_point[0], prm.pressure_reference_point[1],
                              prm.pressure_reference_point[2]);
        double                  nearest   = std::numeric_limits<double>::max();
        types::global_dof_index candidate = 0;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              {
                const double d = cell->vertex(v).distance(target);
                const auto   dof = cell->vertex_dof_index(v, 3);
                if (owned.is_element(dof) && d < nearest)
                  {
                    nearest   = d;
                    candidate = dof;
                  }
              }
        unsigned long long chosen = candidate;
        MPI_Bcast(&chosen, 1, MPI_UNSIGNED_LONG_LONG, rank_of_least(nearest, comm).rank, comm);
        pressure_reference_dof = chosen;
      }

    hanging_and_periodic.clear();
    hanging_and_periodic.reinit(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, hanging_and_periodic);
    for (const auto &bc : prm.boundaries)
      if (bc.type == BoundaryType::periodic)
        DoFTools::make_periodicity_constraints(dof_handler, bc.ids[0], bc.ids[1], bc.direction,
                                               hanging_and_periodic);

    std::set<types::boundary_id> slip_ids;
    for (const auto &bc : prm.boundaries)
      if (bc.type == BoundaryType::slip)
        slip_ids.insert(bc.ids.begin(), bc.ids.end());
    has_slip = !slip_ids.empty();
    slip_constraints.clear();
    slip_constraints.reinit(relevant);
    if (has_slip)
      VectorTools::compute_no_normal_flux_constraints(dof_handler, 0, slip_ids, slip_constraints,
                                                      *mapping);

    build_constraints(true, zero_constraints);
  }

  void VansSolver::make_constraints()
  {
    build_constraints(false, nonzero_constraints);
  }

  void VansSolver::build_constraints(const bool homogeneous, AffineConstraints<double> &c) const
  {
    const FEValuesExtractors::Vector velocities(0);
    const ComponentMask              velocity_mask = fe.component_mask(velocities);
    c.clear();
    c.copy_from(hanging_and_periodic);
    for (unsigned int b = 0; b < prm.boundaries.size(); ++b)
      {
        const auto &bc = prm.boundaries[b];
        if (bc.type != BoundaryType::no_slip && bc.type != BoundaryType::velocity)
          continue;
        const Functions::ZeroFunction<3> zero(4);
        const Function<3>               *f = &zero;
        if (bc.type == BoundaryType::velocity && !homogeneous)
          {
            coefficients.boundary_velocity[b]->set_time(current_time);
            f = coefficients.boundary_velocity[b].get();
          }
        for (const auto id : bc.ids)
          VectorTools::interpolate_boundary_values(*mapping, dof_handler, id, *f, c, velocity_mask);
      }
    // Walls and inlets win where they meet a slip boundary.
    if (has_slip)
      c.merge(slip_constraints, AffineConstraints<double>::left_object_wins, true);
    if (pressure_reference_dof != numbers::invalid_dof_index &&
        relevant.is_element(pressure_reference_dof) && !c.is_constrained(pressure_reference_dof))
      c.add_line(pressure_reference_dof);
    c.close();
  }

  void VansSolver::set_porosity_field()
  {
    // The field is what the Kelly indicator and the output see; the assembly
    // reads it only with 'porosity as field'.
    TrilinosWrappers::MPI::Vector owned_eps(porosity_owned, comm);
    if (coefficients.porosity)
      {
        coefficients.porosity->set_time(current_time);
        VectorTools::interpolate(*mapping, porosity_dof_handler, *coefficients.porosity, owned_eps);
        // A porosity outside (0, 1] has no meaning (and 0 divides): refuse it
        // where it is set, naming the entry, rather than let GMRES fail.
        const double lowest  = -Utilities::MPI::max(-owned_eps.min(), comm);
        const double highest = Utilities::MPI::max(owned_eps.max(), comm);
        if (!(lowest > 0.) || !(highest <= 1.))
          throw InputError("error in '" + file_name + "': entry 'fluid/porosity' takes values in [" +
                           to_text(lowest) + ", " + to_text(highest) + "] at time " +
                           to_text(current_time) +
                           " s; a porosity must lie in (0, 1] everywhere");
      }
    else
      owned_eps = 1.;
    porosity_levels[0] = owned_eps;
  }

  unsigned int VansSolver::solve_linear(NewtonReport &report)
  {
    const auto build = [&]() {
      if (prm.preconditioner == LinearPreconditioner::ilu)
        {
          auto ilu = std::make_unique<TrilinosWrappers::PreconditionILU>();
          ilu->initialize(system_matrix, TrilinosWrappers::PreconditionILU::AdditionalData(
                                           prm.ilu_fill, 1e-12, 1., 0));
          preconditioner = std::move(ilu);
        }
      else if (prm.preconditioner == LinearPreconditioner::lu)
        preconditioner = std::make_unique<FactorizedPreconditioner>(system_matrix);
      else
        {
          auto amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
          TrilinosWrappers::PreconditionAMG::AdditionalData data;
          data.elliptic              = false;
          data.higher_order_elements = prm.velocity_degree > 1;
          data.smoother_type         = "ILU";
          data.coarse_type           = "ILU";
          data.smoother_sweeps       = 2;
          data.aggregation_threshold = 1e-3;
          DoFTools::extract_constant_modes(dof_handler, ComponentMask(4, true),
                                           data.constant_modes);
          amg->initialize(system_matrix, data);
          preconditioner = std::move(amg);
        }
      ++report.preconditioner_builds;
      iterations_after_build = 0;
    };
    bool       fresh       = false;
    const auto build_fresh = [&]() {
      build();
      fresh = true;
      if (preconditioner_broke_down())
        throw LinearSolveFailure{true};
    };
    if (!preconditioner)
      build_fresh();

    for (;;)
      {
        SolverControl control(prm.linear_max_iterations,
                              std::max(prm.linear_tolerance * system_rhs.l2_norm(), 1e-300),
                              false, false);
        SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData data(200);
        SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(control, data);
        newton_update = 0.;
        try
          {
            gmres.solve(system_matrix, newton_update, system_rhs, *preconditioner);
          }
        catch (const SolverControl::NoConvergence &)
          {
            // With a fresh preconditioner a rebuild cannot help: the caller
            // decides (a NaN residual is a zero pivot in the factorisation).
            if (fresh)
              throw LinearSolveFailure{!std::isfinite(control.last_value())};
            build_fresh();
            continue;
          }
        const unsigned int n = control.last_step();
        report.linear_iterations += n;
        // A reused preconditioner that has gone stale: rebuild it next time.
        if (fresh)
          iterations_after_build = n;
        else if (n > 2 * iterations_after_build + 10)
          preconditioner.reset();
        return n;
      }
  }

  /// A freshly built preconditioner P has broken down if applying it to the
  /// right-hand side b gives A P^-1 b far from b: a zero or tiny pivot makes
  /// P^-1 amplify some modes without bound. Over the fluid and coupled tests
  /// working ILU, ML and LU gave |A P^-1 b| / |b| up to 8.5e3, broken ones
  /// 1e22 and more (or NaN). One application and one product per build.
  bool VansSolver::preconditioner_broke_down() const
  {
    const double b = system_rhs.l2_norm();
    if (!(b > 0.))
      return false;
    TrilinosWrappers::MPI::Vector y(owned, comm), z(owned, comm);
    preconditioner->vmult(y, system_rhs);
    system_matrix.vmult(z, y);
    const double amplification = z.l2_norm() / b;
    return !(amplification < 1e10);
  }

  /// Solves for the Newton update. Should GMRES fail with a fresh
  /// preconditioner on the exact Jacobian of a stabilised system, the rest of
  /// this Newton solve leaves out SUPG's derivative in its advecting velocity
  /// (vans_solver.h): a Picard step in that velocity on the same residual, so
  /// the solution it converges to is the same.
  void VansSolver::solve_for_update(NewtonReport &report)
  {
    try
      {
        solve_linear(report);
        return;
      }
    catch (const LinearSolveFailure &f)
      {
        if (!(prm.stabilization && supg_advection_derivative))
          throw linear_solve_failure(f.breakdown);
      }
    supg_advection_derivative = false;
    ++report.picard_starts;
    if (!picard_start_reported && Utilities::MPI::this_mpi_process(comm) == 0)
      std::cerr << "fluid: GMRES with a fresh '" << name_of(prm.preconditioner)
                << "' preconditioner failed at t = " << current_time
                << " on Newton's Jacobian; this Newton solve goes on without SUPG's term in "
                   "its advecting velocity (reported once)\n";
    picard_start_reported = true;
    assemble(true);
    preconditioner.reset();
    try
      {
        solve_linear(report);
      }
    catch (const LinearSolveFailure &f)
      {
        throw linear_solve_failure(f.breakdown);
      }
  }

  SolverFailure VansSolver::linear_solve_failure(const bool breakdown) const
  {
    const std::string also =
      prm.stabilization ? ", also without SUPG's Newton term in its advecting velocity" : "";
    if (breakdown)
      return SolverFailure(
        "the '" + name_of(prm.preconditioner) +
        "' preconditioner ('fluid solver/preconditioner') broke down at t = " +
        to_text(current_time) + also +
        ": a zero pivot in its factorisation of this saddle-point system; 'lu' factorises "
        "with pivoting and solves such systems up to some 10^4 unknowns");
    return SolverFailure(
      "GMRES did not reach 'fluid solver/linear tolerance' = " + to_text(prm.linear_tolerance) +
      " in 'fluid solver/linear max iterations' = " + std::to_string(prm.linear_max_iterations) +
      " iterations with a freshly built preconditioner at t = " + to_text(current_time) + also +
      "; raise the iteration limit, the ILU fill, or shorten 'fluid time/time step'; 'lu' "
      "solves small systems on which 'ilu' and 'amg' break down");
  }

  NewtonReport VansSolver::newton()
  {
    NewtonReport report;
    supg_advection_derivative = true;
    evaluation_point          = present_solution;
    assemble(true);
    double       residual = system_rhs.l2_norm();
    const double first    = residual;
    TrilinosWrappers::MPI::Vector current(owned, comm), trial(owned, comm);
    while (!(residual <= prm.newton_tolerance ||
             residual <= prm.newton_relative_tolerance * first))
      {
        if (report.iterations == prm.newton_max_iterations)
          throw SolverFailure(
            "Newton's method did not converge at t = " + to_text(current_time) + " after " +
            std::to_string(report.iterations) +
            " iterations ('fluid solver/newton max iterations'); residual " +
            to_text(residual) + " against 'fluid solver/newton tolerance' = " +
            to_text(prm.newton_tolerance) + ". " +
            (steady ? "Raise the iteration limit, or start closer with 'fluid/initial velocity'" :
                      "Shorten 'fluid time/time step' or raise the iteration limit"));
        solve_for_update(report);
        zero_constraints.distribute(newton_update);
        current = present_solution;

        // Backtracking: take the longest step among 1, 1/2, ... that lowers
        // the residual; the Jacobian at the accepted point comes with it.
        double step = 1.;
        for (unsigned int tries = 0;; ++tries)
          {
            trial = current;
            trial.add(step, newton_update);
            evaluation_point = trial;
            assemble(true);
            const double r = system_rhs.l2_norm();
            if (r < residual || tries == 6)
              {
                residual = r;
                break;
              }
            step *= 0.5;
          }
        present_solution = evaluation_point;
        ++report.iterations;
        if (!std::isfinite(residual))
          throw SolverFailure("the fluid solution blew up at t = " + to_text(current_time) +
                              "; shorten 'fluid time/time step'");
      }
    report.residual = residual;
    return report;
  }

  void VansSolver::apply_boundary_values()
  {
    TrilinosWrappers::MPI::Vector owned_solution(owned, comm);
    owned_solution = present_solution;
    nonzero_constraints.distribute(owned_solution);
    present_solution = owned_solution;
  }

  NewtonReport VansSolver::solve_steady()
  {
    steady = true;
    make_constraints();
    apply_boundary_values();
    return newton();
  }

  NewtonReport VansSolver::advance(const double dt)
  {
    steady = false;
    old_solutions[1] = old_solutions[0];
    old_solutions[0] = present_solution;
    time_steps[1]    = time_steps[0];
    time_steps[0]    = dt;
    current_time += dt;
    porosity_levels[2] = porosity_levels[1];
    porosity_levels[1] = porosity_levels[0];
    // The new porosity: what the caller set, else the .prm function at the new
    // time; with neither it stays as it was. The same for the momentum source
    // (set_momentum_source() writes the field directly).
    if (porosity_from_caller)
      {
        porosity_levels[0]   = next_porosity;
        porosity_from_caller = false;
      }
    else if (coefficients.porosity)
      set_porosity_field();
    if (coefficients.momentum_source)
      set_momentum_source_field();
    make_constraints();
    apply_boundary_values();
    const NewtonReport report = newton();
    if (prm.exchange_drag_as_field)
      applied_exchange_drag = exchange_drag;
    ++n_steps_done;
    return report;
  }

  void VansSolver::refine_globally()
  {
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        cell->set_refine_flag();
    adapt_mesh_with_flags();
  }

  void VansSolver::adapt_mesh()
  {
    const unsigned int k = prm.velocity_degree;
    Vector<float>      indicator(triangulation.n_active_cells());
    const FEValuesExtractors::Vector velocities(0);
    if (prm.indicator != RefinementIndicator::porosity)
      KellyErrorEstimator<3>::estimate(*mapping, dof_handler, QGauss<2>(k + 1), {}, present_solution,
                                       indicator, fe.component_mask(velocities));
    if (prm.indicator != RefinementIndicator::velocity)
      {
        Vector<float> on_porosity(triangulation.n_active_cells());
        KellyErrorEstimator<3>::estimate(*mapping, porosity_dof_handler, QGauss<2>(k + 1), {},
                                         porosity_levels[0], on_porosity);
        if (prm.indicator == RefinementIndicator::porosity)
          indicator = on_porosity;
        else
          {
            // Each normalised by its largest value, so neither drowns the other.
            const double a = Utilities::MPI::max(double(indicator.linfty_norm()), comm);
            const double b = Utilities::MPI::max(double(on_porosity.linfty_norm()), comm);
            for (unsigned int i = 0; i < indicator.size(); ++i)
              indicator[i] = (a > 0. ? indicator[i] / a : 0.) + (b > 0. ? on_porosity[i] / b : 0.);
          }
      }
    parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
      triangulation, indicator, prm.refine_fraction, prm.coarsen_fraction);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          if (cell->level() >= static_cast<int>(prm.max_level))
            cell->clear_refine_flag();
          if (cell->level() <= static_cast<int>(prm.min_level))
            cell->clear_coarsen_flag();
        }
    adapt_mesh_with_flags();
  }

  void VansSolver::adapt_mesh_with_flags()
  {
    using Transfer = parallel::distributed::SolutionTransfer<3, TrilinosWrappers::MPI::Vector>;
    Transfer solution_transfer(dof_handler), porosity_transfer(porosity_dof_handler),
      source_transfer(source_dof_handler);
    triangulation.prepare_coarsening_and_refinement();
    const std::vector<const TrilinosWrappers::MPI::Vector *> solutions = {
      &present_solution, &old_solutions[0], &old_solutions[1]};
    const std::vector<const TrilinosWrappers::MPI::Vector *> porosities = {
      &porosity_levels[0], &porosity_levels[1], &porosity_levels[2]};
    solution_transfer.prepare_for_coarsening_and_refinement(solutions);
    porosity_transfer.prepare_for_coarsening_and_refinement(porosities);
    if (prm.momentum_source_as_field)
      source_transfer.prepare_for_coarsening_and_refinement(momentum_source_field);
    triangulation.execute_coarsening_and_refinement();
    setup_dofs();

    std::vector<TrilinosWrappers::MPI::Vector> moved(3, TrilinosWrappers::MPI::Vector(owned, comm));
    std::vector<TrilinosWrappers::MPI::Vector *> moved_ptr = {&moved[0], &moved[1], &moved[2]};
    solution_transfer.interpolate(moved_ptr);
    for (auto &v : moved)
      nonzero_constraints.distribute(v);
    present_solution = moved[0];
    old_solutions[0] = moved[1];
    old_solutions[1] = moved[2];

    std::vector<TrilinosWrappers::MPI::Vector> eps(
      3, TrilinosWrappers::MPI::Vector(porosity_owned, comm));
    std::vector<TrilinosWrappers::MPI::Vector *> eps_ptr = {&eps[0], &eps[1], &eps[2]};
    porosity_transfer.interpolate(eps_ptr);
    AffineConstraints<double> hanging(porosity_relevant);
    DoFTools::make_hanging_node_constraints(porosity_dof_handler, hanging);
    hanging.close();
    for (unsigned int l = 0; l < 3; ++l)
      {
        hanging.distribute(eps[l]);
        porosity_levels[l] = eps[l];
      }
    if (prm.momentum_source_as_field)
      {
        TrilinosWrappers::MPI::Vector source(source_owned, comm);
        source_transfer.interpolate(source);
        AffineConstraints<double> source_hanging(source_relevant);
        DoFTools::make_hanging_node_constraints(source_dof_handler, source_hanging);
        source_hanging.close();
        source_hanging.distribute(source);
        momentum_source_field = source;
      }
    // A porosity given as a function is exact on the new mesh too.
    if (coefficients.porosity && !prm.porosity_as_field)
      set_porosity_field();
  }

  FluidIntegrals VansSolver::integrals() const
  {
    const unsigned int k = prm.velocity_degree;
    const QGauss<2>    face_quadrature(k + 1);
    const QGauss<3>    quadrature(k + 1);
    FEFaceValues<3>    face_values(*mapping, fe, face_quadrature,
                                update_values | update_normal_vectors | update_quadrature_points |
                                  update_JxW_values);
    FEFaceValues<3> eps_face_values(*mapping, porosity_fe, face_quadrature, update_values);
    FEValues<3>     cell_values(*mapping, fe, quadrature, update_values | update_JxW_values);
    FEValues<3>     eps_values(*mapping, porosity_fe, quadrature, update_values);
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(3);

    // Per named boundary: area, integral of p, integral of eps u . n; then the
    // kinetic energy; then per boundary the integral of x (for centroids).
    const unsigned int  n_b = prm.boundaries.size();
    std::vector<double> sums(6 * n_b + 1, 0.);
    std::vector<Tensor<1, 3>> u(face_quadrature.size());
    std::vector<double>       p(face_quadrature.size()), eps(face_quadrature.size());
    std::vector<Tensor<1, 3>> uc(quadrature.size());
    std::vector<double>       epsc(quadrature.size());
    std::vector<int>          boundary_of_id(256, -1);
    // A periodic pair counts through its first face only: its two faces carry
    // the same flow with opposite signs.
    for (unsigned int b = 0; b < n_b; ++b)
      for (const auto id : prm.boundaries[b].ids)
        if (prm.boundaries[b].type != BoundaryType::periodic || id == prm.boundaries[b].ids[0])
          boundary_of_id[id] = b;

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const typename DoFHandler<3>::active_cell_iterator eps_cell(
          &triangulation, cell->level(), cell->index(), &porosity_dof_handler);
        cell_values.reinit(cell);
        eps_values.reinit(eps_cell);
        cell_values[velocities].get_function_values(present_solution, uc);
        eps_values.get_function_values(porosity_levels[0], epsc);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          sums[3 * n_b] += 0.5 * prm.density * epsc[q] * uc[q].norm_square() * cell_values.JxW(q);
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->at_boundary(f))
              continue;
            const int b = boundary_of_id[cell->face(f)->boundary_id()];
            if (b < 0)
              continue;
            face_values.reinit(cell, f);
            eps_face_values.reinit(eps_cell, f);
            face_values[velocities].get_function_values(present_solution, u);
            face_values[pressure].get_function_values(present_solution, p);
            eps_face_values.get_function_values(porosity_levels[0], eps);
            for (unsigned int q = 0; q < face_quadrature.size(); ++q)
              {
                const double dA = face_values.JxW(q);
                sums[3 * b] += dA;
                sums[3 * b + 1] += p[q] * dA;
                sums[3 * b + 2] += eps[q] * (u[q] * face_values.normal_vector(q)) * dA;
                for (unsigned int d = 0; d < 3; ++d)
                  sums[3 * n_b + 1 + 3 * b + d] += face_values.quadrature_point(q)[d] * dA;
              }
          }
      }
    Utilities::MPI::sum(sums, comm, sums);

    FluidIntegrals result;
    const auto mean_pressure = [&](const std::string &name) {
      const int b = prm.boundary_index(name);
      return sums[3 * b + 1] / sums[3 * b];
    };
    const auto centroid = [&](const std::string &name) {
      const int b = prm.boundary_index(name);
      Point<3>  c;
      for (unsigned int d = 0; d < 3; ++d)
        c[d] = sums[3 * n_b + 1 + 3 * b + d] / sums[3 * b];
      return c;
    };
    if (!prm.pressure_drop_between[0].empty())
      {
        result.pressure_drop = mean_pressure(prm.pressure_drop_between[0]) -
                               mean_pressure(prm.pressure_drop_between[1]);
        result.drop_distance =
          centroid(prm.pressure_drop_between[0]).distance(centroid(prm.pressure_drop_between[1]));
      }
    for (const auto &name : prm.flow_rate_through)
      result.flow_rates.push_back(sums[3 * prm.boundary_index(name) + 2]);
    result.kinetic_energy = sums[3 * n_b];
    return result;
  }

  FluidErrors VansSolver::errors(const Function<3> &exact) const
  {
    // Pressure is compared with its mean removed on both sides: the discrete
    // pressure is fixed at one node, the exact one is not.
    const QGauss<3> quadrature(prm.velocity_degree + 2);
    FEValues<3>     fe_values(*mapping, fe, quadrature,
                          update_values | update_quadrature_points | update_JxW_values);
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(3);
    std::vector<Tensor<1, 3>>        u(quadrature.size());
    std::vector<double>              p(quadrature.size());
    Vector<double>                   exact_values(4);

    // Pass 1: mean pressures; pass 2: errors.
    double sums[3] = {0., 0., 0.}; // volume, int p_h, int p
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[pressure].get_function_values(present_solution, p);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double dV = fe_values.JxW(q);
              sums[0] += dV;
              sums[1] += p[q] * dV;
              sums[2] += exact.value(fe_values.quadrature_point(q), 3) * dV;
            }
        }
    double global[3];
    MPI_Allreduce(sums, global, 3, MPI_DOUBLE, MPI_SUM, comm);
    const double shift = (global[1] - global[2]) / global[0];

    double e[2] = {0., 0.};
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(present_solution, u);
          fe_values[pressure].get_function_values(present_solution, p);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              exact.vector_value(fe_values.quadrature_point(q), exact_values);
              const double dV = fe_values.JxW(q);
              for (unsigned int d = 0; d < 3; ++d)
                e[0] += std::pow(u[q][d] - exact_values[d], 2) * dV;
              e[1] += std::pow(p[q] - shift - exact_values[3], 2) * dV;
            }
        }
    double ge[2];
    MPI_Allreduce(e, ge, 2, MPI_DOUBLE, MPI_SUM, comm);
    return {std::sqrt(ge[0]), std::sqrt(ge[1])};
  }
} // namespace sluice
