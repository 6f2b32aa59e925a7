#pragma once
// One triangle-mesh wall as runtime state: its surface where it is now, and
// its rigid motion (doc/geometry.md).
//
// The mesh moves with the velocity field v(t) + w(t) x (x - o(t)), o the
// motion origin, which translates with v. The vertices are never advanced
// step by step: the wall keeps its accumulated rotation R and origin o and
// places every vertex at o + R (X - o_0) from the file's (placed) position X,
// so a drum turned a thousand times has the shape it started with. The
// velocities are evaluated once per step, at its middle, as for the planes.

#include <sluice/core/mesh_wall_parameters.h>
#include <sluice/core/vector3.h>
#include <sluice/dem/triangle_mesh.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace sluice
{
  class MeshWall
  {
  public:
    /// Reads and places the mesh and parses its motion. 'scene' names the .prm
    /// in messages. Throws InputError.
    MeshWall(const MeshWallParameters &parameters, const std::string &scene);

    const TriangleMesh &mesh() const { return mesh_; }
    const std::string  &name() const { return name_; }
    unsigned int        material() const { return material_; }
    bool                moving() const { return velocity_fn_ || angular_velocity_fn_; }

    /// The motion origin now, and the velocities at the middle of the last step.
    const Vec3 &origin() const { return pose_.origin; }
    const Vec3 &velocity() const { return pose_.velocity; }
    const Vec3 &angular_velocity() const { return pose_.angular_velocity; }
    /// The wall's velocity at x.
    Vec3 velocity_at(const Vec3 &x) const
    {
      return pose_.velocity + cross(pose_.angular_velocity, x - pose_.origin);
    }

    /// Moves the wall from t to t + dt with its velocities at t + dt/2.
    void move(double t, double dt);

    /// The largest distance a point of the surface has moved since the last
    /// mark_list_build() (a rigid motion moves no point further than a vertex).
    double max_displacement_since_build() const;
    void   mark_list_build();

    /// The state a checkpoint keeps (origin, rotation, velocities, now and at
    /// the last build), and back; set_state() places the vertices again.
    std::vector<double> state() const;
    void                set_state(const std::vector<double> &numbers);
    static constexpr unsigned int state_size = 2 * (3 + 9 + 3 + 3);

  private:
    void place_vertices();

    std::string  name_;
    unsigned int material_;
    TriangleMesh mesh_;
    // The placed file: vertices and normals at t = 0, and the origin then.
    std::vector<Vec3> initial_vertices_, initial_normals_;
    Vec3              initial_origin_;
    std::function<Vec3(double)> velocity_fn_, angular_velocity_fn_;

    struct Pose
    {
      Vec3                origin;
      std::array<Vec3, 3> rotation{{Vec3(1., 0., 0.), Vec3(0., 1., 0.), Vec3(0., 0., 1.)}}; // rows
      Vec3                velocity, angular_velocity;
    };
    Pose              pose_, at_build_;
    std::vector<Vec3> vertices_at_build_;
  };
} // namespace sluice
