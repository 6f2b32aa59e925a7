// The semi-implicit exchange drag (doc/coupling.md, "The semi-implicit
// drag") adds beta_n (u^n - u^n-1) to step n's momentum equation and returns
// beta_n-1 (u^n-1 - u^n-2), the term the step before applied, as a source.
// Over a run the two cancel except for the last step's term, so the fluid
// still receives the particles' impulses. This test asserts that at every
// step, by itself: in a triply periodic box (tests/unit/semi_implicit_exchange.prm)
// with uniform porosity eps, force density f and a drag coefficient that
// changes every step, the uniform velocity must follow the scalar recursion
// of backward Euler,
//   rho eps (u^n - u^n-1) / dt + beta_n (u^n - u^n-1) = f + beta_n-1 (u^n-1 - u^n-2),
// and the fluid's momentum must be f t less the last step's term only:
//   rho eps u^N = N dt f - dt beta_N (u^N - u^N-1).
// A missing implicit term, a returned term with the wrong coefficient, sign
// or velocities, or one not returned, each breaks the recursion at once (the
// coefficient reaches a = dt beta / (eps rho) = 6, where these differ by far
// more than the solver's tolerance).

#include <sluice/fluid/fluid_coefficients.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/vector_tools.h>

#include "fluid_test.h"

#include <cmath>
#include <vector>

using namespace dealii;
using namespace sluice;

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  MPI_Comm                         comm  = MPI_COMM_WORLD;
  const SceneParameters            scene = unit::scene_argument(
    argc, argv, "unit_semi_implicit_exchange tests/unit/semi_implicit_exchange.prm");
  FluidParameters p = scene.fluid;
  // What a coupled scene with 'cfd-dem/semi-implicit drag' sets.
  p.porosity_as_field        = true;
  p.momentum_source_as_field = true;
  p.exchange_drag_as_field   = true;
  VansSolver solver(p, coefficients_from_prm(p), Tensor<1, 3>(), scene.file_name, comm);
  solver.initialize(0.);

  const double rho = p.density, dt = p.time_step, eps = 0.6, f = 30.; // f in N/m^3
  const auto   field = [&](const DoFHandler<3> &dofs, const Function<3> &value) {
    TrilinosWrappers::MPI::Vector v(dofs.locally_owned_dofs(), comm);
    VectorTools::interpolate(solver.get_mapping(), dofs, value, v);
    return v;
  };
  solver.set_initial_porosity(field(solver.porosity_dofs(), Functions::ConstantFunction<3>(eps)));
  const Functions::ConstantFunction<3> force_density(std::vector<double>{f, 0., 0.});
  solver.set_momentum_source(field(solver.momentum_source_dofs(), force_density));
  // beta_n grows from a = 1.2 to a = 6 over the run.
  const auto beta = [&](const unsigned int n) { return eps * rho / dt * (1.2 + 0.24 * n); };

  const Point<3> centre(0.005, 0.005, 0.005), corner(0.001, 0.009, 0.003);
  const auto     velocity_at = [&](const Point<3> &x) {
    const auto s = solver.sample({x});
    return Utilities::MPI::sum(s[0].found ? s[0].velocity : Tensor<1, 3>(), comm);
  };

  const unsigned int  n_steps = 20;
  std::vector<double> u(n_steps + 1, 0.), b(n_steps + 1, 0.);
  double worst_recursion = 0., worst_uniform = 0., worst_transverse = 0.;
  for (unsigned int n = 1; n <= n_steps; ++n)
    {
      b[n] = beta(n);
      const Functions::ConstantFunction<3> beta_n(b[n]);
      solver.set_exchange_drag(field(solver.porosity_dofs(), beta_n));
      solver.advance(dt);
      const Tensor<1, 3> v = velocity_at(centre);
      u[n]                 = v[0];
      const double returned  = n >= 2 ? b[n - 1] * (u[n - 1] - u[n - 2]) : 0.;
      const double recursion = rho * eps * (u[n] - u[n - 1]) / dt + b[n] * (u[n] - u[n - 1]) -
                               f - returned;
      worst_recursion  = std::max(worst_recursion, std::abs(recursion) / f);
      worst_uniform    = std::max(worst_uniform, (velocity_at(corner) - v).norm() / std::abs(u[n]));
      worst_transverse = std::max(worst_transverse, std::hypot(v[1], v[2]) / std::abs(u[n]));
    }
  const double T       = n_steps * dt;
  const double last    = dt * b[n_steps] * (u[n_steps] - u[n_steps - 1]); // not yet returned
  const double balance = rho * eps * u[n_steps] - (T * f - last);
  const double unreturned = last / (T * f);

  unit::RootReport report(comm);
  report(worst_recursion < 1e-6, "every step follows the semi-implicit recursion (|residual| / f)",
         worst_recursion);
  const double imbalance = std::abs(balance) / (T * f);
  report(imbalance < 1e-6, "momentum rho eps u^N = f t - the last step's term (relative)",
         imbalance);
  report(unreturned > 1e-3, "the last step's term is not negligible (so the check above bites)",
         unreturned);
  report(worst_uniform < 1e-8, "the velocity stays uniform (relative)", worst_uniform);
  report(worst_transverse < 1e-8, "and along x (relative)", worst_transverse);
  return report.exit_code();
}
