// The SPH fluid's two steps (sph_solver.h): the leap-frog and Monaghan's
// predictor-corrector, on a shear wave u_x = U sin(k z) in a fully periodic
// box (8 x 8 x 16 spacings, one wavelength along z, no gravity) with a
// viscosity high enough (nu k^2 dt = 0.015 at the coarsest step) that the
// time error stands well above round-off, and a sound speed low enough
// (c_s dt / h = 0.23) that the acoustic noise is resolved by every step
// compared (at c_s = 5 m/s and the same steps the ratios below wander from
// 3.3 to 6):
// - each is second order in time: run to T at dt, dt/2, dt/4, the
//   differences of successive runs fall by 4 (between 3.5 and 4.5; measured
//   3.95 and 4.02);
// - each decays the wave at the rate the viscous equation gives,
//   exp(-nu k^2 T), within 1.5% of the rate (measured 0.9% slow, the weak
//   compressibility's share: 2.6% at c_s = 1 m/s, 0.2% at 5 m/s);
// - each keeps the fluid's momentum, zero for the wave, to round-off;
// - the two converge to each other: their difference at dt/4 is a
//   sixteenth of that at dt (within 3.5 to 4.5 a halving);
// - with a fixed smoothing length (SphSettings::fixed_smoothing_length) the
//   leap-frog keeps every particle's h to the bit and Omega = 1, and decays
//   the wave as the variable h does (the lattice's density is uniform).

#include <sluice/core/scene_parameters.h>
#include <sluice/sph/sph_setup.h>
#include <sluice/sph/sph_solver.h>

#include "check.h"

