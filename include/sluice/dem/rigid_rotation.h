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

  /// q u q* for the unit quaternion (w, x): Eigen's own formula
  /// (Quaternion::_transformVector, t = 2 x cross u, u + w t + x cross t), written
  /// out for the bodies' lanes; the same numbers as Eigen's q * u.
  inline void rotate_vector(const double w, const double x[3], const double u[3], double out[3])
  {
    double t[3] = {x[1] * u[2] - x[2] * u[1], x[2] * u[0] - x[0] * u[2], x[0] * u[1] - x[1] * u[0]};
    for (double &ti : t)
      ti += ti;
    const double c[3] = {x[1] * t[2] - x[2] * t[1], x[2] * t[0] - x[0] * t[2],
                         x[0] * t[1] - x[1] * t[0]};
    for (unsigned int d = 0; d < 3; ++d)
      out[d] = u[d] + w * t[d] + c[d];
  }

  /// Half kick: L += h R^T tau, tau the torque in space [N m].
  inline void kick_rotation(RigidRotation &r, const Eigen::Vector3d &torque, const double h)
  {
    r.body_momentum += h * (r.orientation.conjugate() * torque);
  }

  /// sin x and cos x. A step turns a body by a small angle, where the Taylor
  /// series to x^9 / 9! is exact to round-off (|x| < 0.05: the next term is
  /// below 1e-17 of the sum) and several times cheaper than the library's.
  inline void sin_cos(const double x, double &s, double &c)
  {
    if (std::abs(x) < 0.05)
      {
        // Horner's scheme on the series' coefficients (multiplications only).
        const double x2 = x * x;
        s = x * (1. + x2 * (-1. / 6. + x2 * (1. / 120. + x2 * (-1. / 5040. + x2 * (1. / 362880.)))));
        c = 1. + x2 * (-0.5 + x2 * (1. / 24. + x2 * (-1. / 720. + x2 * (1. / 40320. -
                                                                         x2 * (1. / 3628800.)))));
        return;
      }
    s = std::sin(x);
    c = std::cos(x);
  }

  /// The orientations (w, v) and body-frame momenta L of up to N bodies,
  /// lane by lane, for the free rotation of several bodies at once.
  template <unsigned int N>
  struct RotationLanes
  {
    double w[N], v[3][N], L[3][N], I[3][N];
  };

  /// The five factors of the free rotation over dt (the splitting above) for
  /// every lane. Each factor turns q by the unit quaternion (cos(phi/2),
  /// sin(phi/2) e_k) and L by -phi about e_k, written out: one sincos per
  /// factor, no general rotation. A body's five factors form one chain of
  /// dependent divisions and series; the lanes' chains are independent, so
  /// side by side they overlap. Lane by lane the arithmetic is the same
  /// whatever N.
  template <unsigned int N>
  inline void rotate_lanes_freely(RotationLanes<N> &r, const double dt)
  {
    const auto about = [&r](const unsigned int k, const double h) {
      const unsigned int i = (k + 1) % 3, j = (k + 2) % 3;
      for (unsigned int l = 0; l < N; ++l)
        {
          const double half = 0.5 * h * r.L[k][l] / r.I[k][l];
          double       s, c;
          sin_cos(half, s, c);
          // q (c, s e_k) = (c w - s v_k, c v + s (w e_k + v x e_k)).
          const double w = r.w[l], vk = r.v[k][l], vi = r.v[i][l], vj = r.v[j][l];
          r.w[l]    = c * w - s * vk;
          r.v[k][l] = c * vk + s * w;
          r.v[i][l] = c * vi + s * vj;
          r.v[j][l] = c * vj - s * vi;
          // L turned by -phi about e_k, in the plane of the other two axes.
          const double cos_phi = c * c - s * s, sin_phi = 2. * s * c;
          const double Li = r.L[i][l], Lj = r.L[j][l];
          r.L[i][l] = cos_phi * Li + sin_phi * Lj;
          r.L[j][l] = cos_phi * Lj - sin_phi * Li;
        }
    };
    about(0, 0.5 * dt);
    about(1, 0.5 * dt);
    about(2, dt);
    about(1, 0.5 * dt);
    about(0, 0.5 * dt);
  }

  /// The free rotation of one body over dt (the splitting above).
  inline void rotate_freely(RigidRotation &r, const PrincipalInertia &I, const double dt)
  {
    RotationLanes<1> lane;
    lane.w[0] = r.orientation.w();
    for (unsigned int d = 0; d < 3; ++d)
      {
        lane.v[d][0] = r.orientation.vec()[d];
        lane.L[d][0] = r.body_momentum[d];
        lane.I[d][0] = I[d];
      }
    rotate_lanes_freely(lane, dt);
    // Round-off only: each factor is a unit quaternion.
    r.orientation =
      Eigen::Quaterniond(lane.w[0], lane.v[0][0], lane.v[1][0], lane.v[2][0]).normalized();
    r.body_momentum = Eigen::Vector3d(lane.L[0][0], lane.L[1][0], lane.L[2][0]);
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
