// The kernel projection of the solid fraction (include/sluice/coupling/
// porosity_projection.h), on 1 or more MPI ranks:
//  - conservation: the integral of the projected field equals the particles'
//    total volume to round-off (CG tolerance 1e-14), with particles touching
//    every wall and corner of the box, on a uniform and on a locally refined mesh
//    (hanging nodes);
//  - a uniform suspension (a lattice of particles filling the box, walls
//    included, 2.5 particles per kernel radius) gives a field within 2e-3 of the
//    uniform solid fraction at nodes more than a kernel radius from the walls
//    (measured 6e-4); within a radius of a wall the renormalised kernels of the
//    wall particles put up to 11.5% more there (asserted below 15%: the known
//    price of conserving volume at a wall without image particles); the field
//    is never negative;
//  - the mean solid velocity carries the solid momentum sum V_p v_p exactly,
//    and particles moving as one block give their velocity at every node;
//  - a support radius above the smallest cell is refused with a message.

#include <sluice/coupling/porosity_projection.h>

#include "check.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <cstdio>
#include <random>
#include <stdexcept>

using namespace dealii;
using namespace sluice;
using unit::check;
using unit::failures;

namespace
{
  /// The particles whose centre lies in a locally owned cell.
  std::vector<ProjectedParticle> local(const DoFHandler<3> &dofs, const Mapping<3> &mapping,
                                       const std::vector<ProjectedParticle> &all)
  {
    std::vector<ProjectedParticle> mine;
    for (const auto &p : all)
      {
        const auto found = GridTools::find_active_cell_around_point(mapping, dofs, p.position);
        if (found.first.state() == IteratorState::valid && found.first->is_locally_owned())
          mine.push_back(p);
      }
    return mine;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  MPI_Comm                         comm = MPI_COMM_WORLD;
  const bool root = Utilities::MPI::this_mpi_process(comm) == 0;

  for (const bool refined : {false, true})
    {
      parallel::distributed::Triangulation<3> tria(comm);
      GridGenerator::subdivided_hyper_cube(tria, 8, 0., 0.08); // h = 1 cm
      if (refined)
        {
          // One corner refined once more: hanging nodes, cells of 5 mm.
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned() && cell->center()[0] < 0.03 && cell->center()[1] < 0.03)
              cell->set_refine_flag();
          tria.execute_coarsening_and_refinement();
        }
      const FE_Q<3>  fe(1);
      DoFHandler<3>  dofs(tria);
      dofs.distribute_dofs(fe);
      const MappingQ<3> mapping(1);
      const double      support = refined ? 0.005 : 0.01;

      // 3000 particles of radius 1 mm at random, some placed on walls and corners.
      std::mt19937                           random(7);
      std::uniform_real_distribution<double> uniform(0., 0.08);
      std::vector<ProjectedParticle>         all;
      const double volume = 4. / 3. * M_PI * 1e-9;
      std::uniform_real_distribution<double> speed(-1., 1.);
      for (unsigned int n = 0; n < 3000; ++n)
        all.push_back({Point<3>(uniform(random), uniform(random), uniform(random)), volume,
                       Tensor<1, 3>({speed(random), speed(random), speed(random)})});
      for (const double x : {1e-6, 0.08 - 1e-6})
        for (const double y : {1e-6, 0.04, 0.08 - 1e-6})
          for (const double z : {1e-6, 0.08 - 1e-6})
            all.push_back({Point<3>(x, y, z), volume, Tensor<1, 3>({x, y, z})});
      TrilinosWrappers::MPI::Vector                s;
      std::array<TrilinosWrappers::MPI::Vector, 3> us;
      const ProjectionReport r = project_solid_fraction(dofs, mapping, local(dofs, mapping, all),
                                                        support, s, &us);
      const double momentum_scale = r.deposited_volume; // |v| ~ 1 m/s
      check((r.field_momentum - r.particle_momentum).norm() < 1e-12 * momentum_scale,
            "solid momentum conserved", r.field_momentum.norm(), r.particle_momentum.norm());
      check(std::abs(r.deposited_volume - all.size() * volume) < 1e-12 * all.size() * volume,
            "every particle deposited once", r.deposited_volume, all.size() * volume);
      check(std::abs(r.field_integral - r.deposited_volume) < 1e-11 * r.deposited_volume,
            refined ? "conservation, refined mesh" : "conservation, uniform mesh",
            r.field_integral, r.deposited_volume);
      if (root)
        std::printf("%s mesh: %zu particles, volume %.12e, field integral %.12e, relative "
                    "difference %.2e\n",
                    refined ? "refined" : "uniform", all.size(), r.deposited_volume,
                    r.field_integral, (r.field_integral - r.deposited_volume) / r.deposited_volume);

      // A uniform suspension: a particle at the centre of each 4 mm lattice cell.
      if (!refined)
        {
          std::vector<ProjectedParticle> lattice;
          const Tensor<1, 3>             block_velocity({0.1, -0.2, 0.3});
          for (unsigned int i = 0; i < 20; ++i)
            for (unsigned int j = 0; j < 20; ++j)
              for (unsigned int k = 0; k < 20; ++k)
                lattice.push_back(
                  {Point<3>((i + 0.5) * 0.004, (j + 0.5) * 0.004, (k + 0.5) * 0.004), volume,
                   block_velocity});
          TrilinosWrappers::MPI::Vector                u;
          std::array<TrilinosWrappers::MPI::Vector, 3> block;
          project_solid_fraction(dofs, mapping, local(dofs, mapping, lattice), support, u, &block);
          // Particles moving as one block: the mean solid velocity is theirs.
          double velocity_error = 0.;
          for (unsigned int d = 0; d < 3; ++d)
            for (const auto i : block[d].locally_owned_elements())
              velocity_error = std::max(velocity_error, std::abs(block[d][i] - block_velocity[d]));
          velocity_error = Utilities::MPI::max(velocity_error, comm);
          check(velocity_error < 1e-14, "block velocity reproduced", velocity_error, 0.);
          const double mean = volume / (0.004 * 0.004 * 0.004);
          // Nodal positions: which nodes lie a kernel radius or more from every wall.
          std::map<types::global_dof_index, Point<3>> support_points;
          DoFTools::map_dofs_to_support_points(mapping, dofs, support_points);
          double worst = 0., worst_wall = 0.;
          for (const auto i : u.locally_owned_elements())
            {
              const Point<3> &x = support_points[i];
              double wall = 1.;
              for (unsigned int d = 0; d < 3; ++d)
                wall = std::min({wall, x[d], 0.08 - x[d]});
              const double dev = std::abs(u[i] - mean) / mean;
              if (wall > 1.5 * support)
                worst = std::max(worst, dev);
              else
                worst_wall = std::max(worst_wall, dev);
            }
          worst      = Utilities::MPI::max(worst, comm);
          worst_wall = Utilities::MPI::max(worst_wall, comm);
          if (root)
            std::printf("near-wall nodes: largest deviation %.2e\n", worst_wall);
          check(worst < 2e-3, "uniform suspension stays uniform beyond the kernel radius", worst, 0.);
          check(worst_wall < 0.15, "near-wall excess of the renormalised kernel bounded",
                worst_wall, 0.);
          double lowest = std::numeric_limits<double>::max();
          for (const auto i : u.locally_owned_elements())
            lowest = std::min(lowest, double(u[i]));
          lowest = Utilities::MPI::min(lowest, comm);
          check(lowest >= 0., "solid fraction never negative", lowest, 0.);
          if (root)
            std::printf("uniform suspension: solid fraction %.6f, largest nodal deviation %.2e\n",
                        mean, worst);
        }

      // A support wider than the smallest cell is refused.
      bool refused = false;
      try
        {
          TrilinosWrappers::MPI::Vector t;
          project_solid_fraction(dofs, mapping, {}, 2. * support + 1e-9, t);
        }
      catch (const std::invalid_argument &)
        {
          refused = true;
        }
      check(refused, "support above the cell size refused", refused, 1.);
    }

  if (root)
    std::printf("%s: %d failure(s)\n", failures ? "FAILED" : "passed", failures);
  return Utilities::MPI::max(failures, comm) ? 1 : 0;
}
