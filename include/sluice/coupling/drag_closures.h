#pragma once
// Fluid-particle drag closures. Each gives the per-particle drag coefficient k
// in f = k (u - v) (u fluid velocity at the particle, v particle velocity);
// the volumetric momentum-exchange coefficient is beta = k (1 - eps) / V_p.
// Working with k keeps the dilute limit eps -> 1 free of 0/0.
// Formulas: ../shared/reference/REFERENCE.md §2 and REFERENCE_CASES.md §C
// (Gao & Sun Eqs. 17-22 and 39-40 for Syamlal-O'Brien and Wen-Yu).

#include <sluice/core/coupling_parameters.h>

namespace sluice
{

  /// The local state a closure needs (SI): fluid fraction, fluid density and
  /// dynamic viscosity, particle diameter, slip speed |u - v|.
  struct DragState
  {
    double eps = 1., density = 1000., viscosity = 1e-3, diameter = 1e-3, slip = 0.;
  };

  /// k [kg/s] with f = k (u - v) on one particle.
  double particle_drag_coefficient(DragClosure closure, const DragState &s);

  /// beta [kg/(m^3 s)] = k (1 - eps) / V_p, per unit mixture volume.
  double momentum_exchange_coefficient(DragClosure closure, const DragState &s);

} // namespace sluice
