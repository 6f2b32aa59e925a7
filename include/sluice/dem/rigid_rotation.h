#pragma once
// The rotation of a rigid body (a clump of spheres, issue 14) by the
// symplectic splitting of Dullweber, Leimkuhler & McLachlan (1997, J. Chem.
// Phys. 107, 5840; the same map as NO_SQUISH, Miller et al. 2002, J. Chem.
// Phys. 116, 8649). The state is the orientation q (a unit quaternion, body
// to space) and the angular momentum in the body frame L. A torque kicks L
// for a half step; the free rotation is split into exact rotations about the
// body's principal axes,
//   R_1(h/2) R_2(h/2) R_3(h) R_2(h/2) R_1(h/2),
// each turning q by phi_k = h L_k / I_k about body axis k and L by -phi_k.
// Every sub-step is a rotation, so |q| = 1 and the angular momentum in space
// are kept to round-off, and the map is symplectic: the energy error stays
// bounded (O(h^2)) instead of drifting. Angular velocity is L_k / I_k.

#include <Eigen/Geometry>

#include <cmath>

namespace sluice
{
  struct RigidRotation
  {
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity(); // body -> space
    Eigen::Vector3d    body_momentum = Eigen::Vector3d::Zero();      // L in the body frame
  };

  /// The principal moments of inertia I_1, I_2, I_3 (> 0) [kg m^2].
  using PrincipalInertia = Eigen::Vector3d;

  /// Half kick: L += h R^T tau, tau the torque in space [N m].
  inline void kick_rotation(RigidRotation &r, const Eigen::Vector3d &torque, const double h)
  {
    r.body_momentum += h * (r.orientation.conjugate() * torque);
  }

  /// The free rotation over dt (the splitting above).
  inline void rotate_freely(RigidRotation &r, const PrincipalInertia &I, const double dt)
  {
    const auto about = [&](const int k, const double h) {
      const double    phi = h * r.body_momentum[k] / I[k];
      Eigen::Vector3d axis = Eigen::Vector3d::Zero();
      axis[k]              = 1.;
      const Eigen::Quaterniond turn(Eigen::AngleAxisd(phi, axis));
      r.orientation   = r.orientation * turn;
      r.body_momentum = turn.conjugate() * r.body_momentum;
    };
    about(0, 0.5 * dt);
    about(1, 0.5 * dt);
    about(2, dt);
    about(1, 0.5 * dt);
    about(0, 0.5 * dt);
    // Round-off only: each factor is a unit quaternion.
    r.orientation.normalize();
  }

  /// Angular velocity in space [rad/s].
  inline Eigen::Vector3d angular_velocity(const RigidRotation &r, const PrincipalInertia &I)
  {
    return r.orientation * r.body_momentum.cwiseQuotient(I);
  }

  /// Rotational kinetic energy sum L_k^2 / (2 I_k) [J].
  inline double rotational_energy(const RigidRotation &r, const PrincipalInertia &I)
  {
    return 0.5 * r.body_momentum.cwiseProduct(r.body_momentum).cwiseQuotient(I).sum();
  }

  /// The time between two flips of a torque-free asymmetric body (I_1 < I_2
  /// < I_3) spun near its intermediate axis, body-frame momentum L, in the
  /// case M^2 < 2 E I_2: omega_2 is an elliptic sn, which changes sign every
  /// 2 K(m) / lambda (Landau & Lifshitz, Mechanics, section 37). [s]
  inline double intermediate_axis_flip_time(const PrincipalInertia &I, const Eigen::Vector3d &L)
  {
    const double E  = 0.5 * L.cwiseProduct(L).cwiseQuotient(I).sum();
    const double M2 = L.squaredNorm();
    const double lambda =
      std::sqrt((I[1] - I[0]) * (2. * E * I[2] - M2) / (I[0] * I[1] * I[2]));
    const double m = (I[2] - I[1]) * (M2 - 2. * E * I[0]) / ((I[1] - I[0]) * (2. * E * I[2] - M2));
    return 2. * std::comp_ellint_1(std::sqrt(m)) / lambda;
  }
} // namespace sluice
