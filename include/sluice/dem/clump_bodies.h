#pragma once
// The rigid bodies of a clump scene (issue 14; doc/clumps.md): each body's
// centroid position and velocity, its rotation state (rigid_rotation.h), mass
// and principal moments, as contiguous arrays; its members in space follow
// from its template, x_m = x + R r_m and v_m = v + w x (R r_m). The contact
// passes act on the members; their forces and torques gather onto the
// bodies, F = sum F_m and T = sum (R r_m) x F_m + T_m, and the bodies take
// velocity Verlet's half kicks and drift, the rotation by the symplectic
// splitting.

#include <sluice/core/vector3.h>
#include <sluice/dem/clump_template.h>
#include <sluice/dem/rigid_rotation.h>

#include <vector>

namespace sluice
{
  struct ClumpBodies
  {
    std::vector<unsigned int>     template_index;
    std::vector<Vec3>             position, velocity; // of the centroid [m], [m/s]
    std::vector<RigidRotation>    rotation;
    std::vector<double>           mass;               // [kg]
    std::vector<PrincipalInertia> inertia;            // principal moments [kg m^2]
    std::vector<Vec3>             force, torque;      // gathered from the members [N], [N m]

    std::size_t size() const { return mass.size(); }

    /// A body of template t (density [kg/m^3]) at x, turned by q, moving
    /// with v and spinning with w (in space).
    void add(const ClumpTemplate &t, unsigned int index, double density, const Vec3 &x,
             const Eigen::Quaterniond &q, const Vec3 &v, const Vec3 &w);

    /// Angular velocity of body b in space [rad/s].
    Vec3 angular_velocity_of(std::size_t b) const;
  };

  /// Every body's members in space, body by body in member order.
  struct ClumpMembers
  {
    std::vector<Vec3>         position, velocity, lever; // lever: R r_m [m]
    std::vector<double>       radius;
    std::vector<unsigned int> body;

    std::size_t size() const { return body.size(); }
  };

  ClumpMembers expand_members(const ClumpBodies &bodies, const std::vector<ClumpTemplate> &templates);

  /// Overwrites the bodies' force and torque with the members' loads (forces
  /// at the members' centres and torques about them).
  void gather_loads(ClumpBodies &bodies, const ClumpMembers &members,
                    const std::vector<Vec3> &member_force, const std::vector<Vec3> &member_torque);

  /// v += h (F / m + g), L += h R^T T.
  void half_kick_bodies(ClumpBodies &bodies, double h, const Vec3 &gravity);
  /// x += dt v, and the free rotation over dt.
  void drift_bodies(ClumpBodies &bodies, double dt);
} // namespace sluice
