#pragma once
// The volume-averaged Navier-Stokes solver: stabilised equal- or mixed-order
// finite elements on a distributed hex mesh (p4est), Newton's method for the
// convection and drag terms, GMRES with ILU or AMG from Trilinos, BDF1/BDF2 in
// time, Kelly-driven adaptivity with solution transfer. Equations and weak form:
// doc/fluid.md.

#include <sluice/core/fluid_parameters.h>
#include <sluice/fluid/fluid_reports.h>

#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sluice
{
  /// The data fields of one fluid problem. A null pointer means "identically
  /// zero" (sources, solid velocity) or "identically one" (porosity), and the
  /// assembly then skips the term altogether.
  struct FluidCoefficients
  {
    std::shared_ptr<dealii::Function<3>> porosity;         // 1 component, gradient needed
    std::shared_ptr<dealii::Function<3>> solid_velocity;   // 3 components
    std::shared_ptr<dealii::Function<3>> momentum_source;  // 3 components [N/m^3]
    std::shared_ptr<dealii::Function<3>> mass_source;      // 1 component [1/s]
    std::shared_ptr<dealii::Function<3>> initial_velocity; // 3 components
    /// One 4-component function (u, v, w, unused) per boundary condition of type
    /// 'velocity', in the order of FluidParameters::boundaries; null elsewhere.
    std::vector<std::shared_ptr<dealii::Function<3>>> boundary_velocity;
  };

  struct FluidErrors
  {
    double velocity_l2 = 0., pressure_l2 = 0.; // pressure: both sides with their mean removed
  };

  /// The fluid at one point, for the forces on a particle there.
  struct FluidSample
  {
    bool                 found = false; // the point lies in a locally owned cell
    dealii::Tensor<1, 3> velocity;
    dealii::Tensor<2, 3> velocity_gradient; // [i][j] = d u_i / d x_j
    dealii::Tensor<1, 3> pressure_gradient;
    dealii::Tensor<1, 3> viscous_divergence; // div tau (zero second derivatives for Q1 cells)
    double               porosity = 1.;
    dealii::Tensor<1, 3> porosity_gradient;
  };


  class VansSolver
  {
  public:
    VansSolver(const FluidParameters &parameters, const FluidCoefficients &coefficients,
               const dealii::Tensor<1, 3> &gravity, const std::string &file_name,
               MPI_Comm communicator);
    ~VansSolver();

    /// Builds the mesh (checking its boundary ids against the .prm), the
    /// degrees of freedom and the initial state at time t0. Throws InputError for
    /// a mesh that does not match the boundary conditions; writes nothing.
    void initialize(double t0);

    /// Writes the state a time-dependent run needs to go on: the mesh (p4est),
    /// the solution and its two older time levels, the porosity levels, the
    /// momentum-source field, and (in <base>.state) time, step sizes, step
    /// count and 'extra' lines the caller wants back. Files: <base>.mesh*,
    /// <base>.state; written under a temporary name and renamed, so an
    /// interrupted write leaves the previous checkpoint intact.
    void save_checkpoint(const std::string &base, const std::vector<std::string> &extra) const;

    /// The next linear solve builds its preconditioner afresh instead of
    /// reusing the last one. A coupled scene calls it at each checkpoint: a
    /// run restarted from there has no preconditioner to reuse, and the
    /// uninterrupted run then solves with the same one (bit for bit).
    void rebuild_preconditioner() { preconditioner.reset(); }

    /// Instead of (or after) initialize(): rebuilds the coarse mesh from the
    /// .prm, loads the refined mesh and the state, and returns the 'extra'
    /// lines. Throws InputError, naming 'entry' (the one that asked for the
    /// restart), if the checkpoint is missing or does not fit the scene.
    std::vector<std::string> load_checkpoint(const std::string &base,
                                             const std::string &entry = "fluid time/restart from");

    /// Solves the steady equations by Newton's method.
    NewtonReport solve_steady();

    /// Advances by one step of size dt with BDF1 or BDF2 (BDF1 on the first).
    NewtonReport advance(double dt);

    /// Refines and coarsens with the Kelly estimator, moves every solution
    /// vector to the new mesh and repartitions it.
    void adapt_mesh();

    /// Refines every cell once (for convergence studies).
    void refine_globally();

    FluidIntegrals integrals() const;

    /// The fluid at each point that lies in a locally owned cell (the others
    /// come back with found = false): what the coupling interpolates at the
    /// particles. The porosity is the field's (the expression interpolated, or
    /// what set_porosity() gave).
    std::vector<FluidSample> sample(const std::vector<dealii::Point<3>> &points) const;
    /// The same for points given by their reference coordinates in one locally
    /// owned cell (of the triangulation below), all evaluated with one FEValues:
    /// what the coupling calls for the particles a ParticleHandler has sorted
    /// into cells. 'out' gets one sample per point; its viscous_divergence
    /// (second derivatives) only with 'viscous_divergence'.
    void sample_cell(const dealii::Triangulation<3>::active_cell_iterator &cell,
                     const std::vector<dealii::Point<3>> &reference_points,
                     std::vector<FluidSample> &out, bool viscous_divergence) const;
    FluidErrors    errors(const dealii::Function<3> &exact_solution) const;

    /// Writes <base>_<step>.pvtu (+ one .vtu per rank) with velocity, pressure
    /// and porosity; returns the .pvtu name relative to the directory.
    std::string write_vtu(const std::string &directory, const std::string &base,
                          unsigned int step) const;

    /// The coupling's entry points: the porosity field (FE_Q of the velocity
    /// degree, used by the assembly with 'porosity as field') and the momentum
    /// source field [N/m^3] (FE_Q^3, used when 'momentum source as field').
    /// Both take locally owned vectors on these DoF handlers. The porosity set
    /// becomes the porosity at the end of the next advance() (its time
    /// derivative is taken against the previous level); the source is used
    /// from the next assembly on.
    const dealii::DoFHandler<3> &porosity_dofs() const { return porosity_dof_handler; }
    const dealii::DoFHandler<3> &momentum_source_dofs() const { return source_dof_handler; }
    void set_porosity(const dealii::TrilinosWrappers::MPI::Vector &owned_porosity);
    /// The porosity at the start (all time levels, so no spurious d eps/dt).
    void set_initial_porosity(const dealii::TrilinosWrappers::MPI::Vector &owned_porosity);
    void set_momentum_source(const dealii::TrilinosWrappers::MPI::Vector &owned_source);
    /// With 'exchange_drag_as_field': the particles' drag coefficients per
    /// volume beta [kg/(m^3 s)] on the porosity dofs, for the next advance(),
    /// which adds beta (u - u^n) to the momentum equation and returns the last
    /// step's beta (u^n - u^n-1) as a source (the semi-implicit exchange).
    void set_exchange_drag(const dealii::TrilinosWrappers::MPI::Vector &owned_beta);

    const dealii::parallel::distributed::Triangulation<3> &get_triangulation() const
    {
      return triangulation;
    }
    const dealii::Mapping<3> &get_mapping() const { return *mapping; }
    const FluidParameters    &parameters() const { return prm; }

    double                    time() const { return current_time; }
    unsigned int              steps_done() const { return n_steps_done; }
    dealii::types::global_dof_index n_dofs() const;
    dealii::types::global_cell_index n_active_cells() const;

  private:
    void setup_dofs();
    /// What depends on the mesh alone (the pressure reference, the hanging,
    /// periodic and slip constraints, and the homogeneous set), once per mesh.
    void make_mesh_constraints();
    /// The inhomogeneous set at the current time (an inlet may ramp).
    void make_constraints();
    void build_constraints(bool homogeneous, dealii::AffineConstraints<double> &c) const;
    void set_porosity_field();
    void set_momentum_source_field();
    void assemble(bool assemble_matrix);
    template <bool porous>
    void assemble_cells(bool assemble_matrix);
    template <bool porous>
    struct CellAssembler; // vans_assembly.cc
    unsigned int solve_linear(NewtonReport &report);
    bool         preconditioner_broke_down() const;
    void         solve_for_update(NewtonReport &report);
    SolverFailure linear_solve_failure(bool breakdown) const;
    NewtonReport newton();
    void         apply_boundary_values();
    void         adapt_mesh_with_flags();

    const FluidParameters   &prm;
    FluidCoefficients        coefficients;
    const dealii::Tensor<1, 3> gravity;
    const std::string        file_name;
    MPI_Comm                 comm;

    dealii::parallel::distributed::Triangulation<3> triangulation;
    // Degree 1 on meshes of straight-sided cells; the velocity degree where
    // boundaries are curved (cylinder, channel with cylinder, gmsh meshes), so
    // that the geometry is not the largest error.
    std::unique_ptr<dealii::Mapping<3>>             mapping;
    dealii::FESystem<3>                             fe;
    dealii::DoFHandler<3>                           dof_handler;
    dealii::IndexSet                                owned, relevant;
    dealii::AffineConstraints<double>               zero_constraints, nonzero_constraints;
    // Kept while the mesh is unchanged (make_mesh_constraints): hanging and
    // periodic (not closed), and the slip walls' no-normal-flux.
    dealii::AffineConstraints<double> hanging_and_periodic, slip_constraints;
    bool                              has_slip = false;

    // Porosity as a finite-element field (when asked for, and for the Kelly
    // indicator): same mesh, FE_Q of the velocity degree.
    dealii::FE_Q<3>       porosity_fe;
    dealii::DoFHandler<3> porosity_dof_handler;
    dealii::IndexSet      porosity_owned, porosity_relevant;
    std::array<dealii::TrilinosWrappers::MPI::Vector, 3> porosity_levels; // t^{n+1}, t^n, t^{n-1}
    dealii::TrilinosWrappers::MPI::Vector next_porosity; // owned, from set_porosity()
    bool                                  porosity_from_caller = false;

    // Momentum source as a finite-element field (particle reaction forces).
    dealii::FESystem<3>                   source_fe;
    dealii::DoFHandler<3>                 source_dof_handler;
    dealii::IndexSet                      source_owned, source_relevant;
    dealii::TrilinosWrappers::MPI::Vector momentum_source_field; // ghosted

    // The semi-implicit exchange's drag coefficient per volume (porosity dofs,
    // ghosted): for the coming step, and the one the last step applied (zero
    // before the first), whose term the coming step returns.
    dealii::TrilinosWrappers::MPI::Vector exchange_drag, applied_exchange_drag;

    dealii::TrilinosWrappers::SparseMatrix system_matrix;
    dealii::TrilinosWrappers::MPI::Vector  present_solution; // ghosted
    dealii::TrilinosWrappers::MPI::Vector  evaluation_point; // ghosted, Newton's trial state
    std::array<dealii::TrilinosWrappers::MPI::Vector, 2> old_solutions; // u^n, u^{n-1}, ghosted
    dealii::TrilinosWrappers::MPI::Vector  system_rhs;       // owned: minus the residual
    dealii::TrilinosWrappers::MPI::Vector  newton_update;    // owned

    std::unique_ptr<dealii::TrilinosWrappers::PreconditionBase> preconditioner;
    unsigned int iterations_after_build = 0;
    // Whether the Jacobian holds SUPG's derivative in its advecting velocity,
    // tau_s rho e ((grad v) phi_j) . R_m. Far from equilibrium (water at rest
    // from p = 0: R_m = -rho e g) it outweighs the viscous term some
    // rho^2 |g| h^3 / (12 mu^2)-fold and ILU meets zero pivots; a Newton solve
    // whose GMRES fails with a fresh preconditioner drops it and goes on as a
    // Picard iteration in that velocity. Reset at every Newton solve.
    bool supg_advection_derivative = true;
    bool picard_start_reported     = false; // the console note, once per run

    double                current_time = 0.;
    std::array<double, 2> time_steps{{0., 0.}}; // dt^{n+1}, dt^n
    unsigned int          n_steps_done = 0;
    bool                  steady       = true;
    dealii::types::global_dof_index pressure_reference_dof = dealii::numbers::invalid_dof_index;
  };
} // namespace sluice
