#pragma once
// The fluid a coupled scene asks for ('cfd-dem/fluid backend'): the
// finite-element VANS solver (vans_backend.h) or the SPH fluid
// (sph_backend.h), with the input checks each needs. Only the chosen one is
// built: an SPH scene has no fluid mesh, a finite-element one no SPH particles.

#include <sluice/core/fluid_parameters.h>
#include <sluice/core/scene_parameters.h>
#include <sluice/coupling/fluid_backend.h>

#include <mpi.h>

#include <memory>
#include <string>

namespace sluice
{
  /// The scene as the chosen fluid sees it: with the SPH fluid, the fluid's
  /// density and viscosity are the 'sph' subsection's (for the particle-fluid
  /// forces and the validations' references). Throws InputError for an
  /// SPH scene the coupling cannot run, naming the entry.
  SceneParameters with_fluid_backend(const SceneParameters &parameters);

  /// Builds the fluid (collective); 'largest_diameter' of the particles.
  std::unique_ptr<FluidBackend> make_fluid_backend(const SceneParameters &parameters,
                                                   const FluidParameters &fluid,
                                                   double largest_diameter, MPI_Comm comm);

  /// What the header says about how the particles reach the fluid.
  std::string describe_exchange(const SceneParameters &parameters, const FluidBackend &fluid,
                                double largest_diameter, bool clumps);
} // namespace sluice
