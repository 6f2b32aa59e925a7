#pragma once
// The smoothing kernels of the SPH fluid (issue 15; doc/sph.md), in three
// dimensions, both of compact support 2h:
//   - the cubic spline M4 (Monaghan & Lattanzio 1985):
//       W = 1/(pi h^3) { 1 - 3/2 q^2 + 3/4 q^3   0 <= q < 1
//                        (2 - q)^3 / 4           1 <= q < 2 },  q = r / h;
//   - Wendland's C2 (Wendland 1995), the kernel Robinson, Ramaioli & Luding
//     (2014) use, with the same support:
//       W = 21/(256 pi h^3) (2 - q)^4 (1 + 2 q)    0 <= q < 2.
// For each: W(r, h), its derivative along r (the gradient is dW/dr r_ab / r)
// and its derivative with respect to h at fixed r, which the variable
// smoothing length needs (Price 2012: the Omega term, dW/dh = -(3 W + q
// dW/dq / h^3) / h). The kernel is a template parameter of the SPH loops,
// so the choice costs no branch per pair.

#include <cmath>

namespace sluice
{
  /// The cubic spline M4.
  struct CubicSplineKernel
  {
    static constexpr double support = 2.; // in units of h
    static constexpr const char *name = "cubic_spline";
    /// The mean distance <r> = integral of |x| W(x, h) dx, in units of h.
    static constexpr double mean_distance = 31. / 35.;

    /// The dimensionless shape f(q) (W = f / h^3) and its derivative df/dq.
    static double shape(const double q)
    {
      if (q < 1.)
        return (1. - 1.5 * q * q + 0.75 * q * q * q) / M_PI;
      if (q < 2.)
        {
          const double t = 2. - q;
          return 0.25 * t * t * t / M_PI;
        }
      return 0.;
    }
    static double shape_derivative(const double q)
    {
      if (q < 1.)
        return (-3. * q + 2.25 * q * q) / M_PI;
      if (q < 2.)
        {
          const double t = 2. - q;
          return -0.75 * t * t / M_PI;
        }
      return 0.;
    }
  };

  /// Wendland's C2 kernel in three dimensions.
  struct WendlandC2Kernel
  {
    static constexpr double support = 2.;
    static constexpr const char *name = "wendland_c2";
    static constexpr double mean_distance = 5. / 6.; // <r> / h

    static double shape(const double q)
    {
      if (q >= 2.)
        return 0.;
      const double t = 2. - q, t2 = t * t;
      return 21. / (256. * M_PI) * t2 * t2 * (1. + 2. * q);
    }
    /// d/dq of (2 - q)^4 (1 + 2q) is -10 q (2 - q)^3.
    static double shape_derivative(const double q)
    {
      if (q >= 2.)
        return 0.;
      const double t = 2. - q;
      return -21. / (256. * M_PI) * 10. * q * t * t * t;
    }
  };

  /// W(r, h) [1/m^3].
  template <typename Kernel>
  double kernel_value(const double r, const double h)
  {
    return Kernel::shape(r / h) / (h * h * h);
  }

  /// dW/dr at fixed h [1/m^4].
  template <typename Kernel>
  double kernel_radial_derivative(const double r, const double h)
  {
    return Kernel::shape_derivative(r / h) / (h * h * h * h);
  }

  /// dW/dh at fixed r [1/m^4]: W = f(r/h) / h^3 gives -(3 f + q f') / h^4.
  template <typename Kernel>
  double kernel_h_derivative(const double r, const double h)
  {
    const double q = r / h;
    return -(3. * Kernel::shape(q) + q * Kernel::shape_derivative(q)) / (h * h * h * h);
  }
} // namespace sluice
