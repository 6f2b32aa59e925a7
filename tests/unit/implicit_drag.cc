// The per-particle drag update for stiff coupling (include/sluice/coupling/
// implicit_drag.h) against the analytic Stokes sedimentation curve
// v(t) = v_t (1 - exp(-t / tau_p)) (../shared/reference/REFERENCE.md §4):
//  - steps of tau_p / 3 follow the curve to round-off (the update is exact for a
//    frozen drag coefficient);
//  - one step of 100 tau_p (a glass bead in water + glycerol with the fluid step
//    of a coarse mesh) lands on the terminal velocity, where an explicit update
//    would have amplified the error by 99 per step;
//  - the impulse handed to the fluid equals the closed-form integral of
//    k (u - v) over the step, so particle + fluid momentum is conserved exactly;
//  - no drag is free fall; the switch to the series form at tiny dt k / m is
//    continuous.

#include <sluice/coupling/implicit_drag.h>

#include "check.h"

#include <cmath>
#include <cstdio>
#include <initializer_list>

using namespace sluice;
using unit::check;
using unit::failures;

int main()
{
  // A 0.1 mm glass bead (2500 kg/m^3) in water + 10% glycerol-like fluid:
  // mu = 1.2e-3 Pa s, rho_f = 1030 kg/m^3; Stokes drag k = 3 pi mu d.
  const double d = 1e-4, rho_p = 2500., rho_f = 1030., mu = 1.2e-3, g = 9.81;
  const double volume = M_PI * d * d * d / 6., m = rho_p * volume, k = 3. * M_PI * mu * d;
  const double tau = m / k;
  const Vec3   buoyant_weight(0., 0., -(rho_p - rho_f) * volume * g);
  const double v_t = -(rho_p - rho_f) * g * d * d / (18. * mu); // analytic terminal velocity
  const Vec3   still(0., 0., 0.);

  // Steps of tau / 3 from rest follow the analytic curve.
  Vec3 v;
  for (unsigned int n = 1; n <= 30; ++n)
    {
      v                = integrate_drag(m, k, still, v, buoyant_weight, tau / 3.).velocity;
      const double exact = v_t * (1. - std::exp(-(n * tau / 3.) / tau));
      check(std::abs(v.z - exact) <= 1e-13 * std::abs(v_t), "Stokes curve", v.z, exact);
    }

  // One step of 100 tau from rest: the terminal velocity.
  const DragStep big = integrate_drag(m, k, still, Vec3(0., 0., 0.), buoyant_weight, 100. * tau);
  check(std::abs(big.velocity.z - v_t) <= 1e-14 * std::abs(v_t), "terminal velocity in one step",
        big.velocity.z, v_t);
  // ... also from a velocity far off, and with a moving fluid.
  const Vec3     flow(0.01, 0., 0.02);
  const DragStep off = integrate_drag(m, k, flow, Vec3(1., -2., 3.), buoyant_weight, 100. * tau);
  check(std::abs(off.velocity.x - 0.01) < 1e-15 && std::abs(off.velocity.y) < 1e-15 &&
          std::abs(off.velocity.z - (0.02 + v_t)) < 1e-15,
        "terminal velocity relative to the fluid", off.velocity.z, 0.02 + v_t);

  // The impulse: J = -F dt - m (v0 - v_inf)(1 - exp(-dt/tau)), per component.
  for (const double dt : {tau / 7., tau, 10. * tau, 100. * tau})
    {
      const Vec3     v0(0.3, -0.1, 0.05);
      const DragStep s      = integrate_drag(m, k, flow, v0, buoyant_weight, dt);
      const Vec3     v_inf  = flow + (1. / k) * buoyant_weight;
      const Vec3     closed = -dt * buoyant_weight - m * (1. - std::exp(-dt / tau)) * (v0 - v_inf);
      for (unsigned int c = 0; c < 3; ++c)
        check(std::abs(s.impulse[c] - closed[c]) <= 1e-12 * m * 0.3, "impulse", s.impulse[c],
              closed[c]);
      // particle momentum change = drag impulse + other force * dt
      for (unsigned int c = 0; c < 3; ++c)
        {
          const double balance = m * (s.velocity[c] - v0[c]) - s.impulse[c] - dt * buoyant_weight[c];
          check(std::abs(balance) <= 1e-18, "momentum balance", balance, 0.);
        }
    }

  // No drag: free fall.
  const DragStep fall = integrate_drag(m, 0., flow, Vec3(0., 0., 1.), buoyant_weight, 0.01);
  check(std::abs(fall.velocity.z - (1. + 0.01 * buoyant_weight.z / m)) < 1e-15, "free fall",
        fall.velocity.z, 1. + 0.01 * buoyant_weight.z / m);
  // The two forms agree where they meet (dt k / m = 1e-8).
  const double   dt_switch = 1e-8 * tau;
  const DragStep below = integrate_drag(m, k, flow, Vec3(0.3, 0., 0.), buoyant_weight, dt_switch * 0.999999);
  const DragStep above = integrate_drag(m, k, flow, Vec3(0.3, 0., 0.), buoyant_weight, dt_switch * 1.000001);
  check(std::abs(below.velocity.x - above.velocity.x) < 1e-14, "continuity at the switch",
        below.velocity.x, above.velocity.x);

  std::printf("%s: %d failure(s); tau_p = %.4g s, v_t = %.6g m/s\n",
              failures ? "FAILED" : "passed", failures, tau, v_t);
  return failures ? 1 : 0;
}