#include <cmath>
#include <cstdio>
#include <vector>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double dx = 1e-3, rho_0 = 1000., mu = 1., U = 0.01;
  const double pi = 3.14159265358979323846, k = 2. * pi / (16. * dx);
  const double T = 0.01, dt = 1e-4; // 100 steps at the coarsest

  SceneParameters periodic_box()
  {
    SceneParameters p;
    p.file_name        = "unit.sph_integrator";
    p.lower_corner     = Vec3();
    p.upper_corner     = Vec3(8 * dx, 8 * dx, 16 * dx);
    p.periodic         = {{true, true, true}};
    p.gravity          = Vec3();
    p.sph.spacing      = dx;
    p.sph.density      = rho_0;
    p.sph.viscosity    = mu;
    p.sph.sound_speed  = 3.5;
    p.sph.fluid_lower  = Vec3();
    p.sph.fluid_upper  = p.upper_corner;
    return p;
  }

  /// The fluid particles after T in steps of T / n_steps.
  SphParticles run_wave(const SphIntegrator integrator, const unsigned int n_steps,
                        const bool fixed_h = false)
  {
    SphSetup setup                        = make_sph_setup(periodic_box());
    setup.settings.integrator             = integrator;
    setup.settings.fixed_smoothing_length = fixed_h;
    SphParticles &P                       = setup.particles;
    for (unsigned int a = 0; a < P.n_local; ++a)
      P.velocity[a] = Vec3(U * std::sin(k * P.position[a].z), 0., 0.);
    SphSolver solver(setup.particles, setup.box, setup.settings);
    for (unsigned int s = 0; s < n_steps; ++s)
      solver.step(T / n_steps);
    return solver.particles();
  }

  /// Their velocities alone.
  std::vector<Vec3> run(const SphIntegrator integrator, const unsigned int n_steps)
  {
    const SphParticles Q = run_wave(integrator, n_steps);
    return {Q.velocity.begin(), Q.velocity.begin() + Q.n_local};
  }

  double largest_difference(const std::vector<Vec3> &u, const std::vector<Vec3> &v)
  {
    double largest = 0.;
    for (std::size_t a = 0; a < u.size(); ++a)
      largest = std::max(largest, norm(u[a] - v[a]));
    return largest;
  }

  /// The wave's amplitude: 2 <u_x sin(k z)> at the particles' start positions.
  double amplitude(const std::vector<Vec3> &u)
  {
    const SphSetup setup = make_sph_setup(periodic_box());
    double         sum   = 0.;
    for (std::size_t a = 0; a < u.size(); ++a)
      sum += u[a].x * std::sin(k * setup.particles.position[a].z);
    return 2. * sum / u.size();
  }

  void check_integrator(const SphIntegrator integrator, const char *name,
                        std::vector<Vec3> &at_dt, std::vector<Vec3> &at_quarter)
  {
    const unsigned int      n = static_cast<unsigned int>(std::lround(T / dt));
    const std::vector<Vec3> u1 = run(integrator, n), u2 = run(integrator, 2 * n),
                            u4 = run(integrator, 4 * n);
    const double e1 = largest_difference(u1, u2), e2 = largest_difference(u2, u4);
    std::printf("%s: |u(dt) - u(dt/2)| = %.3e, |u(dt/2) - u(dt/4)| = %.3e, ratio %.3f\n", name,
                e1, e2, e1 / e2);
    check(e1 / e2 > 3.5 && e1 / e2 < 4.5, "second order in time: the differences' ratio",
          e1 / e2, 4.);
    check(e2 > 1e-12 * U, "the time error above round-off", e2, 1e-12 * U);

    const double decay    = amplitude(u4) / U;
    const double expected = std::exp(-mu / rho_0 * k * k * T);
    std::printf("%s: amplitude decayed to %.6f, the viscous equation %.6f\n", name, decay,
                expected);
    check(std::abs(std::log(decay) / std::log(expected) - 1.) < 0.015,
          "the viscous decay rate, relative to nu k^2", std::log(decay) / std::log(expected), 1.);

    Vec3 momentum(0., 0., 0.);
    for (const Vec3 &v : u4)
      momentum += v;
    check(norm(momentum) < 1e-13 * U * u4.size(), "the momentum kept (sum of v, equal masses)",
          norm(momentum), 0.);
    at_dt      = u1;
    at_quarter = u4;
  }

  void check_fixed_smoothing_length()
  {
    const unsigned int n = static_cast<unsigned int>(std::lround(T / dt));
    SphSetup           start = make_sph_setup(periodic_box());
    const SphSolver    at_start(start.particles, start.box, start.settings);
    const SphParticles fixed    = run_wave(SphIntegrator::leap_frog, n, true);
    const SphParticles variable = run_wave(SphIntegrator::leap_frog, n, false);
    bool               kept = true;
    double             h_spread = 0.;
    for (unsigned int a = 0; a < fixed.n_local; ++a)
      {
        kept     = kept && fixed.smoothing[a] == at_start.particles().smoothing[a] &&
               fixed.omega[a] == 1.;
        h_spread = std::max(h_spread, std::abs(variable.smoothing[a] / fixed.smoothing[a] - 1.));
      }
    std::printf("fixed h: every h kept and Omega = 1: %s; the variable h moved by %.1e\n",
                kept ? "yes" : "NO", h_spread);
    check(kept, "fixed h: every h to the bit, Omega = 1", kept, 1.);
    const std::vector<Vec3> u_fixed(fixed.velocity.begin(),
                                    fixed.velocity.begin() + fixed.n_local);
    const std::vector<Vec3> u_variable(variable.velocity.begin(),
                                       variable.velocity.begin() + variable.n_local);
    const double ratio = std::log(amplitude(u_fixed) / U) / std::log(amplitude(u_variable) / U);
    std::printf("fixed h: decay rate / the variable h's %.6f\n", ratio);
    check(std::abs(ratio - 1.) < 1e-3, "fixed h: the variable h's decay", ratio, 1.);
  }
} // namespace

int main()
{
  std::vector<Vec3> leap_frog_dt, leap_frog_quarter, pc_dt, pc_quarter;
  check_integrator(SphIntegrator::leap_frog, "leap-frog", leap_frog_dt, leap_frog_quarter);
  check_integrator(SphIntegrator::predictor_corrector, "predictor-corrector", pc_dt, pc_quarter);
  const double apart_dt      = largest_difference(leap_frog_dt, pc_dt);
  const double apart_quarter = largest_difference(leap_frog_quarter, pc_quarter);
  std::printf("leap-frog against predictor-corrector: %.3e at dt, %.3e at dt/4\n", apart_dt,
              apart_quarter);
  check(apart_dt / apart_quarter > 3.5 * 3.5 && apart_dt / apart_quarter < 4.5 * 4.5,
        "the two steps converge to each other at second order", apart_dt / apart_quarter, 16.);
  check_fixed_smoothing_length();
  return sluice::unit::failures == 0 ? 0 : 1;
}
