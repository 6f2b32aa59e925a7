#pragma once
// The fluid mesh from the .prm: a deal.II GridGenerator shape or a gmsh file,
// with periodic pairs registered with p4est, checked against the boundary
// conditions (every boundary id of the mesh has exactly one condition).

#include <sluice/core/fluid_parameters.h>

#include <deal.II/distributed/tria.h>

#include <string>

namespace sluice
{
  /// Fills the (empty) triangulation and, unless 'coarse_only' (a restart, where
  /// the refined mesh comes from the checkpoint), refines it 'initial
  /// refinement' times. Throws InputError if the mesh cannot be made or its ids
  /// do not match.
  void make_fluid_mesh(dealii::parallel::distributed::Triangulation<3> &triangulation,
                       const FluidParameters &parameters, const std::string &prm_file,
                       bool coarse_only = false);
} // namespace sluice
