// The fluid solution evaluated at arbitrary points (particle centres): velocity
// and its gradient, pressure gradient, divergence of the viscous stress,
// porosity and its gradient, from the finite-element fields through the
// solver's mapping. The coupling calls sample_cell() once per cell for all the
// particles in it; sample() locates each point first (tests, probes).

#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>

namespace sluice
{
  using namespace dealii;

  void VansSolver::sample_cell(const Triangulation<3>::active_cell_iterator &cell,
                               const std::vector<Point<3>>                  &reference_points,
                               std::vector<FluidSample>                     &out,
                               const bool viscous_divergence) const
  {
    const unsigned int n = reference_points.size();
    out.assign(n, FluidSample());
    if (n == 0)
      return;
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(3);
    std::vector<Tensor<1, 3>>        u(n), grad_p(n), grad_eps(n);
    std::vector<Tensor<2, 3>>        grad_u(n);
    std::vector<Tensor<3, 3>>        hess_u(n);
    std::vector<double>              eps(n);
    const double                     mu = prm.viscosity;

    const Quadrature<3> at(reference_points);
    FEValues<3> values(*mapping, fe, at,
                       update_values | update_gradients |
                         (viscous_divergence ? update_hessians : update_default));
    values.reinit(typename DoFHandler<3>::active_cell_iterator(&triangulation, cell->level(),
                                                               cell->index(), &dof_handler));
    values[velocities].get_function_values(present_solution, u);
    values[velocities].get_function_gradients(present_solution, grad_u);
    if (viscous_divergence)
      values[velocities].get_function_hessians(present_solution, hess_u);
    values[pressure].get_function_gradients(present_solution, grad_p);

    FEValues<3> porosity_values(*mapping, porosity_fe, at, update_values | update_gradients);
    porosity_values.reinit(typename DoFHandler<3>::active_cell_iterator(
      &triangulation, cell->level(), cell->index(), &porosity_dof_handler));
    porosity_values.get_function_values(porosity_levels[0], eps);
    porosity_values.get_function_gradients(porosity_levels[0], grad_eps);

    for (unsigned int k = 0; k < n; ++k)
      {
        FluidSample &s      = out[k];
        s.found             = true;
        s.velocity          = u[k];
        s.velocity_gradient = grad_u[k];
        s.pressure_gradient = grad_p[k];
        // div tau = mu (lap u + 1/3 grad div u) for tau = mu (grad u + grad u^T - 2/3 div u I);
        // without the second derivatives it stays zero.
        if (viscous_divergence)
          for (unsigned int i = 0; i < 3; ++i)
            {
              double lap = 0., grad_div = 0.;
              for (unsigned int j = 0; j < 3; ++j)
                {
                  lap += hess_u[k][i][j][j];
                  grad_div += hess_u[k][j][j][i];
                }
              s.viscous_divergence[i] = mu * (lap + grad_div / 3.);
            }
        s.porosity          = eps[k];
        s.porosity_gradient = grad_eps[k];
      }
  }

  std::vector<FluidSample> VansSolver::sample(const std::vector<Point<3>> &points) const
  {
    std::vector<FluidSample> samples(points.size()), one;
    for (unsigned int n = 0; n < points.size(); ++n)
      {
        std::pair<typename DoFHandler<3>::active_cell_iterator, Point<3>> found;
        try
          {
            found = GridTools::find_active_cell_around_point(*mapping, dof_handler, points[n]);
          }
        catch (const std::exception &)
          {
            continue; // outside the mesh
          }
        if (found.first.state() != IteratorState::valid || !found.first->is_locally_owned())
          continue;
        sample_cell(found.first, {found.second}, one, true);
        samples[n] = one[0];
      }
    return samples;
  }
} // namespace sluice
