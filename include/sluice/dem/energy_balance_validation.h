#pragma once
// The validation of the energy bookkeeping (prm/geometry/energy_balance.prm):
// the scene is run with its time step and with half of it, each with the
// contact observer and the energy balance (energy_balance.h), and the
// residual must be a small part of the energy dissipated and fall as dt^2;
// the particle-wall tangential work summed per mesh triangle and per particle
// type must equal the ledger's to round-off.

#include <sluice/core/scene_parameters.h>

#include <mpi.h>

namespace sluice
{
  /// The result line's value is residual / dissipated at the scene's step;
  /// exits 3 above 'validation/tolerance', or if the observed order of the
  /// residual is below 1.8, or the per-triangle or per-type sums differ from
  /// the ledger's by more than 1e-12 relative. One MPI rank (InputError).
  int run_energy_balance_validation(const SceneParameters &parameters, MPI_Comm communicator);
} // namespace sluice
