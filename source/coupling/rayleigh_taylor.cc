// Rayleigh-Taylor growth of a suspension layer (see the header).

#include <sluice/coupling/rayleigh_taylor.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  double krieger_viscosity(const double fluid_viscosity, const double solid_fraction,
                           const double max_packing, const double intrinsic_viscosity)
  {
    return fluid_viscosity *
           std::pow(1. - solid_fraction / max_packing, -intrinsic_viscosity * max_packing);
  }

  double inviscid_growth_rate(const double rho1, const double rho2, const double k, const double g)
  {
    return std::sqrt(std::max(0., (rho2 - rho1) / (rho1 + rho2)) * g * k);
  }

  namespace
  {
    // Chandrasekhar's relation with alpha_i = rho_i / (rho1 + rho2),
    // nu_i = mu_i / rho_i, q_i = sqrt(k^2 + n / nu_i), no surface tension;
    // fluid 2 (heavy) above fluid 1:
    //   -[(g k / n^2)(alpha1 - alpha2) + 1](alpha2 q1 + alpha1 q2 - k) - 4 k alpha1 alpha2
    //   + (4 k^2 / n)(alpha1 nu1 - alpha2 nu2)(alpha2 q1 - alpha1 q2 + k (alpha1 - alpha2))
    //   + (4 k^3 / n^2)(alpha1 nu1 - alpha2 nu2)^2 (q1 - k)(q2 - k) = 0.
    double dispersion(const double n, const double rho1, const double mu1, const double rho2,
                      const double mu2, const double k, const double g)
    {
      const double a1 = rho1 / (rho1 + rho2), a2 = rho2 / (rho1 + rho2);
      const double nu1 = mu1 / rho1, nu2 = mu2 / rho2;
      const double q1 = std::sqrt(k * k + n / nu1), q2 = std::sqrt(k * k + n / nu2);
      const double dn = a1 * nu1 - a2 * nu2;
      return -((g * k / (n * n)) * (a1 - a2) + 1.) * (a2 * q1 + a1 * q2 - k) - 4. * k * a1 * a2 +
             (4. * k * k / n) * dn * (a2 * q1 - a1 * q2 + k * (a1 - a2)) +
             (4. * k * k * k / (n * n)) * dn * dn * (q1 - k) * (q2 - k);
    }
  } // namespace

  double rayleigh_taylor_growth_rate(const double rho1, const double mu1, const double rho2,
                                     const double mu2, const double k, const double g)
  {
    if (rho2 <= rho1)
      return 0.;
    // Viscosity only slows the growth: the root lies below the inviscid rate.
    // Scan down from just above it on a log grid for the first sign change,
    // then bisect.
    const double n_max = 1.01 * inviscid_growth_rate(rho1, rho2, k, g);
    const auto   f     = [&](const double n) { return dispersion(n, rho1, mu1, rho2, mu2, k, g); };
    double       hi = n_max, f_hi = f(hi);
    for (int i = 1; i <= 4000; ++i)
      {
        const double lo = n_max * std::pow(10., -i / 200.), f_lo = f(lo);
        if (f_lo * f_hi <= 0.)
          {
            double a = lo, b = hi, fa = f_lo;
            for (int it = 0; it < 200 && b - a > 1e-14 * b; ++it)
              {
                const double m = 0.5 * (a + b), fm = f(m);
                if (fa * fm <= 0.)
                  b = m;
                else
                  a = m, fa = fm;
              }
            return 0.5 * (a + b);
          }
        hi = lo, f_hi = f_lo;
      }
    return 0.;
  }

  double fit_growth_rate_from_rest(const std::vector<double> &t, const std::vector<double> &a)
  {
    if (t.size() < 3 || a.empty() || !(a[0] > 0.))
      return 0.;
    const double a0       = a[0];
    const auto   residual = [&](const double n) {
      double r = 0.;
      for (std::size_t i = 0; i < t.size(); ++i)
        if (a[i] > 0.)
          {
            const double e = std::log(a[i] / a0) - std::log(std::cosh(n * t[i]));
            r += e * e;
          }
      return r;
    };
    // Golden-section search on n in (0, n_hi], n_hi from the largest growth seen.
    double n_hi = 1.;
    for (std::size_t i = 1; i < t.size(); ++i)
      if (a[i] > a0 && t[i] > 0.)
        n_hi = std::max(n_hi, 4. * std::acosh(a[i] / a0) / t[i]);
    double       lo = 0., hi = n_hi;
    const double phi = 0.5 * (std::sqrt(5.) - 1.);
    double       x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
    double       f1 = residual(x1), f2 = residual(x2);
    for (int it = 0; it < 200 && hi - lo > 1e-12 * n_hi; ++it)
      if (f1 < f2)
        {
          hi = x2, x2 = x1, f2 = f1;
          x1 = hi - phi * (hi - lo), f1 = residual(x1);
        }
      else
        {
          lo = x1, x1 = x2, f1 = f2;
          x2 = lo + phi * (hi - lo), f2 = residual(x2);
        }
    return 0.5 * (lo + hi);
  }
} // namespace sluice
