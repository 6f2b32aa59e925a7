// Assembly of the Newton system of the volume-averaged Navier-Stokes equations:
// the residual R(u, p) and, if asked, its Jacobian, on every locally owned cell.
//
// Weak form (doc/fluid.md), for test functions (v, q), with e = eps, and the
// model factor m = e (model A, Zhou et al. 2010 set II) or 1 (model B, set III):
//   momentum:   (rho e (du/dt + (grad u) u), v) + (m tau, grad v) - (p, m div v)
//               [model A: + (tau grad e, v) - (p, v . grad e)]
//               + (beta_m (u - u_s), v) - (f, v)
//               [semi-implicit exchange: + (beta_x (u - u^n), v)
//                                        - (beta_x' (u^n - u^n-1), v)]
//   continuity: (de/dt + e div u + u . grad e - s, q)
// with tau = mu (grad u + grad u^T - 2/3 div u I), beta_m = beta (model A) or
// beta / e (model B), f the body force, sources and driving pressure gradient.
// The semi-implicit exchange (coupled scenes, 'cfd-dem/semi-implicit drag';
// doc/coupling.md): beta_x is the particles' drag coefficient per volume, as
// deposited for this step, and beta_x' the one the last step applied; the
// second term returns the first's momentum one step later, so the sum over
// the steps is the last step's term alone, and the fluid still receives the
// particles' impulses (the explicit source in f) to round-off.
// Model A's viscous and pressure terms are eps div tau and -eps grad p
// integrated by parts against v; the traction-free boundary is natural.
//
// Stabilisation (residual based, Tezduyar 1992; Hughes, Franca & Balestra 1986):
//   + (tau_s R_m, grad q)                      PSPG
//   + (tau_s R_m, rho e (grad v) u)            SUPG
//   + (gamma R_c, e div v + v . grad e)        grad-div, optional
// with R_m, R_c the strong residuals and
//   tau_s = [ (2 rho e / dt)^2 + (2 rho e |u| / h)^2 + 9 (4 m mu / h^2)^2 + beta_m^2 ]^(-1/2).
// For degree-1 velocity the second derivatives in R_m are dropped (they vanish on
// affine cells), as is usual.
//
// Each velocity shape function has one non-zero component, so the Jacobian entry
// of test i (component c) and trial j is phi_i G_j[c] + grad phi_i . H_j[c] with
// G_j, H_j computed once per trial function: the double loop costs a few
// multiplications per entry.

