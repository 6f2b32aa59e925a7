// The drag closures, each written for the per-particle coefficient k (f = k w),
// w = |u - v|, phi = 1 - eps, V_p = pi d^3 / 6. Reynolds numbers follow each
// closure's own convention (noted per case); at w = 0 every closure takes its
// Stokes-regime limit, reached by evaluating at a tiny Reynolds number.

#include <sluice/coupling/drag_closures.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sluice
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    // Below this the Reynolds number is replaced by it: every closure is smooth
    // in w there and k tends to its creeping-flow value.
    constexpr double smallest_reynolds = 1e-12;

    double particle_volume(const double d)
    {
      return pi * d * d * d / 6.;
    }

    /// Schiller-Naumann with Newton's cap (Gao & Sun Eq. 40).
    double schiller_naumann(const double re)
    {
      return re < 1000. ? 24. / re * (1. + 0.15 * std::pow(re, 0.687)) : 0.44;
    }

    double dallavalle_cd(const double re)
    {
      const double a = 0.63 + 4.8 / std::sqrt(re);
      return a * a;
    }

    /// k of the Di Felice form: f = 1/2 C_d rho (pi d^2/4) eps^2 w^2 eps^(-chi),
    /// C_d of Dallavalle at Re = eps rho d w / mu.
    double voidage_form(const DragState &s, const double re, const double chi)
    {
      // w = Re mu / (eps rho d): written with Re so that w -> 0 stays finite.
      const double w = re * s.viscosity / (s.eps * s.density * s.diameter);
      return 0.5 * dallavalle_cd(re) * s.density * pi * s.diameter * s.diameter / 4. * s.eps *
             s.eps * w * std::pow(s.eps, -chi);
    }

    double ergun(const DragState &s)
    {
      const double phi = 1. - s.eps, d = s.diameter;
      // beta = 150 phi^2 mu / (eps d^2) + 1.75 phi rho w / d, divided by phi / V_p.
      return particle_volume(d) *
             (150. * phi * s.viscosity / (s.eps * d * d) + 1.75 * s.density * s.slip / d);
    }

    double wen_yu(const DragState &s, const double re)
    {
      // beta = 3/4 C_d eps phi rho w eps^-2.65 / d (Gao & Sun Eq. 39), Re = eps rho d w / mu.
      const double w = re * s.viscosity / (s.eps * s.density * s.diameter);
      return particle_volume(s.diameter) * 0.75 * schiller_naumann(re) * s.eps * s.density * w *
             std::pow(s.eps, -2.65) / s.diameter;
    }

    double syamlal_obrien(const DragState &s)
    {
      // Re = rho d w / mu (no eps); Gao & Sun Eqs. 17-22.
      const double re = std::max(s.density * s.diameter * s.slip / s.viscosity, smallest_reynolds);
      const double w  = re * s.viscosity / (s.density * s.diameter);
      const double a  = std::pow(s.eps, 4.14);
      const double b  = s.eps <= 0.85 ? 0.8 * std::pow(s.eps, 1.28) : std::pow(s.eps, 2.65);
      const double vr = 0.5 * (a - 0.06 * re +
                               std::sqrt(0.0036 * re * re + 0.12 * re * (2. * b - a) + a * a));
      const double cd = std::pow(0.63 + 4.8 * std::sqrt(vr / re), 2);
      return particle_volume(s.diameter) * 0.75 * s.eps * s.density * w * cd /
             (vr * vr * s.diameter);
    }

    double beetstra(const DragState &s, const double re)
    {
      const double phi = 1. - s.eps, e2 = s.eps * s.eps;
      double       f = 10. * phi / e2 + e2 * (1. + 1.5 * std::sqrt(phi));
      f += 0.413 * re / (24. * e2) * (1. / s.eps + 3. * s.eps * phi + 8.4 * std::pow(re, -0.343)) /
           (1. + std::pow(10., 3. * phi) * std::pow(re, -(1. + 4. * phi) / 2.));
      // beta = 18 mu eps phi F / d^2.
      return particle_volume(s.diameter) * 18. * s.viscosity * s.eps * f /
             (s.diameter * s.diameter);
    }

    double koch_hill(const DragState &s)
    {
      // Re based on the radius: Re = d eps rho w / (2 mu) (MFiX DRAG_KOCH_HILL).
      const double phi = 1. - s.eps;
      const double re  = 0.5 * s.diameter * s.eps * s.density * s.slip / s.viscosity;
      const double dense = 10. * phi / std::pow(s.eps, 3);
      double       f;
      // phi ln(phi) -> 0 as phi -> 0 (a single sphere).
      const double ln = phi > 0. ? phi * std::log(phi) : 0.;
      if (phi <= 0.01)
        {
          const double f2 = 1. + 3. * std::sqrt(phi / 2.) + 135. / 64. * ln + 17.89 * phi;
          const double f3 = 0.9351 * phi + 0.03667;
          const double re_t1 = (f2 - 1.) / (3. / 8. - f3);
          f = re <= re_t1 ? 1. + 3. * re / 8. : f2 + f3 * re;
        }
      else
        {
          const double w = std::exp(-10. * (0.4 - phi) / phi);
          const double sq = std::sqrt(phi / 2.);
          const double f0 =
            phi < 0.4 ? (1. - w) * (1. + 3. * sq + 135. / 64. * ln + 17.14 * phi) /
                            (1. + 0.681 * phi - 8.48 * phi * phi + 8.16 * phi * phi * phi) +
                          w * dense :
                        dense;
          const double f1 = phi <= 0.1 ? std::sqrt(2. / phi) / 40. :
                                         0.11 + 5.1e-4 * std::exp(11.6 * phi);
          const double f2 =
            phi < 0.4 ? (1. - w) * (1. + 3. * sq + 135. / 64. * ln + 17.89 * phi) /
                            (1. + 0.681 * phi - 11.03 * phi * phi + 15.41 * phi * phi * phi) +
                          w * dense :
                        dense;
          const double f3 = phi < 0.0953 ? 0.9351 * phi + 0.03667 :
                                           0.0673 + 0.212 * phi + 0.0232 / std::pow(s.eps, 5);
          const double re_t2 = (f3 + std::sqrt(f3 * f3 - 4. * f1 * (f0 - f2))) / (2. * f1);
          f = re <= re_t2 ? f0 + f1 * re * re : f2 + f3 * re;
        }
      // beta = 18 mu eps^2 phi F / d^2.
      return particle_volume(s.diameter) * 18. * s.viscosity * s.eps * s.eps * f /
             (s.diameter * s.diameter);
    }

    /// k of a sphere of diameter s.diameter by the closure, at its Re.
    double sphere_drag_coefficient(const DragClosure closure, const DragState &s, const double re)
    {
      const double d = s.diameter;
      switch (closure)
        {
          case DragClosure::stokes:
            return 3. * pi * s.viscosity * d;
          case DragClosure::dallavalle:
            {
              // A single sphere: Re = rho d w / mu, no voidage.
              const double re1 = std::max(s.density * d * s.slip / s.viscosity, smallest_reynolds);
              const double w   = re1 * s.viscosity / (s.density * d);
              return 0.5 * dallavalle_cd(re1) * s.density * pi * d * d / 4. * w;
            }
          case DragClosure::di_felice:
            {
              const double l   = 1.5 - std::log10(re);
              const double chi = 3.7 - 0.65 * std::exp(-l * l / 2.);
              return voidage_form(s, re, chi);
            }
          case DragClosure::rong:
            {
              const double l   = 1.5 - std::log10(re);
              const double chi = 2.65 * (s.eps + 1.) -
                                 (5.3 - 3.5 * s.eps) * s.eps * s.eps * std::exp(-l * l / 2.);
              return voidage_form(s, re, chi);
            }
          case DragClosure::wen_yu:
            return wen_yu(s, re);
          case DragClosure::ergun:
            return ergun(s);
          case DragClosure::gidaspow:
            return s.eps <= 0.8 ? ergun(s) : wen_yu(s, re);
          case DragClosure::syamlal_obrien:
            return syamlal_obrien(s);
          case DragClosure::beetstra:
            return beetstra(s, re);
          case DragClosure::koch_hill:
            return koch_hill(s);
          case DragClosure::hoelzer_sommerfeld:
            break; // not a sphere closure (particle_drag_coefficient)
        }
      return 0.;
    }
  } // namespace

  double hoelzer_sommerfeld_drag_coefficient(const double re, const DragState &s)
  {
    // A union that is a sphere (one member inside another) may come out at
    // 1 + 1e-12 by quadrature: -log phi must not turn negative under ^0.2.
    const double log_term = std::max(-std::log10(s.sphericity), 0.);
    return 8. / (re * std::sqrt(s.lengthwise_sphericity)) + 16. / (re * std::sqrt(s.sphericity)) +
           3. / (std::sqrt(re) * std::pow(s.sphericity, 0.75)) +
           0.42 * std::pow(10., 0.4 * std::pow(log_term, 0.2)) / s.crosswise_sphericity;
  }

  double particle_drag_coefficient(const DragClosure closure, const DragState &s)
  {
    // The usual suspension Reynolds number, Re = eps rho d w / mu.
    const double re =
      std::max(s.eps * s.density * s.diameter * s.slip / s.viscosity, smallest_reynolds);
    if (closure == DragClosure::hoelzer_sommerfeld)
      {
        // A single particle: Re = rho d_v w / mu, no voidage.
        const double re1 =
          std::max(s.density * s.diameter * s.slip / s.viscosity, smallest_reynolds);
        const double w = re1 * s.viscosity / (s.density * s.diameter);
        return 0.5 * hoelzer_sommerfeld_drag_coefficient(re1, s) * s.density * pi * s.diameter *
               s.diameter / 4. * w;
      }
    const double k = sphere_drag_coefficient(closure, s, re);
    if (s.spherical())
      return k;
    return k * hoelzer_sommerfeld_drag_coefficient(re, s) /
           hoelzer_sommerfeld_drag_coefficient(re, DragState());
  }


  double momentum_exchange_coefficient(const DragClosure closure, const DragState &s)
  {
    return particle_drag_coefficient(closure, s) * (1. - s.eps) / particle_volume(s.diameter);
  }

} // namespace sluice
