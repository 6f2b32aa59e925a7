#pragma once
// What a fluid solve reports, as plain numbers: integral quantities for the
// .csv and the validations, and the work a nonlinear solve took.

#include <sluice/core/run_stopped.h>

#include <stdexcept>
#include <vector>

namespace sluice
{
  /// Integral quantities for the .csv and the validation.
  struct FluidIntegrals
  {
    double              pressure_drop = 0.; // mean p on the first named boundary minus the second
    double              drop_distance = 0.; // distance between the centroids of those two
    std::vector<double> flow_rates;         // integral of eps u . n, per named boundary
    double              kinetic_energy = 0.; // integral of rho eps |u|^2 / 2
  };

  /// A fluid solve that cannot go on (Newton or GMRES failed, or a step too
  /// long for the explicit particle reaction); the message names the
  /// parameter to change (exit 4).
  class SolverFailure : public RunStopped
  {
  public:
    using RunStopped::RunStopped;
  };

  struct NewtonReport
  {
    unsigned int iterations = 0, linear_iterations = 0, preconditioner_builds = 0;
    /// Newton solves that fell back to a Picard linearisation of SUPG's
    /// advecting velocity because GMRES failed with a fresh preconditioner
    /// (vans_solver.h).
    unsigned int picard_starts = 0;
    double       residual   = 0.;
  };
} // namespace sluice
