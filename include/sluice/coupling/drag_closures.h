#pragma once
// Fluid-particle drag closures. Each gives the per-particle drag coefficient k
// in f = k (u - v) (u fluid velocity at the particle, v particle velocity);
// the volumetric momentum-exchange coefficient is beta = k (1 - eps) / V_p.
// Working with k keeps the dilute limit eps -> 1 free of 0/0.
// Formulas: ../shared/reference/REFERENCE.md §2 and REFERENCE_CASES.md §C
// (Gao & Sun Eqs. 17-22 and 39-40 for Syamlal-O'Brien and Wen-Yu).

#include <string>

namespace sluice
{
  enum class DragClosure
  {
    stokes,         // f = 3 pi mu d w
    dallavalle,     // single sphere, C_d = (0.63 + 4.8/sqrt(Re))^2, Re = rho d w / mu
    di_felice,      // Dallavalle C_d with the voidage function eps^(2-chi) (Di Felice 1994)
    rong,           // Di Felice form with Rong et al. (2013)'s chi(eps, Re)
    wen_yu,         // Wen & Yu (1966), Schiller-Naumann C_d, eps^-2.65
    ergun,          // Ergun (1952) in Gidaspow's beta form
    gidaspow,       // Ergun for eps <= 0.8, Wen-Yu above
    syamlal_obrien, // Syamlal & O'Brien (1988), terminal-velocity ratio V_r
    beetstra,       // Beetstra, van der Hoef & Kuipers (2007)
    koch_hill       // Hill, Koch & Ladd (2001) as in Benyahia et al. (2006)
  };

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

  /// The .prm name of each closure ("stokes", "di_felice", ...), and back.
  std::string drag_closure_name(DragClosure closure);
  /// Throws std::invalid_argument for an unknown name.
  DragClosure drag_closure_from_name(const std::string &name);
  /// All names, '|'-separated, for a deal.II Selection pattern.
  std::string drag_closure_names();
} // namespace sluice