#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cmath>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    Tensor<2, 3> identity()
    {
      Tensor<2, 3> t;
      for (unsigned int d = 0; d < 3; ++d)
        t[d][d] = 1.;
      return t;
    }

    /// The strong residuals at one quadrature point and the weights of the
    /// stabilised weak form built from them.
    struct PointResidual
    {
      double       e = 1., m = 1.;            // porosity and the model factor
      Tensor<1, 3> w;                         // slip against the solid (drag)
      double       beta = 0., b_slope = 0., w_norm = 0.;
      Tensor<1, 3> Rm;                        // strong momentum residual
      double       Rc = 0.;                   // strong continuity residual
      double       tau_s = 0., gamma = 0.;    // PSPG/SUPG and grad-div weights
      Tensor<1, 3> Gr, Pr;                    // tested with phi (velocity), grad q
      Tensor<2, 3> Hr;                        // tested with grad phi (velocity)
    };
  } // namespace

  /// The cell loop's state: the FEValues, the fields at the quadrature points
  /// of the current cell and the shape functions at the current point.
  template <bool porous>
  struct VansSolver::CellAssembler
  {
    CellAssembler(VansSolver &solver, bool assemble_matrix);

    /// Adds one cell's residual (and Jacobian) to the system.
    void assemble(const DoFHandler<3>::active_cell_iterator &cell);

  private:
    // (The per-point parts are inlined into the cell loop, as they were
    // written there: splitting them out must not cost time.)
    void solution_at(const DoFHandler<3>::active_cell_iterator &cell);
    void porosity_at(const DoFHandler<3>::active_cell_iterator &cell);
    void sources_at(const DoFHandler<3>::active_cell_iterator &cell);
    inline PointResidual residual_at(unsigned int q, double h) const;
    inline void          shapes_at(unsigned int q);
    inline void          add_residual(const PointResidual &r, unsigned int q, double JxW);
    inline void          add_jacobian(const PointResidual &r, unsigned int q, double JxW);

    VansSolver &s;
    const bool  assemble_matrix;

    const unsigned int k_u;
    const QGauss<3>    quadrature;
    const bool         second_derivatives;
    const bool         supg_advection_derivative; // VansSolver's switch, vans_solver.h
    FEValues<3>        fe_values, porosity_values, source_values;
    const FEValuesExtractors::Vector source_components{0}, velocities{0};
    const FEValuesExtractors::Scalar pressure{3};
    const unsigned int n_q, n_dofs;

    FullMatrix<double>                   cell_matrix;
    Vector<double>                       cell_rhs;
    std::vector<types::global_dof_index> dof_indices;

    // Solution and data at the quadrature points.
    std::vector<Tensor<1, 3>>   field_source, u, u_old, u_older, grad_p;
    std::vector<Tensor<2, 3>>   grad_u;
    std::vector<Tensor<3, 3>>   hess_u;
    std::vector<double>         p, eps, deps_dt, mass, eps_old, eps_older;
    std::vector<double>         exchange_beta, applied_beta; // the semi-implicit exchange
    std::vector<Tensor<1, 3>>   grad_eps;
    std::vector<Vector<double>> vector_values;
    std::vector<Tensor<1, 3>>   solid_velocity, source;

    // Per shape function: component, value, gradient, second-derivative parts.
    std::vector<unsigned int> component;
    std::vector<double>       phi, laplacian_phi;
    std::vector<Tensor<1, 3>> grad_phi, grad_div_phi;
    std::vector<Tensor<1, 3>> G, P;
    std::vector<Tensor<2, 3>> H;
    std::vector<double>       Rc_trial;

    // du/dt ~ c0 u^{n+1} + c1 u^n + c2 u^{n-1} (variable-step BDF).
    double             c0 = 0., c1 = 0., c2 = 0.;
    const bool         model_a;
    const bool         semi_implicit; // the exchange's drag in the matrix (transient only)
    const double       rho, mu;
    const double       t;
    Tensor<1, 3>       constant_force, driving;
  };

  template <bool porous>
  VansSolver::CellAssembler<porous>::CellAssembler(VansSolver &solver, const bool matrix)
    : s(solver), assemble_matrix(matrix), k_u(solver.prm.velocity_degree), quadrature(k_u + 1)
    , second_derivatives(solver.prm.stabilization && k_u > 1)
    , supg_advection_derivative(solver.supg_advection_derivative)
    , fe_values(*solver.mapping, solver.fe, quadrature,
                update_values | update_gradients | update_quadrature_points | update_JxW_values |
                  (second_derivatives ? update_hessians : update_default))
    , porosity_values(*solver.mapping, solver.porosity_fe, quadrature,
                      update_values | update_gradients)
    , source_values(*solver.mapping, solver.source_fe, quadrature, update_values)
    , n_q(quadrature.size()), n_dofs(solver.fe.n_dofs_per_cell()), cell_matrix(n_dofs, n_dofs)
    , cell_rhs(n_dofs), dof_indices(n_dofs), field_source(n_q), u(n_q), u_old(n_q), u_older(n_q)
    , grad_p(n_q), grad_u(n_q), hess_u(n_q), p(n_q), eps(n_q, 1.), deps_dt(n_q, 0.)
    , mass(n_q, 0.), eps_old(n_q), eps_older(n_q), exchange_beta(n_q, 0.), applied_beta(n_q, 0.)
    , grad_eps(n_q)
    , vector_values(n_q, Vector<double>(3)), solid_velocity(n_q), source(n_q), component(n_dofs)
    , phi(n_dofs), laplacian_phi(n_dofs), grad_phi(n_dofs), grad_div_phi(n_dofs), G(n_dofs)
    , P(n_dofs), H(n_dofs), Rc_trial(n_dofs)
    , model_a(solver.prm.formulation == VansFormulation::model_a)
    , semi_implicit(solver.prm.exchange_drag_as_field && !solver.steady), rho(solver.prm.density)
    , mu(solver.prm.viscosity), t(solver.current_time)
  {
    for (unsigned int k = 0; k < n_dofs; ++k)
      component[k] = s.fe.system_to_component_index(k).first;
    if (!s.steady)
      {
        const double dt = s.time_steps[0];
        if (s.prm.time_integration == TimeIntegration::bdf2 && s.n_steps_done >= 1)
          {
            const double w = dt / s.time_steps[1];
            c0 = (1. + 2. * w) / ((1. + w) * dt);
            c1 = -(1. + w) / dt;
            c2 = w * w / ((1. + w) * dt);
          }
        else
          {
            c0 = 1. / dt;
            c1 = -1. / dt;
          }
      }
    if (s.prm.use_gravity)
      constant_force += rho * s.gravity; // multiplied by eps below
    for (unsigned int d = 0; d < 3; ++d)
      driving[d] = -s.prm.driving_pressure_gradient[d];
  }

  template <bool porous>
  void VansSolver::CellAssembler<porous>::solution_at(const DoFHandler<3>::active_cell_iterator &cell)
  {
    fe_values.reinit(cell);
    fe_values[velocities].get_function_values(s.evaluation_point, u);
    fe_values[velocities].get_function_gradients(s.evaluation_point, grad_u);
    fe_values[pressure].get_function_values(s.evaluation_point, p);
    fe_values[pressure].get_function_gradients(s.evaluation_point, grad_p);
    if (second_derivatives)
      fe_values[velocities].get_function_hessians(s.evaluation_point, hess_u);
    if (!s.steady)
      {
        fe_values[velocities].get_function_values(s.old_solutions[0], u_old);
        if (c2 != 0. || semi_implicit)
          fe_values[velocities].get_function_values(s.old_solutions[1], u_older);
      }
  }

  /// Porosity, its gradient and its time derivative (same BDF as u).
  template <bool porous>
  void VansSolver::CellAssembler<porous>::porosity_at(const DoFHandler<3>::active_cell_iterator &cell)
  {
    const auto &x = fe_values.get_quadrature_points();
    if (s.prm.porosity_as_field)
      {
        const DoFHandler<3>::active_cell_iterator eps_cell(&s.triangulation, cell->level(),
                                                           cell->index(), &s.porosity_dof_handler);
        porosity_values.reinit(eps_cell);
        porosity_values.get_function_values(s.porosity_levels[0], eps);
        porosity_values.get_function_gradients(s.porosity_levels[0], grad_eps);
        if (!s.steady)
          {
            porosity_values.get_function_values(s.porosity_levels[1], eps_old);
            if (c2 != 0.)
              porosity_values.get_function_values(s.porosity_levels[2], eps_older);
          }
        if (semi_implicit)
          {
            porosity_values.get_function_values(s.exchange_drag, exchange_beta);
            porosity_values.get_function_values(s.applied_exchange_drag, applied_beta);
          }
      }
    else if (s.coefficients.porosity)
      {
        auto &f = *s.coefficients.porosity;
        f.set_time(t);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            eps[q]      = f.value(x[q]);
            grad_eps[q] = f.gradient(x[q]);
          }
        if (!s.steady)
          {
            f.set_time(t - s.time_steps[0]);
            for (unsigned int q = 0; q < n_q; ++q)
              eps_old[q] = f.value(x[q]);
            if (c2 != 0.)
              {
                f.set_time(t - s.time_steps[0] - s.time_steps[1]);
                for (unsigned int q = 0; q < n_q; ++q)
                  eps_older[q] = f.value(x[q]);
              }
            f.set_time(t);
          }
      }
    for (unsigned int q = 0; q < n_q; ++q)
      deps_dt[q] = s.steady ? 0. :
                              c0 * eps[q] + c1 * eps_old[q] + (c2 != 0. ? c2 * eps_older[q] : 0.);
  }

  /// The solid velocity (porous drag), the body force with the driving
  /// pressure gradient and the momentum source, and the mass source.
  template <bool porous>
  void VansSolver::CellAssembler<porous>::sources_at(const DoFHandler<3>::active_cell_iterator &cell)
  {
    const auto &x = fe_values.get_quadrature_points();
    const auto &c = s.coefficients;
    if (c.solid_velocity)
      {
        c.solid_velocity->set_time(t);
        c.solid_velocity->vector_value_list(x, vector_values);
        for (unsigned int q = 0; q < n_q; ++q)
          for (unsigned int d = 0; d < 3; ++d)
            solid_velocity[q][d] = vector_values[q][d];
      }
    for (unsigned int q = 0; q < n_q; ++q)
      source[q] = eps[q] * constant_force + (model_a ? eps[q] : 1.) * driving;
    if (s.prm.momentum_source_as_field)
      {
        const DoFHandler<3>::active_cell_iterator source_cell(&s.triangulation, cell->level(),
                                                              cell->index(),
                                                              &s.source_dof_handler);
        source_values.reinit(source_cell);
        source_values[source_components].get_function_values(s.momentum_source_field,
                                                             field_source);
        for (unsigned int q = 0; q < n_q; ++q)
          source[q] += field_source[q];
      }
    else if (c.momentum_source)
      {
        c.momentum_source->set_time(t);
        c.momentum_source->vector_value_list(x, vector_values);
        for (unsigned int q = 0; q < n_q; ++q)
          for (unsigned int d = 0; d < 3; ++d)
            source[q][d] += vector_values[q][d];
      }
    if (c.mass_source)
      {
        c.mass_source->set_time(t);
        c.mass_source->value_list(x, mass);
      }
    // The semi-implicit exchange returns the term the last step applied.
    if constexpr (porous)
      if (semi_implicit)
        for (unsigned int q = 0; q < n_q; ++q)
          source[q] += applied_beta[q] * (u_old[q] - u_older[q]);
  }

  template <bool porous>
  __attribute__((always_inline)) inline PointResidual VansSolver::CellAssembler<porous>::residual_at(const unsigned int q,
                                                               const double h) const
  {
    const FluidParameters &prm = s.prm;
    const Tensor<2, 3>     I   = identity();
    const double           rho = this->rho, mu = this->mu;
    PointResidual          r;
    const double          e = eps[q], m = model_a ? e : 1.;
    r.e                     = e;
    r.m                     = m;
    const Tensor<1, 3> &ge    = grad_eps[q];
    const Tensor<2, 3> &gu    = grad_u[q];
    const double        div_u = trace(gu);
    const Tensor<1, 3>  dudt =
      s.steady ? Tensor<1, 3>() :
                 c0 * u[q] + c1 * u_old[q] + (c2 != 0. ? c2 * u_older[q] : Tensor<1, 3>());
    const Tensor<1, 3> convection = gu * u[q];
    const Tensor<2, 3> tau = mu * (gu + transpose(gu)) - (2. / 3.) * mu * div_u * I;

    // Porous drag (Ergun): beta = a + b |w|, d(beta w)/du = beta I + b w (x) w / |w|.
    if constexpr (porous)
      {
        if (prm.drag == PorousDrag::ergun)
          {
            r.w      = u[q] - solid_velocity[q];
            r.w_norm = r.w.norm();
            const double d = prm.particle_diameter, sf = 1. - e;
            r.beta    = 150. * sf * sf * mu / (e * d * d) + 1.75 * sf * rho * r.w_norm / d;
            r.b_slope = 1.75 * sf * rho / d;
            if (!model_a)
              {
                r.beta /= e;
                r.b_slope /= e;
              }
          }
        else if (semi_implicit)
          {
            // The drag's part in u, beta_x (u - u^n): the Jacobian's beta term.
            r.beta = exchange_beta[q];
            r.w    = u[q] - u_old[q];
          }
      }

    Tensor<1, 3> viscous_strong;
    if (second_derivatives)
      for (unsigned int i = 0; i < 3; ++i)
        {
          double lap = 0., grad_div = 0.;
          for (unsigned int j = 0; j < 3; ++j)
            {
              lap += hess_u[q][i][j][j];
              grad_div += hess_u[q][j][j][i];
            }
          viscous_strong[i] = mu * (lap + grad_div / 3.);
        }

    r.Rm = rho * e * (dudt + convection) + m * grad_p[q] - m * viscous_strong + r.beta * r.w -
           source[q];
    r.Rc = deps_dt[q] + e * div_u - mass[q];
    if constexpr (porous)
      r.Rc += u[q] * ge;

    if (prm.stabilization)
      {
        const double transient = s.steady ? 0. : 2. * rho * e / s.time_steps[0];
        const double advective = 2. * rho * e * u[q].norm() / h;
        const double diffusive = 12. * m * mu / (h * h);
        r.tau_s = 1. / std::sqrt(transient * transient + advective * advective +
                                 diffusive * diffusive + r.beta * r.beta);
      }
    r.gamma = prm.grad_div > 0. ? prm.grad_div * (mu + rho * u[q].norm() * h) : 0.;

    // Residual, in the same G/H form: velocity test i of component c gets
    // phi_i Gr[c] + grad phi_i . Hr[c]; pressure test gets
    // phi_i Rc + grad phi_i . tau_s Rm.
    r.Gr = rho * e * (dudt + convection) + r.beta * r.w - source[q];
    r.Hr = m * tau - (m * p[q]) * I;
    if constexpr (porous)
      if (model_a)
        r.Gr += tau * ge - p[q] * ge;
    for (unsigned int c = 0; c < 3; ++c)
      r.Hr[c] += (r.tau_s * rho * e * r.Rm[c]) * u[q];
    if (r.gamma > 0.)
      {
        r.Hr += (r.gamma * e * r.Rc) * I;
        if constexpr (porous)
          r.Gr += (r.gamma * r.Rc) * ge;
      }
    r.Pr = r.tau_s * r.Rm;
    return r;
  }

  template <bool porous>
  __attribute__((always_inline)) inline void VansSolver::CellAssembler<porous>::shapes_at(const unsigned int q)
  {
    for (unsigned int k = 0; k < n_dofs; ++k)
      {
        phi[k]      = fe_values.shape_value_component(k, q, component[k]);
        grad_phi[k] = fe_values.shape_grad_component(k, q, component[k]);
        if (second_derivatives && component[k] < 3)
          {
            const Tensor<2, 3> hs = fe_values.shape_hessian_component(k, q, component[k]);
            laplacian_phi[k]      = trace(hs);
            grad_div_phi[k]       = hs[component[k]];
          }
      }
  }

  template <bool porous>
  __attribute__((always_inline)) inline void VansSolver::CellAssembler<porous>::add_residual(const PointResidual &r, unsigned int,
                                                       const double JxW)
  {
    for (unsigned int i = 0; i < n_dofs; ++i)
      {
        const unsigned int c   = component[i];
        const double       val = c < 3 ? phi[i] * r.Gr[c] + grad_phi[i] * r.Hr[c] :
                                         phi[i] * r.Rc + grad_phi[i] * r.Pr;
        cell_rhs(i) -= val * JxW;
      }
  }

  /// Derivatives of R_m, R_c and the Galerkin terms for each trial function,
  /// then the entries phi_i G_j[c] + grad phi_i . H_j[c].
  template <bool porous>
  __attribute__((always_inline)) inline void VansSolver::CellAssembler<porous>::add_jacobian(const PointResidual &r,
                                                       const unsigned int q, const double JxW)
  {
    const double        e = r.e, m = r.m;
    const Tensor<1, 3> &ge = grad_eps[q];
    const Tensor<2, 3> &gu = grad_u[q];
    const Tensor<2, 3>  I  = identity();
    const double        rho = this->rho, mu = this->mu, c0 = this->c0;
    const unsigned int  n_dofs = this->n_dofs;
    for (unsigned int j = 0; j < n_dofs; ++j)
      {
        const unsigned int cj = component[j];
        Tensor<1, 3>       dRm, g;
        Tensor<2, 3>       h_j;
        double             dRc = 0.;
        if (cj < 3)
          {
            const double        f  = phi[j];
            const Tensor<1, 3> &gf = grad_phi[j];
            Tensor<1, 3>        ej;
            ej[cj] = 1.;
            // (grad phi) u = e_cj (gf . u); (grad u) phi = f * column cj of grad u.
            Tensor<1, 3> linear_inertia = (c0 * f + gf * u[q]) * ej;
            for (unsigned int d = 0; d < 3; ++d)
              linear_inertia[d] += gu[d][cj] * f;
            dRm = rho * e * linear_inertia + r.beta * f * ej;
            if (r.b_slope > 0. && r.w_norm > 0.)
              dRm += (r.b_slope * r.w[cj] * f / r.w_norm) * r.w;
            g = dRm; // the Galerkin part tested with v (inertia and drag)
            if (second_derivatives)
              {
                Tensor<1, 3> v_strong = (mu * laplacian_phi[j]) * ej;
                v_strong += (mu / 3.) * grad_div_phi[j];
                dRm -= m * v_strong;
              }
            // tau(phi) = mu (e_cj (x) gf + gf (x) e_cj) - 2/3 mu gf[cj] I
            Tensor<2, 3> dtau = (-(2. / 3.) * mu * gf[cj]) * I;
            for (unsigned int d = 0; d < 3; ++d)
              {
                dtau[cj][d] += mu * gf[d];
                dtau[d][cj] += mu * gf[d];
              }
            h_j = m * dtau;
            dRc = e * gf[cj];
            if constexpr (porous)
              {
                dRc += f * ge[cj];
                if (model_a)
                  g += dtau * ge;
              }
          }
        else
          {
            const double f = phi[j];
            dRm            = m * grad_phi[j];
            h_j            = (-m * f) * I;
            if constexpr (porous)
              if (model_a)
                g = -f * ge;
          }
        // SUPG: tau_s rho e [((grad v) u) . dRm + ((grad v) phi_j) . Rm]
        const double supg = r.tau_s * rho * e;
        for (unsigned int c = 0; c < 3; ++c)
          h_j[c] += (supg * dRm[c]) * u[q];
        if (cj < 3 && supg_advection_derivative)
          for (unsigned int c = 0; c < 3; ++c)
            h_j[c][cj] += supg * r.Rm[c] * phi[j];
        if (r.gamma > 0.)
          {
            h_j += (r.gamma * e * dRc) * I;
            if constexpr (porous)
              g += (r.gamma * dRc) * ge;
          }
        G[j]        = g;
        H[j]        = h_j;
        P[j]        = r.tau_s * dRm;
        Rc_trial[j] = dRc;
      }

    for (unsigned int i = 0; i < n_dofs; ++i)
      {
        const unsigned int c  = component[i];
        const double       f  = phi[i] * JxW;
        const Tensor<1, 3> gf = grad_phi[i] * JxW;
        if (c < 3)
          for (unsigned int j = 0; j < n_dofs; ++j)
            cell_matrix(i, j) += f * G[j][c] + gf * H[j][c];
        else
          for (unsigned int j = 0; j < n_dofs; ++j)
            cell_matrix(i, j) += f * Rc_trial[j] + gf * P[j];
      }
  }

  template <bool porous>
  void VansSolver::CellAssembler<porous>::assemble(const DoFHandler<3>::active_cell_iterator &cell)
  {
    cell_matrix = 0.;
    cell_rhs    = 0.;
    solution_at(cell);
    if constexpr (porous)
      porosity_at(cell);
    sources_at(cell);
    const double h = std::cbrt(cell->measure()) / k_u;
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const PointResidual r   = residual_at(q, h);
        const double        JxW = fe_values.JxW(q);
        shapes_at(q);
        add_residual(r, q, JxW);
        if (assemble_matrix)
          add_jacobian(r, q, JxW);
      }
    cell->get_dof_indices(dof_indices);
    if (assemble_matrix)
      s.zero_constraints.distribute_local_to_global(cell_matrix, cell_rhs, dof_indices,
                                                    s.system_matrix, s.system_rhs);
    else
      s.zero_constraints.distribute_local_to_global(cell_rhs, dof_indices, s.system_rhs);
  }

  void VansSolver::assemble(const bool assemble_matrix)
  {
    if (coefficients.porosity || prm.drag != PorousDrag::none || prm.porosity_as_field)
      assemble_cells<true>(assemble_matrix);
    else
      assemble_cells<false>(assemble_matrix);
  }

  template <bool porous>
  void VansSolver::assemble_cells(const bool assemble_matrix)
  {
    CellAssembler<porous> assembler(*this, assemble_matrix);
    if (assemble_matrix)
      system_matrix = 0.;
    system_rhs = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        assembler.assemble(cell);
    if (assemble_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
  }

  template void VansSolver::assemble_cells<true>(bool);
  template void VansSolver::assemble_cells<false>(bool);
} // namespace sluice
