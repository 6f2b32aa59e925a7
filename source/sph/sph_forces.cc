// The momentum side of an SPH step (see the header).

#include <sluice/sph/sph_density.h>
#include <sluice/sph/sph_forces.h>
#include <sluice/sph/sph_kernel.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  double TaitEquation::pressure(const double density, const double porosity) const
  {
    const double B = reference_density * sound_speed * sound_speed / exponent;
    return B * (std::pow(density / (porosity * reference_density), exponent) - 1.);
  }

  double TaitEquation::density(const double pressure, const double porosity) const
  {
    const double B = reference_density * sound_speed * sound_speed / exponent;
    return porosity * reference_density * std::pow(1. + pressure / B, 1. / exponent);
  }

  void pressures(SphParticles &P, const TaitEquation &state)
  {
    for (unsigned int a = 0; a < P.size(); ++a)
      P.pressure[a] = state.pressure(P.density[a], P.porosity[a]);
  }

  namespace
  {
    /// The accelerations with the viscous form and the formulation fixed at
    /// compile time: the pair loop has no branch on them. model_a: the
    /// pressure and viscous terms on each particle scaled by its own fluid
    /// fraction (SphForceParameters::stress_times_fluid_fraction).
    template <typename Kernel, SphViscosityForm form, bool model_a>
    void accumulate(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                    const SphForceParameters &parameters,
                    const std::vector<Vec3> &viscous_velocity, const SphPairKernels &kernels)
    {
      for (unsigned int a = 0; a < P.n_local; ++a)
        P.acceleration[a] = parameters.gravity;
      const double mu = parameters.viscosity, c_s = parameters.state.sound_speed;
      for (unsigned int a = 0; a < P.n_local; ++a)
        {
          const double pa = P.pressure[a] / (P.omega[a] * P.density[a] * P.density[a]);
          for (unsigned int k = pairs.offset[a]; k < pairs.offset[a + 1]; ++k)
            {
              const unsigned int b = pairs.partner[k];
              const double       r = kernels.r[k];
              // A pair in the list's skin, beyond both supports: every term
              // below has a kernel factor that vanishes there.
              if (!(r > 0.) || !(r < Kernel::support * std::max(P.smoothing[a], P.smoothing[b])))
                continue;
              Vec3 d = P.position[a] - P.position[b];
              if (box.any_periodic)
                d = box.minimum_image(d);
              const double r2 = norm_square(d);
              const double pb = P.pressure[b] / (P.omega[b] * P.density[b] * P.density[b]);
              // grad_a W(r, h) = W'(r, h) d / r; W' <= 0.
              const double pressure_term = pa * kernels.dW_a[k] + pb * kernels.dW_b[k];
              const double h_mean = 0.5 * (P.smoothing[a] + P.smoothing[b]);
              const Vec3 v_ab = viscous_velocity[a] - viscous_velocity[b];
              // The pressure and physical viscous part; in model A each side
              // takes it at its own fluid fraction, below.
              const Vec3 stress =
                (-pressure_term / r) * d +
                viscous_pair_acceleration<form, Kernel>(d, r, r2, h_mean, v_ab, P.density[a],
                                                        P.density[b], mu, c_s);
              Vec3 pair_force = model_a ? Vec3() : stress;
              const bool tension = P.pressure[a] < 0. || P.pressure[b] < 0.;
              if (parameters.artificial_pressure > 0. && tension)
                {
                  const double R = parameters.artificial_pressure *
                                   (std::max(-P.pressure[a], 0.) / (P.density[a] * P.density[a]) +
                                    std::max(-P.pressure[b], 0.) / (P.density[b] * P.density[b]));
                  const double f =
                    kernel_value<Kernel>(r, h_mean) /
                    kernel_value<Kernel>(h_mean / parameters.smoothing_factor, h_mean);
                  const double f4 = (f * f) * (f * f);
                  pair_force += (-R * f4 * kernel_radial_derivative<Kernel>(r, h_mean) / r) * d;
                }
              // The walls' own velocities: their no-slip extrapolation is for the
              // physical viscosity only (Adami et al. 2012); seen here it would
              // add a friction of order alpha c_s h at every wall.
              const double approach = dot(P.velocity[a] - P.velocity[b], d);
              if (parameters.artificial_viscosity > 0. && approach < 0.)
                {
                  const double Pi = -parameters.artificial_viscosity *
                                    parameters.state.sound_speed * h_mean * approach /
                                    (0.5 * (P.density[a] + P.density[b]) *
                                     (r2 + 0.01 * h_mean * h_mean));
                  pair_force += (-Pi * kernel_radial_derivative<Kernel>(r, h_mean) / r) * d;
                }
              // Per unit mass of each: m_b on a, -m_a on b. Model A: a takes
              // the stresses at eps_a, b at eps_b; the pair is then no longer
              // antisymmetric, the rest of the momentum going to the grains
              // through their -V grad p.
              Vec3 on_a = pair_force, on_b = pair_force;
              if constexpr (model_a)
                {
                  on_a += P.porosity[a] * stress;
                  on_b += P.porosity[b] * stress;
                }
              P.acceleration[a] += P.mass[b] * on_a;
              if (b < P.n_local)
                P.acceleration[b] -= P.mass[a] * on_b;
            }
        }
    }
  } // namespace

  template <typename Kernel>
  void accelerations(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                     const SphForceParameters &parameters,
                     const std::vector<Vec3> &viscous_velocity, const SphPairKernels &kernels)
  {
    constexpr auto signal = SphViscosityForm::signal_velocity, morris = SphViscosityForm::morris;
    const bool     signal_velocity = parameters.viscosity_form == signal;
    if (parameters.stress_times_fluid_fraction)
      {
        if (signal_velocity)
          accumulate<Kernel, signal, true>(P, pairs, box, parameters, viscous_velocity, kernels);
        else
          accumulate<Kernel, morris, true>(P, pairs, box, parameters, viscous_velocity, kernels);
      }
    else if (signal_velocity)
      accumulate<Kernel, signal, false>(P, pairs, box, parameters, viscous_velocity, kernels);
    else
      accumulate<Kernel, morris, false>(P, pairs, box, parameters, viscous_velocity, kernels);
  }

  template <typename Kernel>
  void accelerations(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                     const SphForceParameters &parameters,
                     const std::vector<Vec3> &viscous_velocity)
  {
    SphPairKernels kernels;
    pair_kernels<Kernel>(P, pairs, box, kernels);
    accelerations<Kernel>(P, pairs, box, parameters, viscous_velocity, kernels);
  }

#define SLUICE_SPH_ACCELERATIONS(Kernel)                                                          \
  template void accelerations<Kernel>(SphParticles &, const SphPairs &, const PeriodicBox &,      \
                                      const SphForceParameters &, const std::vector<Vec3> &,      \
                                      const SphPairKernels &);                                    \
  template void accelerations<Kernel>(SphParticles &, const SphPairs &, const PeriodicBox &,      \
                                      const SphForceParameters &, const std::vector<Vec3> &);
  SLUICE_SPH_ACCELERATIONS(CubicSplineKernel)
  SLUICE_SPH_ACCELERATIONS(WendlandC2Kernel)
#undef SLUICE_SPH_ACCELERATIONS
} // namespace sluice
