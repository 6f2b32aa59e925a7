// The fluid sampled at arbitrary points (what the coupling interpolates at
// particle centres), on the Poiseuille scene (prm/fluid/poiseuille.prm), whose
// Q2-Q1 solution is exact: at 200 random points the velocity equals the
// parabola 4 U y (H - y) / H^2, the pressure gradient is -8 mu U / H^2 along x,
// the viscous-stress divergence balances it (mu lap u = grad p), the porosity is
// 1 with zero gradient. The velocity agrees to 1e-6 of U (measured 1.2e-7), the
// gradients to 1e-5 (measured 2e-6: the Newton and GMRES tolerances of the
// solve, not the sampling); on several ranks every point is found on exactly
// one of them.

#include <sluice/fluid/fluid_coefficients.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/mpi.h>

#include "fluid_test.h"

#include <cmath>
#include <random>

using namespace dealii;
using namespace sluice;

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  MPI_Comm                         comm = MPI_COMM_WORLD;
  const SceneParameters scene =
    unit::scene_argument(argc, argv, "unit_fluid_sampling prm/fluid/poiseuille.prm");
  const FluidParameters &p = scene.fluid;
  VansSolver solver(p, coefficients_from_prm(p), Tensor<1, 3>(), scene.file_name, comm);
  solver.initialize(0.);
  solver.solve_steady();

  const double U = p.poiseuille_maximum_velocity, mu = p.viscosity;
  const double L = p.upper_corner[0] - p.lower_corner[0], H = p.upper_corner[1] - p.lower_corner[1],
               W = p.upper_corner[2] - p.lower_corner[2];
  const double dpdx = -8. * mu * U / (H * H);

  std::mt19937                           random(3);
  std::uniform_real_distribution<double> unit(0.01, 0.99);
  std::vector<Point<3>>                  points;
  for (unsigned int n = 0; n < 200; ++n)
    points.emplace_back(unit(random) * L, unit(random) * H, unit(random) * W);
  const auto samples = solver.sample(points);

  double found    = 0., worst_u = 0., worst_p = 0., worst_tau = 0., worst_eps = 0.;
  for (unsigned int n = 0; n < points.size(); ++n)
    {
      const auto &s = samples[n];
      if (!s.found)
        continue;
      found += 1.;
      const double y = points[n][1];
      Tensor<1, 3> u;
      u[0] = 4. * U * y * (H - y) / (H * H);
      Tensor<1, 3> g;
      g[0]      = dpdx;
      worst_u   = std::max(worst_u, (s.velocity - u).norm() / U);
      worst_p   = std::max(worst_p, (s.pressure_gradient - g).norm() / std::abs(dpdx));
      worst_tau = std::max(worst_tau, (s.viscous_divergence - g).norm() / std::abs(dpdx));
      worst_eps = std::max(worst_eps, std::abs(s.porosity - 1.) + s.porosity_gradient.norm());
    }
  found     = Utilities::MPI::sum(found, comm);
  worst_u   = Utilities::MPI::max(worst_u, comm);
  worst_p   = Utilities::MPI::max(worst_p, comm);
  worst_tau = Utilities::MPI::max(worst_tau, comm);
  worst_eps = Utilities::MPI::max(worst_eps, comm);
  unit::RootReport report(comm);
  report(found == points.size(), "points found once over all ranks (count)", found);
  report(worst_u < 1e-6, "velocity against the parabola, relative to U", worst_u);
  report(worst_p < 1e-5, "pressure gradient, relative", worst_p);
  report(worst_tau < 1e-5, "div tau balances the pressure gradient, relative", worst_tau);
  report(worst_eps < 1e-12, "porosity 1, zero gradient", worst_eps);
  return report.exit_code();
}
