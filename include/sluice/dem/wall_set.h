#pragma once
// The walls of a DEM scene as runtime state: where each plane is now, how fast
// it moves, and how far it has moved since the neighbour list was built.
//
// A wall moves rigidly with the velocity field v(t) + w(t) x (x - x0(t)), x0
// being the wall's reference point (the point given in the scene), which
// translates with v. The contact kernel reads the hot data (point, normal,
// velocities, material) from one contiguous array; the velocity functions are
// evaluated once per step, never per contact.
//
// Triangle meshes are the second kind of wall (mesh_wall.h). The walls are
// numbered planes first (box faces, then the extra planes), then the meshes:
// wall n_planes() + m is mesh m, in the .csv, the wall forces and the
// contact observers.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/vector3.h>
#include <sluice/dem/mesh_wall.h>
#include <sluice/dem/periodic_box.h>

#include <functional>
#include <string>
#include <vector>

namespace sluice
{
  /// What the contact kernel needs of one plane, at the current time.
  struct Plane
  {
    Vec3         point;  // the reference point x0(t)
    Vec3         normal; // unit, pointing into the particles
    Vec3         velocity, angular_velocity; // at the middle of the last step
    unsigned int material = 0;

    /// The wall's velocity at x.
    Vec3 velocity_at(const Vec3 &x) const { return velocity + cross(angular_velocity, x - point); }
  };

  class WallSet
  {
  public:
    WallSet() = default;
    /// The walls as the scene describes them, at t = 0. Throws InputError for a
    /// velocity expression that does not parse.
    /// With the mesh walls (their files read and checked; a name used twice
    /// is an error).
    WallSet(const std::vector<PlaneWall> &walls, const std::vector<MeshWallParameters> &meshes,
            const PeriodicBox &box, const std::string &file_name);

    unsigned int              n_planes() const { return planes_.size(); }
    unsigned int              n_meshes() const { return meshes_.size(); }
    unsigned int              n_walls() const { return n_planes() + n_meshes(); }
    const std::vector<Plane> &planes() const { return planes_; }
    /// Plane w (w < n_planes()).
    const Plane              &operator[](const unsigned int w) const { return planes_[w]; }
    const std::vector<MeshWall> &meshes() const { return meshes_; }
    /// Name and material of wall w, plane or mesh.
    const std::string        &name(const unsigned int w) const { return names_[w]; }
    unsigned int              material(unsigned int w) const;
    /// Whether any plane has a motion (else the kernel skips the wall velocity).
    bool                      any_moving() const { return any_moving_; }
    /// The triangles of all meshes numbered in one sequence: mesh m's triangle
    /// t is triangle_offset(m) + t.
    unsigned int              triangle_offset(const unsigned int m) const { return triangle_offset_[m]; }

    /// Moves every wall from t to t + dt with its velocities at t + dt/2 (exact
    /// for a steady motion; second order otherwise, like the particles' drift).
    void move(double t, double dt);

    /// The largest distance a wall surface has moved, along its normal, at any
    /// point of the box (a mesh: any point of it) since the last call of
    /// mark_list_build().
    double max_displacement_since_build() const;
    void   mark_list_build();

    /// The state a checkpoint keeps: point and normal of each plane, and where
    /// they were at the last list build, then each mesh's pose (mesh_wall.h).
    /// set_state() takes the same numbers.
    std::vector<double> state() const;
    void                set_state(const std::vector<double> &numbers);

  private:
    std::vector<Plane>       planes_, at_build_;
    std::vector<MeshWall>    meshes_;
    std::vector<unsigned int> triangle_offset_;
    std::vector<std::string> names_; // planes, then meshes
    // Per wall: the translational and the angular velocity as functions of t
    // (empty: at rest).
    std::vector<std::function<Vec3(double)>> velocity_, angular_velocity_;
    bool                     any_moving_ = false;
    Vec3                     box_lower_, box_upper_;
  };
} // namespace sluice
