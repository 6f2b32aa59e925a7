#pragma once
// The walls of a DEM scene as runtime state: where each plane is now, how fast
// it moves, and how far it has moved since the neighbour list was built.
//
// A wall moves rigidly with the velocity field v(t) + w(t) x (x - x0(t)), x0
// being the wall's reference point (the point given in the scene), which
// translates with v. The contact kernel reads the hot data (point, normal,
// velocities, material) from one contiguous array; the velocity functions are
// evaluated once per step, never per contact. A triangle mesh will be a second
// kind of wall element in this set.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/vector3.h>
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
    WallSet(const std::vector<PlaneWall> &walls, const PeriodicBox &box,
            const std::string &file_name);

    unsigned int              size() const { return planes_.size(); }
    bool                      empty() const { return planes_.empty(); }
    const std::vector<Plane> &planes() const { return planes_; }
    const Plane              &operator[](const unsigned int w) const { return planes_[w]; }
    const std::string        &name(const unsigned int w) const { return names_[w]; }
    /// Whether any wall has a motion (else the kernel skips the wall velocity).
    bool                      any_moving() const { return any_moving_; }

    /// Moves every wall from t to t + dt with its velocities at t + dt/2 (exact
    /// for a steady motion; second order otherwise, like the particles' drift).
    void move(double t, double dt);

    /// The largest distance a wall surface has moved, along its normal, at any
    /// point of the box since the last call of mark_list_build().
    double max_displacement_since_build() const;
    void   mark_list_build();

    /// The state a checkpoint keeps: point and normal of each plane, and where
    /// they were at the last list build. set_state() takes the same numbers.
    std::vector<double> state() const;
    void                set_state(const std::vector<double> &numbers);

  private:
    std::vector<Plane>       planes_, at_build_;
    std::vector<std::string> names_;
    // Per wall: the translational and the angular velocity as functions of t
    // (empty: at rest).
    std::vector<std::function<Vec3(double)>> velocity_, angular_velocity_;
    bool                     any_moving_ = false;
    Vec3                     box_lower_, box_upper_;
  };
} // namespace sluice
