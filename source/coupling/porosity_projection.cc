// Kernel projection of the particles' solid fraction (see the header for the
// scheme and why it conserves volume exactly).

#include <sluice/coupling/porosity_projection.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/affine_constraints.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    /// K(xi) = (1 - xi^2)^4 for xi < 1 (Gao & Sun Eq. 24), unnormalised.
    double kernel(const double xi)
    {
      if (xi >= 1.)
        return 0.;
      const double a = 1. - xi * xi;
      return a * a * a * a;
    }
  } // namespace

  ProjectionReport project_solid_fraction(const DoFHandler<3>                  &dof_handler,
                                          const Mapping<3>                     &mapping,
                                          const std::vector<ProjectedParticle> &particles,
                                          const double                          support_radius,
                                          TrilinosWrappers::MPI::Vector        &solid_fraction,
                                          std::array<TrilinosWrappers::MPI::Vector, 3> *solid_velocity)
  {
    const auto &triangulation = dof_handler.get_triangulation();
    MPI_Comm    comm          = triangulation.get_communicator();
    const auto &fe            = dof_handler.get_fe();

    // The support must stay within the neighbours of the particle's cell.
    double smallest = std::numeric_limits<double>::max();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        smallest = std::min(smallest, cell->minimum_vertex_distance());
    smallest = Utilities::MPI::min(smallest, comm);
    if (support_radius > smallest * (1. + 1e-10))
      throw std::invalid_argument("the kernel support radius " + std::to_string(support_radius) +
                                  " m exceeds the smallest fluid cell (" +
                                  std::to_string(smallest) +
                                  " m); allowed: a radius up to the smallest cell size");

    const IndexSet owned = dof_handler.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    AffineConstraints<double> hanging(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, hanging);
    hanging.close();

    const QGauss<3> quadrature(fe.degree + 2);
    FEValues<3>     fe_values(mapping, fe, quadrature,
                          update_values | update_quadrature_points | update_JxW_values);
    const unsigned int n_q = quadrature.size(), n_dofs = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    Vector<double>                       cell_rhs(n_dofs);

    // b with writable ghost entries: deposits on ghost cells travel to their owners.
    TrilinosWrappers::MPI::Vector rhs;
    rhs.reinit(owned, relevant, comm, true);
    // The same deposits times each velocity component (solid momentum).
    std::array<TrilinosWrappers::MPI::Vector, 3> momentum_rhs;
    if (solid_velocity)
      for (auto &m : momentum_rhs)
        m.reinit(owned, relevant, comm, true);
    Tensor<1, 3> particle_momentum;
    // Adds a cell's deposit (volume weights in cell_rhs) for one particle.
    const auto deposit = [&](const ProjectedParticle &particle) {
      hanging.distribute_local_to_global(cell_rhs, dof_indices, rhs);
      if (solid_velocity)
        for (unsigned int d = 0; d < 3; ++d)
          {
            Vector<double> m(cell_rhs);
            m *= particle.velocity[d];
            hanging.distribute_local_to_global(m, dof_indices, momentum_rhs[d]);
          }
    };
    const auto vertex_to_cells = GridTools::vertex_to_cell_map(triangulation);

    double deposited = 0.;
    for (const auto &particle : particles)
      {
        const auto found = GridTools::find_active_cell_around_point(mapping, dof_handler,
                                                                    particle.position);
        const auto home = found.first;
        if (!home->is_locally_owned())
          throw std::invalid_argument("project_solid_fraction: a particle outside this rank's cells");
        std::set<typename DoFHandler<3>::active_cell_iterator> support;
        for (const unsigned int v : home->vertex_indices())
          for (const auto &c : vertex_to_cells[home->vertex_index(v)])
            support.insert(typename DoFHandler<3>::active_cell_iterator(&triangulation, c->level(),
                                                                        c->index(), &dof_handler));

        // Normalisation over the part of the support inside the domain.
        double total = 0.;
        for (const auto &cell : support)
          {
            fe_values.reinit(cell);
            for (unsigned int q = 0; q < n_q; ++q)
              total += kernel(fe_values.quadrature_point(q).distance(particle.position) /
                              support_radius) *
                       fe_values.JxW(q);
          }
        deposited += particle.volume;
        particle_momentum += particle.volume * particle.velocity;
        if (!(total > 0.))
          {
            // No quadrature point within reach (a support far below the cell
            // size): deposit at the centre, b_i = V_p phi_i(x_p).
            const Point<3> unit = found.second;
            for (unsigned int i = 0; i < n_dofs; ++i)
              cell_rhs(i) = particle.volume * fe.shape_value(i, unit);
            home->get_dof_indices(dof_indices);
            deposit(particle);
            continue;
          }
        for (const auto &cell : support)
          {
            fe_values.reinit(cell);
            cell_rhs = 0.;
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const double w = particle.volume *
                                 kernel(fe_values.quadrature_point(q).distance(particle.position) /
                                        support_radius) *
                                 fe_values.JxW(q) / total;
                if (w != 0.)
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    cell_rhs(i) += w * fe_values.shape_value(i, q);
              }
            cell->get_dof_indices(dof_indices);
            deposit(particle);
          }
      }
    rhs.compress(VectorOperation::add);
    if (solid_velocity)
      for (auto &m : momentum_rhs)
        m.compress(VectorOperation::add);

    // The lumped-mass projection s_i = b_i / m_i, m_i = integral of phi_i: local,
    // never negative (a consistent L2 projection rings near steep deposits and
    // can turn a solid fraction negative), and conservative, since the integral
    // of s_h is sum_i s_i m_i = sum_i b_i.
    TrilinosWrappers::MPI::Vector lumped;
    lumped.reinit(owned, relevant, comm, true);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_rhs = 0.;
          for (unsigned int q = 0; q < n_q; ++q)
            for (unsigned int i = 0; i < n_dofs; ++i)
              cell_rhs(i) += fe_values.shape_value(i, q) * fe_values.JxW(q);
          cell->get_dof_indices(dof_indices);
          hanging.distribute_local_to_global(cell_rhs, dof_indices, lumped);
        }
    lumped.compress(VectorOperation::add);
    solid_fraction.reinit(owned, comm);
    for (const auto i : owned)
      if (!hanging.is_constrained(i))
        solid_fraction[i] = rhs[i] / lumped[i];
    solid_fraction.compress(VectorOperation::insert);
    hanging.distribute(solid_fraction);

    ProjectionReport report;
    if (solid_velocity)
      for (unsigned int d = 0; d < 3; ++d)
        {
          auto &u = (*solid_velocity)[d];
          u.reinit(owned, comm);
          for (const auto i : owned)
            if (!hanging.is_constrained(i) && rhs[i] > 0.)
              {
                u[i] = momentum_rhs[d][i] / rhs[i];
                report.field_momentum[d] += lumped[i] * solid_fraction[i] * u[i];
              }
          u.compress(VectorOperation::insert);
          hanging.distribute(u);
        }
    report.field_momentum    = Utilities::MPI::sum(report.field_momentum, comm);
    report.particle_momentum = Utilities::MPI::sum(particle_momentum, comm);

    report.deposited_volume = Utilities::MPI::sum(deposited, comm);
    TrilinosWrappers::MPI::Vector ghosted(owned, relevant, comm);
    ghosted = solid_fraction;
    double              integral = 0.;
    std::vector<double> values(n_q);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(ghosted, values);
          for (unsigned int q = 0; q < n_q; ++q)
            integral += values[q] * fe_values.JxW(q);
        }
    report.field_integral = Utilities::MPI::sum(integral, comm);
    return report;
  }
} // namespace sluice
