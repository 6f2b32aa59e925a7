// The fields a DEM particle feels, at the SPH particles (see the header).

#include <sluice/sph/sph_fluid_fields.h>
#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_viscosity.h>

#include <cmath>

namespace sluice
{
  namespace
  {
    /// The pressure force's bracket of the pair (a, b) at distance r, d = x_a - x_b,
    /// with the kernels' radial derivatives at h_a and h_b, as in sph_forces.cc.
    Vec3 pressure_bracket(const SphParticles &P, const unsigned int a, const unsigned int b,
                          const Vec3 &d, const double r, const double dWa, const double dWb)
    {
      const double pa = P.pressure[a] / (P.omega[a] * P.density[a] * P.density[a]);
      const double pb = P.pressure[b] / (P.omega[b] * P.density[b] * P.density[b]);
      return ((pa * dWa + pb * dWb) / r) * d;
    }
  } // namespace

  namespace
  {
    /// The fields with the viscous form fixed at compile time.
    template <typename Kernel, SphViscosityForm form>
    SphFluidFields fluid_fields_of_form(const SphParticles &P, const SphPairs &pairs,
                                        const PeriodicBox &box,
                                        const SphForceParameters &parameters,
                                        const std::vector<Vec3> &velocity)
    {
      const unsigned int n = P.n_local;
      SphFluidFields     F;
      F.pressure_gradient.assign(n, Vec3());
      F.viscous_divergence.assign(n, Vec3());
      F.porosity_gradient.assign(n, Vec3());
      for (auto &row : F.velocity_gradient)
        row.assign(n, Vec3());
      const double mu = parameters.viscosity, c_s = parameters.state.sound_speed;
      // Each pair once: its share to a, and to b when b is owned.
      const auto add = [&](const unsigned int a, const unsigned int b, const Vec3 &pressure_sum,
                           const Vec3 &viscous_sum, const Vec3 &grad_W_a) {
        if (P.wall[a])
          return;
        F.pressure_gradient[a] += P.mass[b] * pressure_sum;
        F.viscous_divergence[a] += P.mass[b] * viscous_sum;
        const double V_b = P.mass[b] / P.density[b];
        const Vec3   du  = velocity[b] - velocity[a];
        for (unsigned int i = 0; i < 3; ++i)
          F.velocity_gradient[i][a] += (V_b * du[i]) * grad_W_a;
        if (!P.wall[b])
          F.porosity_gradient[a] += (V_b * (P.porosity[b] - P.porosity[a])) * grad_W_a;
      };
      for_each_pair(P, pairs, box, [&](const unsigned int a, const unsigned int b, const Vec3 &d,
                                       const double r) {
        if (!(r > 0.))
          return;
        const double dWa    = kernel_radial_derivative<Kernel>(r, P.smoothing[a]);
        const double dWb    = kernel_radial_derivative<Kernel>(r, P.smoothing[b]);
        const double h_mean = 0.5 * (P.smoothing[a] + P.smoothing[b]);
        // The pressure force's bracket and the viscous term, as in sph_forces.cc.
        const Vec3 pressure_sum = pressure_bracket(P, a, b, d, r, dWa, dWb);
        const Vec3 v_ab         = velocity[a] - velocity[b];
        const Vec3 viscous_sum  = viscous_pair_acceleration<form, Kernel>(
          d, r, r * r, h_mean, v_ab, P.density[a], P.density[b], mu, c_s);
        add(a, b, pressure_sum, viscous_sum, (dWa / r) * d);
        if (b < n)
          add(b, a, -pressure_sum, -viscous_sum, (-dWb / r) * d);
      });
      for (unsigned int a = 0; a < n; ++a)
        {
          F.pressure_gradient[a] *= P.density[a];
          F.viscous_divergence[a] *= P.density[a];
        }
      return F;
    }
  } // namespace

  template <typename Kernel>
  SphFluidFields fluid_fields(const SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                              const SphForceParameters &parameters,
                              const std::vector<Vec3> &velocity)
  {
    if (parameters.viscosity_form == SphViscosityForm::signal_velocity)
      return fluid_fields_of_form<Kernel, SphViscosityForm::signal_velocity>(P, pairs, box,
                                                                             parameters, velocity);
    return fluid_fields_of_form<Kernel, SphViscosityForm::morris>(P, pairs, box, parameters,
                                                                  velocity);
  }

  template <typename Kernel>
  std::vector<Vec3> pressure_gradients(const SphParticles &P, const SphPairs &pairs,
                                       const PeriodicBox &box)
  {
    // The pairs in fluid_fields' order, so that the sums round alike.
    const unsigned int n = P.n_local;
    std::vector<Vec3>  grad_p(n, Vec3());
    for_each_pair(P, pairs, box, [&](const unsigned int a, const unsigned int b, const Vec3 &d,
                                     const double r) {
      if (!(r > 0.))
        return;
      const Vec3 s = pressure_bracket(P, a, b, d, r,
                                      kernel_radial_derivative<Kernel>(r, P.smoothing[a]),
                                      kernel_radial_derivative<Kernel>(r, P.smoothing[b]));
      if (!P.wall[a])
        grad_p[a] += P.mass[b] * s;
      if (b < n && !P.wall[b])
        grad_p[b] += P.mass[a] * (-s);
    });
    for (unsigned int a = 0; a < n; ++a)
      grad_p[a] *= P.density[a];
    return grad_p;
  }

#define SLUICE_INSTANTIATE(Kernel)                                                                \
  template std::vector<Vec3> pressure_gradients<Kernel>(const SphParticles &, const SphPairs &,  \
                                                        const PeriodicBox &);                     \
  template SphFluidFields fluid_fields<Kernel>(const SphParticles &, const SphPairs &,            \
                                               const PeriodicBox &, const SphForceParameters &,   \
                                               const std::vector<Vec3> &);
  SLUICE_INSTANTIATE(CubicSplineKernel)
  SLUICE_INSTANTIATE(WendlandC2Kernel)
#undef SLUICE_INSTANTIATE
} // namespace sluice
