// The fluid solution evaluated at arbitrary points (particle centres): velocity,
// pressure gradient, divergence of the viscous stress, porosity and its
// gradient, from the finite-element fields through the solver's mapping.

#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>

namespace sluice
{
  using namespace dealii;

  std::vector<FluidSample> VansSolver::sample(const std::vector<Point<3>> &points) const
  {
    std::vector<FluidSample>         samples(points.size());
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(3);
    std::vector<Tensor<1, 3>>        u(1), grad_p(1), grad_eps(1);
    std::vector<Tensor<2, 3>>        grad_u(1);
    std::vector<Tensor<3, 3>>        hess_u(1);
    std::vector<double>              eps(1);
    const double                     mu = prm.viscosity;

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
        const Quadrature<3> at(found.second);
        FEValues<3> values(*mapping, fe, at, update_values | update_gradients | update_hessians);
        values.reinit(found.first);
        values[velocities].get_function_values(present_solution, u);
        values[velocities].get_function_gradients(present_solution, grad_u);
        values[velocities].get_function_hessians(present_solution, hess_u);
        values[pressure].get_function_gradients(present_solution, grad_p);

        FluidSample &s = samples[n];
        s.found             = true;
        s.velocity          = u[0];
        s.pressure_gradient = grad_p[0];
        // div tau = mu (lap u + 1/3 grad div u) for tau = mu (grad u + grad u^T - 2/3 div u I).
        for (unsigned int i = 0; i < 3; ++i)
          {
            double lap = 0., grad_div = 0.;
            for (unsigned int j = 0; j < 3; ++j)
              {
                lap += hess_u[0][i][j][j];
                grad_div += hess_u[0][j][j][i];
              }
            s.viscous_divergence[i] = mu * (lap + grad_div / 3.);
          }

        FEValues<3> porosity_values(*mapping, porosity_fe, at, update_values | update_gradients);
        porosity_values.reinit(typename DoFHandler<3>::active_cell_iterator(
          &triangulation, found.first->level(), found.first->index(), &porosity_dof_handler));
        porosity_values.get_function_values(porosity_levels[0], eps);
        porosity_values.get_function_gradients(porosity_levels[0], grad_eps);
        s.porosity          = eps[0];
        s.porosity_gradient = grad_eps[0];
      }
    return samples;
  }
} // namespace sluice
