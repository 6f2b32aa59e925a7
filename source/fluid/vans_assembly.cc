// Assembly of the Newton system of the volume-averaged Navier-Stokes equations:
// the residual R(u, p) and, if asked, its Jacobian, on every locally owned cell.
//
// Weak form (doc/fluid.md), for test functions (v, q), with e = eps, and the
// model factor m = e (model A, Zhou et al. 2010 set II) or 1 (model B, set III):
//   momentum:   (rho e (du/dt + (grad u) u), v) + (m tau, grad v) - (p, m div v)
//               [model A: + (tau grad e, v) - (p, v . grad e)]
//               + (beta_m (u - u_s), v) - (f, v)
//   continuity: (de/dt + e div u + u . grad e - s, q)
// with tau = mu (grad u + grad u^T - 2/3 div u I), beta_m = beta (model A) or
// beta / e (model B), f the body force, sources and driving pressure gradient.
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
  } // namespace

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
    const unsigned int k_u = prm.velocity_degree;
    const QGauss<3>    quadrature(k_u + 1);
    const bool         second_derivatives = prm.stabilization && k_u > 1;
    UpdateFlags        flags = update_values | update_gradients | update_quadrature_points |
                        update_JxW_values;
    if (second_derivatives)
      flags |= update_hessians;
    FEValues<3> fe_values(*mapping, fe, quadrature, flags);
    FEValues<3> porosity_values(*mapping, porosity_fe, quadrature, update_values | update_gradients);
    FEValues<3> source_values(*mapping, source_fe, quadrature, update_values);
    const FEValuesExtractors::Vector source_components(0);
    std::vector<Tensor<1, 3>>        field_source(quadrature.size());

    const unsigned int n_q = quadrature.size(), n_dofs = fe.n_dofs_per_cell();
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(3);

    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs);
    Vector<double>                       cell_rhs(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);

    // Solution and data at the quadrature points.
    std::vector<Tensor<1, 3>> u(n_q), u_old(n_q), u_older(n_q), grad_p(n_q);
    std::vector<Tensor<2, 3>> grad_u(n_q);
    std::vector<Tensor<3, 3>> hess_u(n_q);
    std::vector<double>       p(n_q);
    std::vector<double>       eps(n_q, 1.), deps_dt(n_q, 0.), mass(n_q, 0.);
    std::vector<double>       eps_old(n_q), eps_older(n_q);
    std::vector<Tensor<1, 3>> grad_eps(n_q);
    std::vector<Vector<double>> vector_values(n_q, Vector<double>(3));
    std::vector<Tensor<1, 3>> solid_velocity(n_q), source(n_q);

    // Per shape function: component, value, gradient, second-derivative parts.
    std::vector<unsigned int> component(n_dofs);
    for (unsigned int k = 0; k < n_dofs; ++k)
      component[k] = fe.system_to_component_index(k).first;
    std::vector<double>       phi(n_dofs), laplacian_phi(n_dofs);
    std::vector<Tensor<1, 3>> grad_phi(n_dofs), grad_div_phi(n_dofs);
    std::vector<Tensor<1, 3>> G(n_dofs), P(n_dofs);
    std::vector<Tensor<2, 3>> H(n_dofs);
    std::vector<double>       Rc_trial(n_dofs);

    // Time derivative du/dt ~ c0 u^{n+1} + c1 u^n + c2 u^{n-1} (variable-step BDF).
    double c0 = 0., c1 = 0., c2 = 0.;
    if (!steady)
      {
        const double dt = time_steps[0];
        if (prm.time_integration == TimeIntegration::bdf2 && n_steps_done >= 1)
          {
            const double w = dt / time_steps[1];
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
    const bool   model_a = prm.formulation == VansFormulation::model_a;
    const double rho = prm.density, mu = prm.viscosity;
    const Tensor<2, 3> I = identity();
    const double t = current_time;

    Tensor<1, 3> constant_force;
    if (prm.use_gravity)
      constant_force += rho * gravity; // multiplied by eps below
    Tensor<1, 3> driving;
    for (unsigned int d = 0; d < 3; ++d)
      driving[d] = -prm.driving_pressure_gradient[d];

    if (assemble_matrix)
      system_matrix = 0.;
    system_rhs = 0.;

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        fe_values.reinit(cell);
        cell_matrix = 0.;
        cell_rhs    = 0.;

        fe_values[velocities].get_function_values(evaluation_point, u);
        fe_values[velocities].get_function_gradients(evaluation_point, grad_u);
        fe_values[pressure].get_function_values(evaluation_point, p);
        fe_values[pressure].get_function_gradients(evaluation_point, grad_p);
        if (second_derivatives)
          fe_values[velocities].get_function_hessians(evaluation_point, hess_u);
        if (!steady)
          {
            fe_values[velocities].get_function_values(old_solutions[0], u_old);
            if (c2 != 0.)
              fe_values[velocities].get_function_values(old_solutions[1], u_older);
          }
        const auto &x = fe_values.get_quadrature_points();

        // Porosity, its gradient and its time derivative (same BDF as u).
        if constexpr (porous)
          {
            if (prm.porosity_as_field)
              {
                const typename DoFHandler<3>::active_cell_iterator eps_cell(
                  &triangulation, cell->level(), cell->index(), &porosity_dof_handler);
                porosity_values.reinit(eps_cell);
                porosity_values.get_function_values(porosity_levels[0], eps);
                porosity_values.get_function_gradients(porosity_levels[0], grad_eps);
                if (!steady)
                  {
                    porosity_values.get_function_values(porosity_levels[1], eps_old);
                    if (c2 != 0.)
                      porosity_values.get_function_values(porosity_levels[2], eps_older);
                  }
              }
            else if (coefficients.porosity)
              {
                auto &f = *coefficients.porosity;
                f.set_time(t);
                for (unsigned int q = 0; q < n_q; ++q)
                  {
                    eps[q]      = f.value(x[q]);
                    grad_eps[q] = f.gradient(x[q]);
                  }
                if (!steady)
                  {
                    f.set_time(t - time_steps[0]);
                    for (unsigned int q = 0; q < n_q; ++q)
                      eps_old[q] = f.value(x[q]);
                    if (c2 != 0.)
                      {
                        f.set_time(t - time_steps[0] - time_steps[1]);
                        for (unsigned int q = 0; q < n_q; ++q)
                          eps_older[q] = f.value(x[q]);
                      }
                    f.set_time(t);
                  }
              }
            for (unsigned int q = 0; q < n_q; ++q)
              deps_dt[q] = steady ? 0. :
                                    c0 * eps[q] + c1 * eps_old[q] + (c2 != 0. ? c2 * eps_older[q] : 0.);
          }
        if (coefficients.solid_velocity)
          {
            coefficients.solid_velocity->set_time(t);
            coefficients.solid_velocity->vector_value_list(x, vector_values);
            for (unsigned int q = 0; q < n_q; ++q)
              for (unsigned int d = 0; d < 3; ++d)
                solid_velocity[q][d] = vector_values[q][d];
          }
        for (unsigned int q = 0; q < n_q; ++q)
          source[q] = eps[q] * constant_force + (model_a ? eps[q] : 1.) * driving;
        if (prm.momentum_source_as_field)
          {
            const typename DoFHandler<3>::active_cell_iterator source_cell(
              &triangulation, cell->level(), cell->index(), &source_dof_handler);
            source_values.reinit(source_cell);
            source_values[source_components].get_function_values(momentum_source_field,
                                                                 field_source);
            for (unsigned int q = 0; q < n_q; ++q)
              source[q] += field_source[q];
          }
        else if (coefficients.momentum_source)
          {
            coefficients.momentum_source->set_time(t);
            coefficients.momentum_source->vector_value_list(x, vector_values);
            for (unsigned int q = 0; q < n_q; ++q)
              for (unsigned int d = 0; d < 3; ++d)
                source[q][d] += vector_values[q][d];
          }
        if (coefficients.mass_source)
          {
            coefficients.mass_source->set_time(t);
            coefficients.mass_source->value_list(x, mass);
          }

        const double h = std::cbrt(cell->measure()) / k_u;

        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double e = eps[q], m = model_a ? e : 1.;
            const Tensor<1, 3> &ge = grad_eps[q];
            const Tensor<2, 3> &gu = grad_u[q];
            const double        div_u = trace(gu);
            const Tensor<1, 3>  dudt =
              steady ? Tensor<1, 3>() :
                       c0 * u[q] + c1 * u_old[q] + (c2 != 0. ? c2 * u_older[q] : Tensor<1, 3>());
            const Tensor<1, 3> convection = gu * u[q];
            const Tensor<2, 3> tau = mu * (gu + transpose(gu)) - (2. / 3.) * mu * div_u * I;

            // Porous drag (Ergun): beta = a + b |w|, d(beta w)/du = beta I + b w (x) w / |w|.
            Tensor<1, 3> w;
            double       beta = 0., b_slope = 0., w_norm = 0.;
            if constexpr (porous)
              if (prm.drag == PorousDrag::ergun)
                {
                  w      = u[q] - solid_velocity[q];
                  w_norm = w.norm();
                  const double d = prm.particle_diameter, s = 1. - e;
                  beta    = 150. * s * s * mu / (e * d * d) + 1.75 * s * rho * w_norm / d;
                  b_slope = 1.75 * s * rho / d;
                  if (!model_a)
                    {
                      beta /= e;
                      b_slope /= e;
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

            const Tensor<1, 3> Rm = rho * e * (dudt + convection) + m * grad_p[q] -
                                    m * viscous_strong + beta * w - source[q];
            double Rc = deps_dt[q] + e * div_u - mass[q];
            if constexpr (porous)
              Rc += u[q] * ge;

            double tau_s = 0.;
            if (prm.stabilization)
              {
                const double transient = steady ? 0. : 2. * rho * e / time_steps[0];
                const double advective = 2. * rho * e * u[q].norm() / h;
                const double diffusive = 12. * m * mu / (h * h);
                tau_s = 1. / std::sqrt(transient * transient + advective * advective +
                                       diffusive * diffusive + beta * beta);
              }
            const double gamma =
              prm.grad_div > 0. ? prm.grad_div * (mu + rho * u[q].norm() * h) : 0.;
            const double JxW = fe_values.JxW(q);

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

            // Residual, in the same G/H form: velocity test i of component c gets
            // phi_i Gr[c] + grad phi_i . Hr[c]; pressure test gets
            // phi_i Rc + grad phi_i . tau_s Rm.
            Tensor<1, 3> Gr = rho * e * (dudt + convection) + beta * w - source[q];
            Tensor<2, 3> Hr = m * tau - (m * p[q]) * I;
            if constexpr (porous)
              if (model_a)
                Gr += tau * ge - p[q] * ge;
            for (unsigned int c = 0; c < 3; ++c)
              Hr[c] += (tau_s * rho * e * Rm[c]) * u[q];
            if (gamma > 0.)
              {
                Hr += (gamma * e * Rc) * I;
                if constexpr (porous)
                  Gr += (gamma * Rc) * ge;
              }
            const Tensor<1, 3> Pr = tau_s * Rm;
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                const unsigned int c = component[i];
                const double       r = c < 3 ? phi[i] * Gr[c] + grad_phi[i] * Hr[c] :
                                               phi[i] * Rc + grad_phi[i] * Pr;
                cell_rhs(i) -= r * JxW;
              }

            if (!assemble_matrix)
              continue;

            // Derivatives of R_m, R_c and the Galerkin terms for each trial function.
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
                    dRm = rho * e * linear_inertia + beta * f * ej;
                    if (b_slope > 0. && w_norm > 0.)
                      dRm += (b_slope * w[cj] * f / w_norm) * w;
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
                const double supg = tau_s * rho * e;
                for (unsigned int c = 0; c < 3; ++c)
                  h_j[c] += (supg * dRm[c]) * u[q];
                if (cj < 3)
                  for (unsigned int c = 0; c < 3; ++c)
                    h_j[c][cj] += supg * Rm[c] * phi[j];
                if (gamma > 0.)
                  {
                    h_j += (gamma * e * dRc) * I;
                    if constexpr (porous)
                      g += (gamma * dRc) * ge;
                  }
                G[j]        = g;
                H[j]        = h_j;
                P[j]        = tau_s * dRm;
                Rc_trial[j] = dRc;
              }

            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                const unsigned int  c  = component[i];
                const double        f  = phi[i] * JxW;
                const Tensor<1, 3>  gf = grad_phi[i] * JxW;
                if (c < 3)
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += f * G[j][c] + gf * H[j][c];
                else
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += f * Rc_trial[j] + gf * P[j];
              }
          }

        cell->get_dof_indices(dof_indices);
        if (assemble_matrix)
          zero_constraints.distribute_local_to_global(cell_matrix, cell_rhs, dof_indices,
                                                      system_matrix, system_rhs);
        else
          zero_constraints.distribute_local_to_global(cell_rhs, dof_indices, system_rhs);
      }
    if (assemble_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
  }

  template void VansSolver::assemble_cells<true>(bool);
  template void VansSolver::assemble_cells<false>(bool);
} // namespace sluice
