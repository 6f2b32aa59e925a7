#pragma once
// The physical viscosity between two SPH particles a and b, in one of two
// forms, as the acceleration it gives a per unit mass of b (doc/sph.md).
// d = x_a - x_b, v_ab = v_a - v_b, hbar = (h_a + h_b) / 2, rho the SPH
// (superficial) densities, mu the dynamic viscosity.
//   - Morris, Fox & Zhu (1997, J. Comput. Phys. 136, 214, Eq. 8):
//       2 mu / (rho_a rho_b) (d . grad_a W(r, hbar)) / (r^2 + 0.01 hbar^2) v_ab,
//     along v_ab; it keeps linear momentum.
//   - Monaghan's (1997, J. Comput. Phys. 136, 298) signal-velocity form, tied
//     to mu as Robinson, Ramaioli & Luding (2014, Eqs. 13-14) do:
//       -Pi_ab grad_a W(r, hbar),  Pi_ab = -K v_sig w / rhobar,
//       w = v_ab . d / r,  v_sig = 2 (c_s + |w|).
//     Its continuum limit (v_b - v_a expanded to second order, the angular
//     mean of four unit vectors taken) is nu lap v + 2 nu grad div v with
//       nu = (dim + 1) K v_sig <r> / (2 dim (dim + 2)) = (2/15) K v_sig <r>,
//     <r> = kappa hbar the kernel's mean distance (5/6 for Wendland C2,
//     31/35 for the cubic spline, sph_kernel.h). So K 2 c_s = 15 nu /
//     (2 kappa hbar) at low Mach number and, with nu / rhobar written
//     mu / (rho_a rho_b) as in Morris' form,
//       Pi_ab = -15 mu (1 + |w| / c_s) w / (2 kappa hbar rho_a rho_b).
//     The pair force is central: it keeps angular momentum as well, and a
//     rigid rotation feels none.

#include <sluice/core/vector3.h>
#include <sluice/sph/sph_kernel.h>

#include <cmath>

namespace sluice
{
  enum class SphViscosityForm
  {
    morris,
    signal_velocity
  };

  /// The pair's viscous acceleration of a per unit mass of b; r2 is the
  /// squared distance as the caller computed it (Morris' denominator).
  template <SphViscosityForm form, typename Kernel>
  inline Vec3 viscous_pair_acceleration(const Vec3 &d, const double r, const double r2,
                                        const double h_mean, const Vec3 &v_ab,
                                        const double rho_a, const double rho_b,
                                        const double mu, const double sound_speed)
  {
    const double dW = kernel_radial_derivative<Kernel>(r, h_mean);
    if constexpr (form == SphViscosityForm::morris)
      return (2. * mu / (rho_a * rho_b) * dW * r / (r2 + 0.01 * h_mean * h_mean)) * v_ab;
    else
      {
        const double w  = dot(v_ab, d) / r;
        const double Pi = -15. * mu * (1. + std::abs(w) / sound_speed) * w /
                          (2. * Kernel::mean_distance * h_mean * rho_a * rho_b);
        return (-Pi * dW / r) * d;
      }
  }
} // namespace sluice
