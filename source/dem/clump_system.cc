// A clump scene's rigid bodies (see the header).

#include <sluice/core/sphere.h>
#include <sluice/dem/clump_system.h>
#include <sluice/dem/eigen_conversion.h>
#include <sluice/dem/particle_exchange.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  namespace
  {
    /// One sphere as a template: exact, with its centre at the origin.
    ClumpTemplate sphere_template(const double radius)
    {
      ClumpTemplate t;
      t.name    = "sphere";
      t.members = {Vec3()};
      t.radii   = {radius};
      t.volume  = sphere_volume(radius);
      t.surface_area = 4. * M_PI * radius * radius;
      t.principal_inertia = Eigen::Vector3d::Constant(0.4 * t.volume * radius * radius);
      return t;
    }
  } // namespace

  std::vector<ClumpTemplate> make_clump_templates(const ClumpParameters &parameters)
  {
    std::vector<ClumpTemplate> templates;
    for (const ClumpTemplateParameters &t : parameters.templates)
      switch (t.shape)
        {
          case ClumpShape::sphere:
            templates.push_back(sphere_template(t.member_radius));
            break;
          case ClumpShape::tetrahedron:
            templates.push_back(tetrahedron_clump(t.member_radius, t.overlap));
            break;
          case ClumpShape::rod:
            templates.push_back(t.rod_members == 1 ? sphere_template(t.member_radius) :
                                                     rod_clump(t.rod_members, t.member_radius,
                                                               t.overlap));
            break;
          case ClumpShape::cube:
            templates.push_back(cube_clump(t.member_radius, t.overlap));
            break;
          default:
            templates.push_back(t.radii.size() == 1 ?
                                  sphere_template(t.radii[0]) :
                                  make_clump_template("members", t.centres, t.radii));
            // A single listed sphere keeps its place: the body frame is centred on it.
        }
    return templates;
  }

  void ClumpSystem::declare_fields(ParticleFieldRegistry &fields)
  {
    const ParticleFieldRegistry::Use kept{true, false, true};
    fields.declare(clump_fields::momentum, 3, kept);
    fields.declare(clump_fields::orientation, 4, kept);
    fields.declare(clump_fields::shape, 1, kept);
    fields.declare(clump_fields::scale, 1, kept);
  }

  ClumpSystem::ClumpSystem(const ClumpParameters &parameters, const ParticleFieldRegistry &fields)
    : templates(make_clump_templates(parameters))
    , momentum_at(fields.find(clump_fields::momentum)->offset)
    , orientation_at(fields.find(clump_fields::orientation)->offset)
    , template_at(fields.find(clump_fields::shape)->offset)
    , scale_at(fields.find(clump_fields::scale)->offset)
  {
    for (const ClumpTemplate &t : templates)
      member_stride = std::max<unsigned int>(member_stride, t.members.size());
  }

  RigidRotation ClumpSystem::rotation_of(const unsigned int b) const
  {
    const double *e = bodies.extra_of(b);
    RigidRotation r;
    r.orientation = Eigen::Quaterniond(e[orientation_at], e[orientation_at + 1],
                                       e[orientation_at + 2], e[orientation_at + 3]);
    r.body_momentum = Eigen::Vector3d(e[momentum_at], e[momentum_at + 1], e[momentum_at + 2]);
    return r;
  }

  void ClumpSystem::set_mass_properties(const std::vector<double> &densities,
                                        const bool from_momentum)
  {
    ParticleStorage &B = bodies;
    inertia.resize(B.size());
    for (unsigned int b = 0; b < B.size(); ++b)
      {
        const ClumpTemplate &t   = template_of(b);
        const double         s   = scale_of(b);
        const double         rho = densities[B.type[b]];
        if (t.members.size() == 1)
          {
            // As a sphere's (particle_storage.cc), to the last bit.
            const double r = s * t.radii[0], m = sphere_mass(rho, r);
            B.mass[b]            = m;
            inertia[b]           = Eigen::Vector3d::Constant(0.4 * m * r * r);
          }
        else
          {
            B.mass[b]  = rho * s * s * s * t.volume;
            inertia[b] = (rho * std::pow(s, 5)) * t.principal_inertia;
          }
        B.inverse_mass[b]    = 1. / B.mass[b];
        B.inverse_inertia[b] = 3. / inertia[b].sum(); // the mean moment's, for reports
        // A ghost's angular velocity is its owner's, sent with it.
        if (from_momentum && b < B.n_local)
          B.angular_velocity[b] = to_vec3(angular_velocity(rotation_of(b), inertia[b]));
      }
  }

  void ClumpSystem::set_momenta_from_angular_velocity(const std::uint64_t first_id,
                                                      const std::uint64_t end_id)
  {
    ParticleStorage &B = bodies;
    for (unsigned int b = 0; b < B.size(); ++b)
      if (B.id[b] >= first_id && B.id[b] < end_id)
        {
          const RigidRotation   r = rotation_of(b);
          const Eigen::Vector3d L =
            inertia[b].cwiseProduct(r.orientation.conjugate() * to_eigen(B.angular_velocity[b]));
          for (unsigned int d = 0; d < 3; ++d)
            B.extra_of(b)[momentum_at + d] = L[d];
        }
  }

  void ClumpSystem::expand(ParticleStorage &M)
  {
    const ParticleStorage &B = bodies;
    M.clear();
    M.n_extra = 0;
    body_index.clear();
    body_frame_offset.clear();
    for (unsigned int b = 0; b < B.size(); ++b)
      {
        const ClumpTemplate &t = template_of(b);
        const double         s = scale_of(b);
        if (b == B.n_local)
          M.n_local = M.size();
        for (unsigned int k = 0; k < t.members.size(); ++k)
          {
            M.id.push_back(member_id(B.id[b], k));
            M.radius.push_back(s * t.radii[k]);
            M.type.push_back(B.type[b]);
            M.mass.push_back(B.mass[b]);
            M.inverse_mass.push_back(B.inverse_mass[b]);
            M.inverse_inertia.push_back(B.inverse_inertia[b]);
            M.coordination.push_back(0);
            body_index.push_back(b);
            body_frame_offset.push_back(s * t.members[k]);
          }
      }
    if (B.n_local == B.size())
      M.n_local = M.size();
    const std::size_t n = M.id.size();
    M.position.resize(n);
    M.velocity.resize(n);
    M.angular_velocity.resize(n);
    M.force.assign(n, Vec3());
    M.torque.assign(n, Vec3());
    lever.resize(n);
    move_members(M);
  }

  void ClumpSystem::move_members(ParticleStorage &M, const unsigned int first) const
  {
    const ParticleStorage &B = bodies;
    double fastest_2 = 0.;
    // Members are stored body by body; find the first of body 'first'.
    std::size_t i = std::lower_bound(body_index.begin(), body_index.end(), first) - body_index.begin();
    for (; i < body_index.size();)
      {
        const unsigned int    b = body_index[i];
        const Eigen::Matrix3d R = rotation_of(b).orientation.toRotationMatrix();
        const Vec3            w = B.angular_velocity[b];
        for (; i < body_index.size() && body_index[i] == b; ++i)
          {
            const Vec3 r    = to_vec3(R * to_eigen(body_frame_offset[i]));
            lever[i]        = r;
            M.position[i]   = B.position[b] + r;
            M.velocity[i]   = B.velocity[b] + cross(w, r);
            M.angular_velocity[i] = w;
            if (i < M.n_local)
              fastest_2 = std::max(fastest_2, norm_square(M.velocity[i]));
          }
      }
    if (first == 0)
      M.max_drift_speed_2 = fastest_2;
  }

  void ClumpSystem::update_member_velocities(ParticleStorage &M) const
  {
    const ParticleStorage &B = bodies;
    for (unsigned int i = 0; i < M.n_local; ++i)
      {
        const unsigned int b  = body_index[i];
        M.velocity[i]         = B.velocity[b] + cross(B.angular_velocity[b], lever[i]);
        M.angular_velocity[i] = B.angular_velocity[b];
      }
  }

  void ClumpSystem::gather(const ParticleStorage &M)
  {
    ParticleStorage &B = bodies;
    std::fill(B.force.begin(), B.force.begin() + B.n_local, Vec3());
    std::fill(B.torque.begin(), B.torque.begin() + B.n_local, Vec3());
    for (unsigned int i = 0; i < M.n_local; ++i)
      {
        const unsigned int b = body_index[i];
        B.force[b] += M.force[i];
        B.torque[b] += cross(lever[i], M.force[i]) + M.torque[i];
      }
  }

  void ClumpSystem::kick_rotation(const double h)
  {
    // sluice::kick_rotation and angular_velocity (rigid_rotation.h) written
    // out on the arrays, the same numbers: L += h R^T T, w = R (L / I).
    ParticleStorage &B = bodies;
    for (unsigned int b = 0; b < B.n_local; ++b)
      {
        double      *e = B.extra_of(b);
        const double q = e[orientation_at];
        const double x[3] = {e[orientation_at + 1], e[orientation_at + 2], e[orientation_at + 3]};
        const double minus_x[3] = {-x[0], -x[1], -x[2]};
        const double T[3] = {B.torque[b].x, B.torque[b].y, B.torque[b].z};
        double       body_torque[3], u[3], w[3];
        rotate_vector(q, minus_x, T, body_torque);
        for (unsigned int d = 0; d < 3; ++d)
          {
            e[momentum_at + d] += h * body_torque[d];
            u[d] = e[momentum_at + d] / inertia[b][d];
          }
        rotate_vector(q, x, u, w);
        B.angular_velocity[b] = Vec3(w[0], w[1], w[2]);
      }
  }

  void ClumpSystem::drift(const double dt)
  {
    ParticleStorage &B = bodies;
    // Four bodies' rotations side by side (rigid_rotation.h): the same
    // numbers as one at a time, in about half the time (doc/clumps.md).
    constexpr unsigned int N = 4;
    for (unsigned int first = 0; first < B.n_local; first += N)
      {
        const unsigned int n = std::min(N, B.n_local - first);
        RotationLanes<N>   lanes;
        for (unsigned int l = 0; l < N; ++l)
          {
            // Lanes past the last body turn nothing (L = 0).
            const double *e = B.extra_of(first + std::min(l, n - 1));
            lanes.w[l]      = e[orientation_at];
            for (unsigned int d = 0; d < 3; ++d)
              {
                lanes.v[d][l] = e[orientation_at + 1 + d];
                lanes.L[d][l] = l < n ? e[momentum_at + d] : 0.;
                lanes.I[d][l] = inertia[first + std::min(l, n - 1)][d];
              }
          }
        rotate_lanes_freely(lanes, dt);
        for (unsigned int l = 0; l < n; ++l)
          {
            const unsigned int b = first + l;
            B.position[b] += dt * B.velocity[b];
            RigidRotation r;
            // Round-off only: each factor is a unit quaternion.
            r.orientation = Eigen::Quaterniond(lanes.w[l], lanes.v[0][l], lanes.v[1][l],
                                               lanes.v[2][l])
                              .normalized();
            r.body_momentum = Eigen::Vector3d(lanes.L[0][l], lanes.L[1][l], lanes.L[2][l]);
            double *e       = B.extra_of(b);
            for (unsigned int d = 0; d < 3; ++d)
              e[momentum_at + d] = r.body_momentum[d];
            e[orientation_at]     = r.orientation.w();
            e[orientation_at + 1] = r.orientation.x();
            e[orientation_at + 2] = r.orientation.y();
            e[orientation_at + 3] = r.orientation.z();
            B.angular_velocity[b] = to_vec3(angular_velocity(r, inertia[b]));
          }
      }
  }

  double ClumpSystem::rotational_energy() const
  {
    double e = 0.;
    for (unsigned int b = 0; b < bodies.n_local; ++b)
      e += sluice::rotational_energy(rotation_of(b), inertia[b]);
    return e;
  }
} // namespace sluice
