// Rigid bodies of clumps (see the header).

#include <sluice/dem/clump_bodies.h>

namespace sluice
{
  namespace
  {
    Eigen::Vector3d to_eigen(const Vec3 &v) { return Eigen::Vector3d(v.x, v.y, v.z); }
    Vec3            to_vec3(const Eigen::Vector3d &v) { return Vec3(v.x(), v.y(), v.z()); }
  } // namespace

  void ClumpBodies::add(const ClumpTemplate &t, const unsigned int index, const double density,
                        const Vec3 &x, const Eigen::Quaterniond &q, const Vec3 &v, const Vec3 &w)
  {
    template_index.push_back(index);
    position.push_back(x);
    velocity.push_back(v);
    mass.push_back(density * t.volume);
    inertia.push_back(density * t.principal_inertia);
    RigidRotation r;
    r.orientation = q.normalized();
    // L in the body frame: I (R^T w).
    r.body_momentum = inertia.back().cwiseProduct(r.orientation.conjugate() * to_eigen(w));
    rotation.push_back(r);
    force.emplace_back();
    torque.emplace_back();
  }

  Vec3 ClumpBodies::angular_velocity_of(const std::size_t b) const
  {
    return to_vec3(angular_velocity(rotation[b], inertia[b]));
  }

  ClumpMembers expand_members(const ClumpBodies &bodies, const std::vector<ClumpTemplate> &templates)
  {
    ClumpMembers m;
    for (std::size_t b = 0; b < bodies.size(); ++b)
      {
        const ClumpTemplate  &t = templates[bodies.template_index[b]];
        const Eigen::Matrix3d R = bodies.rotation[b].orientation.toRotationMatrix();
        const Vec3            w = bodies.angular_velocity_of(b);
        for (std::size_t k = 0; k < t.members.size(); ++k)
          {
            const Vec3 lever = to_vec3(R * to_eigen(t.members[k]));
            m.position.push_back(bodies.position[b] + lever);
            m.velocity.push_back(bodies.velocity[b] + cross(w, lever));
            m.lever.push_back(lever);
            m.radius.push_back(t.radii[k]);
            m.body.push_back(b);
          }
      }
    return m;
  }

  void gather_loads(ClumpBodies &bodies, const ClumpMembers &members,
                    const std::vector<Vec3> &member_force, const std::vector<Vec3> &member_torque)
  {
    std::fill(bodies.force.begin(), bodies.force.end(), Vec3());
    std::fill(bodies.torque.begin(), bodies.torque.end(), Vec3());
    for (std::size_t k = 0; k < members.size(); ++k)
      {
        const unsigned int b = members.body[k];
        bodies.force[b] += member_force[k];
        bodies.torque[b] += cross(members.lever[k], member_force[k]) + member_torque[k];
      }
  }

  void half_kick_bodies(ClumpBodies &bodies, const double h, const Vec3 &gravity)
  {
    for (std::size_t b = 0; b < bodies.size(); ++b)
      {
        bodies.velocity[b] += h * ((1. / bodies.mass[b]) * bodies.force[b] + gravity);
        kick_rotation(bodies.rotation[b], to_eigen(bodies.torque[b]), h);
      }
  }

  void drift_bodies(ClumpBodies &bodies, const double dt)
  {
    for (std::size_t b = 0; b < bodies.size(); ++b)
      {
        bodies.position[b] += dt * bodies.velocity[b];
        rotate_freely(bodies.rotation[b], bodies.inertia[b], dt);
      }
  }
} // namespace sluice
