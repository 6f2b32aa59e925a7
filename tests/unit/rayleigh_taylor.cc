// The two-fluid Rayleigh-Taylor growth rate behind the rayleigh_taylor scene:
// Chandrasekhar's viscous relation must give the rates that
// ../shared/reference/scripts/sphdem_robinson.py prints for Robinson et al.'s
// set-up (REFERENCE_CASES.md B.4, copied below: CI has no ../shared) to their
// four digits; tend to the inviscid sqrt(A g k) as the viscosities vanish;
// fall as the suspension's viscosity rises; and be zero for a stable layering.
// The Krieger viscosity must match the table's mu2, and the fit of a cosh
// growth must recover the rate of a curve made with it.

#include <sluice/coupling/rayleigh_taylor.h>

#include "check.h"

#include <cmath>
#include <vector>

using namespace sluice;
using unit::check;
using unit::failures;

int main()
{
  const double g = 9.81, rho_p = 2500., L = 0.004, k = std::sqrt(2.) * 2. * M_PI / L;
  struct Row
  {
    double rho_f, mu_f, eps, mu2, n, inviscid;
  };
  // fluid, eps, mu2 (Krieger), n, inviscid (REFERENCE_CASES.md B.4)
  const Row rows[] = {{1000., 8.9e-4, 0.80, 1.624e-3, 43.67, 53.31},
                      {1000., 8.9e-4, 0.93, 1.071e-3, 25.77, 32.97},
                      {1150., 8.9e-3, 0.80, 1.624e-2, 18.53, 47.85},
                      {1150., 8.9e-3, 0.93, 1.071e-2, 9.121, 29.33},
                      {1.1839, 1.86e-5, 0.80, 3.394e-5, 146.1, 147.3}};
  for (const Row &r : rows)
    {
      const double rho2 = r.eps * r.rho_f + (1. - r.eps) * rho_p;
      const double mu2  = krieger_viscosity(r.mu_f, 1. - r.eps);
      check(std::abs(mu2 - r.mu2) < 5e-4 * r.mu2, "Krieger viscosity", mu2, r.mu2);
      const double n = rayleigh_taylor_growth_rate(r.rho_f, r.mu_f, rho2, mu2, k, g);
      check(std::abs(n - r.n) < 5e-4 * r.n, "viscous growth rate (B.4 table)", n, r.n);
      const double inviscid = inviscid_growth_rate(r.rho_f, rho2, k, g);
      check(std::abs(inviscid - r.inviscid) < 5e-4 * r.inviscid, "inviscid rate", inviscid,
            r.inviscid);
      // The suspension's extra viscosity slows the growth.
      const double n_clear = rayleigh_taylor_growth_rate(r.rho_f, r.mu_f, rho2, r.mu_f, k, g);
      check(n_clear > n && n_clear < inviscid, "mu2 = mu1 lies between Krieger and inviscid",
            n_clear, n);
      // Vanishing viscosities: the inviscid limit.
      const double n0 = rayleigh_taylor_growth_rate(r.rho_f, 1e-12, rho2, 1e-12, k, g);
      check(std::abs(n0 - inviscid) < 1e-3 * inviscid, "inviscid limit", n0, inviscid);
    }
  check(rayleigh_taylor_growth_rate(1300., 1e-3, 1000., 1e-3, k, g) == 0., "stable layering", 1., 0.);

  // The fit recovers n from a0 cosh(n t), and from a noisy curve within 1%.
  std::vector<double> t, a, noisy;
  for (int i = 0; i <= 60; ++i)
    {
      t.push_back(i * 1e-3);
      a.push_back(5e-5 * std::cosh(37. * t.back()));
      noisy.push_back(a.back() * (1. + 0.01 * std::sin(7. * i)));
    }
  const double n_fit = fit_growth_rate_from_rest(t, a);
  check(std::abs(n_fit - 37.) < 1e-6 * 37., "cosh fit", n_fit, 37.);
  const double n_noisy = fit_growth_rate_from_rest(t, noisy);
  check(std::abs(n_noisy - 37.) < 1e-2 * 37., "cosh fit with 1% noise", n_noisy, 37.);
  return failures == 0 ? 0 : 1;
}
