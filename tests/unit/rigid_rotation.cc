// The rigid-body rotation of dem/rigid_rotation.h (the clumps' integrator):
// - torque-free rotation of an asymmetric body (I = 1, 2, 3) started near its
//   intermediate axis flips over and over (the Dzhanibekov effect): the time
//   between flips against the closed form 2 K(m) / lambda (Landau & Lifshitz,
//   Mechanics §37, the case M^2 < 2 E I_2) within 0.5%, and converging as dt^2;
//   the angular momentum in space kept to round-off, |q| = 1 to round-off, the
//   energy error bounded with no drift above 1e-8 per turn;
// - a constant torque on a body with equal moments from rest: the angular
//   momentum tau t and the angle tau t^2 / (2 I) exact (kick, rotate, kick).

#include <sluice/dem/rigid_rotation.h>

#include "check.h"

#include <cmath>
#include <vector>

using namespace sluice;
using sluice::unit::check;

namespace
{
  struct FlipRun
  {
    double flip_time = 0., closed_form = 0., max_energy_error = 0., energy_drift_per_turn = 0.;
    double momentum_error = 0., norm_error = 0.;
  };

  /// Torque-free rotation with 'steps_per_turn' steps per turn about the
  /// intermediate axis, for 'flips' flips.
  FlipRun run_flips(const unsigned int steps_per_turn, const unsigned int flips)
  {
    const PrincipalInertia I(1., 2., 3.);
    const double           w2 = 2. * M_PI, w1 = 0.1 * w2;
    RigidRotation          r;
    r.orientation   = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
    r.body_momentum = Eigen::Vector3d(I[0] * w1, I[1] * w2, 0.);
    const double          E  = rotational_energy(r, I);
    const Eigen::Vector3d L0 = r.orientation * r.body_momentum;
    // M^2 < 2 E I_2: omega_2 ~ sn, which changes sign every 2 K / lambda.
    FlipRun run;
    run.closed_form = intermediate_axis_flip_time(I, r.body_momentum);

    const double        dt = 1. / steps_per_turn; // a turn about axis 2 takes 1 s
    std::vector<double> crossings;
    double              w_previous = r.body_momentum[1] / I[1], t = 0.;
    double              first_turn_mean = 0., last_turn_mean = 0.;
    const unsigned long n_steps = std::ceil((flips + 1.5) * run.closed_form / dt);
    const unsigned long last_turn_start = n_steps - steps_per_turn;
    for (unsigned long s = 1; s <= n_steps; ++s)
      {
        rotate_freely(r, I, dt); // no torque: the kicks do nothing
        t += dt;
        const double w = r.body_momentum[1] / I[1];
        if ((w < 0.) != (w_previous < 0.))
          crossings.push_back(t - dt * w / (w - w_previous));
        w_previous = w;
        const double e = (rotational_energy(r, I) - E) / E;
        run.max_energy_error = std::max(run.max_energy_error, std::abs(e));
        if (s <= steps_per_turn)
          first_turn_mean += e / steps_per_turn;
        if (s > last_turn_start)
          last_turn_mean += e / steps_per_turn;
      }
    run.flip_time = (crossings.back() - crossings.front()) / (crossings.size() - 1);
    run.energy_drift_per_turn = std::abs(last_turn_mean - first_turn_mean) / (t - 1.);
    run.momentum_error        = (r.orientation * r.body_momentum - L0).norm() / L0.norm();
    run.norm_error            = std::abs(r.orientation.norm() - 1.);
    return run;
  }

  void check_flips()
  {
    const FlipRun coarse = run_flips(400, 10), fine = run_flips(800, 10);
    const double  e_coarse = std::abs(coarse.flip_time / coarse.closed_form - 1.);
    const double  e_fine   = std::abs(fine.flip_time / fine.closed_form - 1.);
    std::printf("flip: time between flips %.9f s (closed form %.9f s), error %.2e at 400 "
                "steps per turn, %.2e at 800 (order %.2f)\n",
                fine.flip_time, fine.closed_form, e_coarse, e_fine, std::log2(e_coarse / e_fine));
    std::printf("flip: energy error max %.2e, drift %.2e per turn; angular momentum %.2e; "
                "|q| - 1 %.2e\n",
                fine.max_energy_error, fine.energy_drift_per_turn, fine.momentum_error,
                fine.norm_error);
    check(e_fine < 5e-3, "time between flips against 2 K / lambda", fine.flip_time,
          fine.closed_form);
    check(std::log2(e_coarse / e_fine) > 1.8, "flip time converges as dt^2",
          std::log2(e_coarse / e_fine), 2.);
    check(fine.energy_drift_per_turn < 1e-8, "energy drift per turn", fine.energy_drift_per_turn,
          0.);
    check(fine.max_energy_error < 1e-3, "energy error bounded", fine.max_energy_error, 0.);
    check(fine.momentum_error < 1e-12, "angular momentum in space kept", fine.momentum_error, 0.);
    check(fine.norm_error < 1e-14, "|q| = 1", fine.norm_error, 0.);
  }

  void check_constant_torque()
  {
    const PrincipalInertia I(2., 2., 2.);
    const Eigen::Vector3d  tau(0., 0., 0.5);
    RigidRotation          r;
    const double           dt = 1e-3;
    for (unsigned int s = 0; s < 2000; ++s)
      {
        kick_rotation(r, tau, 0.5 * dt);
        rotate_freely(r, I, dt);
        kick_rotation(r, tau, 0.5 * dt);
      }
    const double t = 2., angle = tau.z() * t * t / (2. * I[2]);
    const Eigen::AngleAxisd turned(r.orientation);
    check(std::abs((r.orientation * r.body_momentum).z() - tau.z() * t) < 1e-12,
          "angular momentum tau t", (r.orientation * r.body_momentum).z(), tau.z() * t);
    check(std::abs(turned.angle() * turned.axis().z() - angle) < 1e-12, "angle tau t^2 / (2 I)",
          turned.angle() * turned.axis().z(), angle);
  }
} // namespace

int main()
{
  check_flips();
  check_constant_torque();
  if (sluice::unit::failures == 0)
    std::printf("rigid rotation: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
