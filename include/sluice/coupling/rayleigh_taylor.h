#pragma once
// The Rayleigh-Taylor instability of a suspension layer above clear fluid, as
// the two-fluid model sees it (Robinson, Ramaioli & Luding 2014, Eqs. 38-40):
// the heavy layer is a fluid of the suspension's density and viscosity, and
// a mode of wavenumber k grows at the rate n of Chandrasekhar's dispersion
// relation for two viscous fluids (Hydrodynamic and Hydromagnetic Stability,
// 1961, ch. X, Eq. 113, without surface tension).

#include <vector>

namespace sluice
{
  /// Krieger & Dougherty (1959): mu_s = mu (1 - phi / phi_max)^(-[eta] phi_max),
  /// [eta] = 2.5, phi_max = 0.63 as in Robinson et al.
  double krieger_viscosity(double fluid_viscosity, double solid_fraction,
                           double max_packing = 0.63, double intrinsic_viscosity = 2.5);

  /// The growth rate n > 0 [1/s] of a mode of wavenumber k [1/m] with the heavy
  /// fluid (rho2, mu2) above the light one (rho1, mu1) under gravity g [m/s^2]:
  /// the largest positive root of Chandrasekhar's relation. 0 if the layering
  /// is stable (rho2 <= rho1).
  double rayleigh_taylor_growth_rate(double rho1, double mu1, double rho2, double mu2, double k,
                                     double g);

  /// The inviscid limit sqrt(A g k), A = (rho2 - rho1) / (rho1 + rho2).
  double inviscid_growth_rate(double rho1, double rho2, double k, double g);

  /// The rate n of a(t) = a0 cosh(n t), the linear growth of a mode released
  /// from rest, fitted to (t, a) by least squares on ln a (a0 = a at t = 0).
  double fit_growth_rate_from_rest(const std::vector<double> &t, const std::vector<double> &a);
} // namespace sluice
