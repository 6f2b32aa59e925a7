#pragma once
// The validation measurements of a clump scene (doc/clumps.md), on body 0:
//   - clump_impact: a clump falls onto a plane wall and touches it with one
//     member; its velocity and angular velocity after the impact against an
//     independent integration of the same rigid body with one contact point
//     (the plane motion of its centroid and its turn about the axis normal to
//     that plane, classical Runge-Kutta with steps 20 times shorter, the same
//     normal force law; no quaternions, no member expansion, no lists).
//   - clump_rotation: a torque-free asymmetric body spun near its
//     intermediate axis flips over and over; the mean time between flips
//     against the closed form 2 K(m) / lambda (rigid_rotation.h), with the
//     drift per turn of its energy and of its angular momentum in space.

#include <sluice/dem/dem_system.h>
#include <sluice/dem/validation.h>

#include <vector>

namespace sluice
{
  class ClumpValidation
  {
  public:
    explicit ClumpValidation(const SceneParameters &parameters);

    bool active() const
    {
      return parameters.validation == ValidationCase::clump_impact ||
             parameters.validation == ValidationCase::clump_rotation;
    }

    /// After every step, and once at the start (collective).
    void observe(const DemSystem &dem);
    /// At the end (collective).
    ValidationResult finish(const DemSystem &dem) const;

    std::vector<double> state() const;
    void                set_state(const std::vector<double> &numbers);

  private:
    /// Body 0 as every rank sees it (whichever rank owns it).
    struct Body
    {
      Vec3            x, v, w;
      Eigen::Vector4d q = Eigen::Vector4d(1., 0., 0., 0.); // w, x, y, z
      Eigen::Vector3d L = Eigen::Vector3d::Zero();        // body frame
      Eigen::Vector3d I = Eigen::Vector3d::Ones();
      double          mass = 0.;
    };
    static Body gather_body(const DemSystem &dem);
    ValidationResult finish_impact(const DemSystem &dem) const;
    ValidationResult finish_rotation() const;

    const SceneParameters &parameters;
    bool                   started = false;
    Body                   initial;
    // clump_rotation: where L_2 changed sign, and the energy's means over the
    // first and the last turn.
    std::vector<double> crossings;
    double              previous_time = 0., previous_L2 = 0.;
    double first_turn_energy = 0., last_turn_energy = 0., first_turn_steps = 0.,
           last_turn_steps = 0., last_momentum_error = 0.;
  };
} // namespace sluice
