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
} // namespace sluice
