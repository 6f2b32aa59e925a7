#pragma once
// Fluid-particle drag closures. Each gives the per-particle drag coefficient k
// in f = k (u - v) (u fluid velocity at the particle, v particle velocity);
// the volumetric momentum-exchange coefficient is beta = k (1 - eps) / V_p.
// Working with k keeps the dilute limit eps -> 1 free of 0/0.
// Formulas: ../shared/reference/REFERENCE.md §2 and REFERENCE_CASES.md §C
// (Gao & Sun Eqs. 17-22 and 39-40 for Syamlal-O'Brien and Wen-Yu).
//
// A non-spherical particle (a clump body, dem/clump_sphericities.h) enters
// with its volume-equivalent diameter and its three sphericities. The
// 'hoelzer_sommerfeld' closure is their single-particle correlation itself
// (Hoelzer & Sommerfeld 2008, Eq. 9). Every other closure keeps its own
// voidage dependence and is multiplied by the shape's drag ratio
// C_D,HS(Re; phi, phi_perp, phi_par) / C_D,HS(Re; 1, 1, 1) at the closure's
// Re = eps rho d_v w / mu; a sphere's ratio is 1 and is never computed.

#include <sluice/core/coupling_parameters.h>

namespace sluice
{

  /// The local state a closure needs (SI): fluid fraction, fluid density and
  /// dynamic viscosity, particle diameter (volume-equivalent), slip speed
  /// |u - v|; and the particle's sphericity, crosswise and lengthwise
  /// sphericity along the slip (all 1 for a sphere).
  struct DragState
  {
    double eps = 1., density = 1000., viscosity = 1e-3, diameter = 1e-3, slip = 0.;
    double sphericity = 1., crosswise_sphericity = 1., lengthwise_sphericity = 1.;

    bool spherical() const
    {
      return sphericity == 1. && crosswise_sphericity == 1. && lengthwise_sphericity == 1.;
    }
  };

  /// k [kg/s] with f = k (u - v) on one particle.
  double particle_drag_coefficient(DragClosure closure, const DragState &s);

  /// Hoelzer & Sommerfeld's (2008, Eq. 9) drag coefficient of a single
  /// particle of these sphericities at Re = rho d_v w / mu (log: base 10):
  ///   C_D = 8 / (Re sqrt(phi_par)) + 16 / (Re sqrt(phi)) + 3 / (sqrt(Re) phi^(3/4))
  ///         + 0.42 10^(0.4 (-log phi)^0.2) / phi_perp.
  double hoelzer_sommerfeld_drag_coefficient(double reynolds, const DragState &s);

  /// beta [kg/(m^3 s)] = k (1 - eps) / V_p, per unit mixture volume.
  double momentum_exchange_coefficient(DragClosure closure, const DragState &s);

} // namespace sluice
