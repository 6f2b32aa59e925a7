// Wall motion and the displacement test of the neighbour list (see the header).

#include <sluice/dem/motion_expressions.h>
#include <sluice/dem/wall_set.h>

#include <algorithm>
#include <cmath>

namespace sluice
{

  WallSet::WallSet(const std::vector<PlaneWall> &walls,
                   const std::vector<MeshWallParameters> &meshes, const PeriodicBox &box,
                   const std::string &file_name)
    : box_lower_(box.lower), box_upper_(box.upper)
  {
    for (const PlaneWall &w : walls)
      {
        Plane plane;
        plane.point    = w.point;
        plane.normal   = w.normal;
        plane.material = w.material;
        planes_.push_back(plane);
        names_.push_back(w.name);
        velocity_.push_back(
          vector_of_time(w.velocity, "walls/plane velocities", w.name, file_name));
        angular_velocity_.push_back(
          vector_of_time(w.angular_velocity, "walls/plane angular velocities", w.name, file_name));
        any_moving_ = any_moving_ || velocity_.back() || angular_velocity_.back();
      }
    unsigned int n_triangles = 0;
    for (const MeshWallParameters &m : meshes)
      {
        if (std::find(names_.begin(), names_.end(), m.name) != names_.end())
          throw InputError("error in '" + file_name + "': the wall name '" + m.name +
                           "' is used twice; every wall needs its own name");
        meshes_.emplace_back(m, file_name);
        names_.push_back(m.name);
        triangle_offset_.push_back(n_triangles);
        n_triangles += meshes_.back().mesh().size();
      }
    // The velocities at the start, for the contacts before the first step.
    for (unsigned int w = 0; w < n_planes(); ++w)
      {
        if (velocity_[w])
          planes_[w].velocity = velocity_[w](0.);
        if (angular_velocity_[w])
          planes_[w].angular_velocity = angular_velocity_[w](0.);
      }
    mark_list_build();
  }

  unsigned int WallSet::material(const unsigned int w) const
  {
    return w < n_planes() ? planes_[w].material : meshes_[w - n_planes()].material();
  }

  void WallSet::move(const double t, const double dt)
  {
    for (MeshWall &mesh : meshes_)
      mesh.move(t, dt);
    if (!any_moving_)
      return;
    const double t_mid = t + 0.5 * dt;
    for (unsigned int w = 0; w < n_planes(); ++w)
      {
        Plane &plane = planes_[w];
        if (velocity_[w])
          {
            plane.velocity = velocity_[w](t_mid);
            plane.point += dt * plane.velocity;
          }
        if (angular_velocity_[w])
          {
            plane.angular_velocity = angular_velocity_[w](t_mid);
            // The normal turns with the wall; a fixed step keeps it unit to round-off.
            plane.normal = rotated(plane.normal, dt * plane.angular_velocity);
            plane.normal = (1. / norm(plane.normal)) * plane.normal;
          }
      }
  }

  double WallSet::max_displacement_since_build() const
  {
    double largest = 0.;
    for (const MeshWall &mesh : meshes_)
      largest = std::max(largest, mesh.max_displacement_since_build());
    if (!any_moving_)
      return largest;
    // The signed distance to a plane is affine in x, so the change between two
    // positions of a plane is largest at a corner of the box.
    for (unsigned int w = 0; w < n_planes(); ++w)
      for (unsigned int c = 0; c < 8; ++c)
        {
          const Vec3 x(c & 1 ? box_upper_.x : box_lower_.x, c & 2 ? box_upper_.y : box_lower_.y,
                       c & 4 ? box_upper_.z : box_lower_.z);
          const double now    = dot(x - planes_[w].point, planes_[w].normal);
          const double before = dot(x - at_build_[w].point, at_build_[w].normal);
          largest             = std::max(largest, std::abs(now - before));
        }
    return largest;
  }

  void WallSet::mark_list_build()
  {
    at_build_ = planes_;
    for (MeshWall &mesh : meshes_)
      mesh.mark_list_build();
  }

  std::vector<double> WallSet::state() const
  {
    std::vector<double> numbers;
    for (const auto *set : {&planes_, &at_build_})
      for (const Plane &plane : *set)
        for (const Vec3 *v : {&plane.point, &plane.normal, &plane.velocity, &plane.angular_velocity})
          numbers.insert(numbers.end(), {v->x, v->y, v->z});
    for (const MeshWall &mesh : meshes_)
      {
        const std::vector<double> pose = mesh.state();
        numbers.insert(numbers.end(), pose.begin(), pose.end());
      }
    return numbers;
  }

  void WallSet::set_state(const std::vector<double> &numbers)
  {
    std::size_t k = 0;
    for (auto *set : {&planes_, &at_build_})
      for (Plane &plane : *set)
        for (Vec3 *v : {&plane.point, &plane.normal, &plane.velocity, &plane.angular_velocity})
          {
            *v = Vec3(numbers.at(k), numbers.at(k + 1), numbers.at(k + 2));
            k += 3;
          }
    for (MeshWall &mesh : meshes_)
      {
        if (k + MeshWall::state_size > numbers.size())
          throw std::out_of_range("wall state too short");
        mesh.set_state(std::vector<double>(numbers.begin() + k,
                                           numbers.begin() + k + MeshWall::state_size));
        k += MeshWall::state_size;
      }
  }
} // namespace sluice
