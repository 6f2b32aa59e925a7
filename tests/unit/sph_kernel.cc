// The SPH kernels (sph/sph_kernel.h), cubic spline and Wendland C2:
// - normalised: the integral of W over its support is 1 (radial Gauss-Legendre
//   quadrature on the pieces where W is a polynomial: exact to round-off);
// - second moment: int q^2 W dV = 9/10 (spline) and 4/5 (Wendland), the
//   closed forms (Wendland's by Beta functions, 21/64 * 512 (B(5,5) + 4 B(6,5)));
// - mean distance: int q W dV = 31/35 (spline) and 5/6 (Wendland), the
//   constants the signal-velocity viscosity is tied to mu with (sph_viscosity.h);
// - compact support: W, dW/dr and dW/dh vanish from r = 2h on, and W is
//   continuous with its first derivative at q = 1 (spline) and at q = 2;
// - the derivatives against central differences of W in r and in h;
// - on a simple cubic lattice of spacing dx with h = 1.5 dx (Robinson et al.'s
//   choice), the sum m sum_b W_ab gives the density within 2e-3 (spline:
//   1.0016) and 5e-3 (Wendland: 1.0028), and the gradients cancel by symmetry.

#include <sluice/sph/sph_kernel.h>

#include "check.h"

#include <cmath>
#include <cstdio>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  /// int_0^2 4 pi q^2 f(q)^power q^extra dq by 8-point Gauss-Legendre on [0,1] and [1,2].
  template <typename Kernel>
  double radial_integral(const unsigned int extra)
  {
    static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                0.9602898564975363};
    static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                0.1012285362903763};
    double sum = 0.;
    for (const double a : {0., 1.})
      for (unsigned int k = 0; k < 4; ++k)
        for (const double sign : {-1., 1.})
          {
            const double q = a + 0.5 * (1. + sign * x[k]);
            sum += 0.5 * w[k] * 4. * M_PI * q * q * std::pow(q, extra) * Kernel::shape(q);
          }
    return sum;
  }

  template <typename Kernel>
  void check_kernel(const double second_moment, const double density_bound)
  {
    const std::string name = Kernel::name;
    const double      norm = radial_integral<Kernel>(0), moment = radial_integral<Kernel>(2);
    check(std::abs(norm - 1.) < 1e-14, (name + ": normalised").c_str(), norm, 1.);
    check(std::abs(moment - second_moment) < 1e-14, (name + ": second moment").c_str(), moment,
          second_moment);
    std::printf("%s: integral of W %.16f, of q^2 W %.16f\n", Kernel::name, norm, moment);
    const double mean = radial_integral<Kernel>(1);
    check(std::abs(mean - Kernel::mean_distance) < 1e-14, (name + ": mean distance").c_str(), mean,
          Kernel::mean_distance);

    const double h = 0.37;
    // Compact support, and continuity at the knots.
    check(kernel_value<Kernel>(2. * h, h) == 0. && kernel_radial_derivative<Kernel>(2. * h, h) == 0. &&
            kernel_h_derivative<Kernel>(2. * h, h) == 0. && kernel_value<Kernel>(3. * h, h) == 0.,
          (name + ": zero from 2h on").c_str(), kernel_value<Kernel>(2. * h, h), 0.);
    for (const double knot : {1., 2.})
      {
        const double e = 1e-9;
        check(std::abs(Kernel::shape(knot - e) - Kernel::shape(knot + e)) < 1e-8 &&
                std::abs(Kernel::shape_derivative(knot - e) - Kernel::shape_derivative(knot + e)) <
                  1e-7,
              (name + ": continuous with its slope at a knot").c_str(), knot, 0.);
      }
    // Derivatives against central differences.
    double worst_r = 0., worst_h = 0.;
    for (double r = 0.013; r < 2. * h; r += 0.031)
      {
        const double d  = 1e-6;
        const double fr = (kernel_value<Kernel>(r + d, h) - kernel_value<Kernel>(r - d, h)) / (2. * d);
        const double fh = (kernel_value<Kernel>(r, h + d) - kernel_value<Kernel>(r, h - d)) / (2. * d);
        const double scale = kernel_value<Kernel>(0., h) / h;
        worst_r = std::max(worst_r, std::abs(fr - kernel_radial_derivative<Kernel>(r, h)) / scale);
        worst_h = std::max(worst_h, std::abs(fh - kernel_h_derivative<Kernel>(r, h)) / scale);
      }
    check(worst_r < 1e-8, (name + ": dW/dr against differences").c_str(), worst_r, 0.);
    check(worst_h < 1e-8, (name + ": dW/dh against differences").c_str(), worst_h, 0.);

    // A lattice of unit mass per cell: the density sum and the gradient sum.
    const double dx = 1., hl = 1.5 * dx;
    double       rho = 0., grad = 0.;
    for (int i = -4; i <= 4; ++i)
      for (int j = -4; j <= 4; ++j)
        for (int k = -4; k <= 4; ++k)
          {
            const double x = i * dx + 0.1, y = j * dx, z = k * dx, r = std::sqrt(x * x + y * y + z * z);
            rho += kernel_value<Kernel>(r, hl);
            if (r > 0.)
              grad += kernel_radial_derivative<Kernel>(r, hl) * y / r;
          }
    std::printf("%s: lattice density %.6f (1 exact), transverse gradient sum %.1e\n", Kernel::name,
                rho, grad);
    check(std::abs(rho - 1.) < density_bound, (name + ": lattice density").c_str(), rho, 1.);
    check(std::abs(grad) < 1e-14, (name + ": symmetric gradient sum").c_str(), grad, 0.);
  }
} // namespace

int main()
{
  check_kernel<CubicSplineKernel>(0.9, 2e-3);
  check_kernel<WendlandC2Kernel>(0.8, 5e-3);
  if (sluice::unit::failures == 0)
    std::printf("sph kernels: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
