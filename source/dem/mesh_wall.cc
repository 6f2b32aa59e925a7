// A moving triangle-mesh wall (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/mesh_wall.h>
#include <sluice/dem/motion_expressions.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  namespace
  {
    Vec3 times(const std::array<Vec3, 3> &rows, const Vec3 &v)
    {
      return {dot(rows[0], v), dot(rows[1], v), dot(rows[2], v)};
    }

    /// The rows of R' = Q R for the rotation Q by the vector a, made orthonormal
    /// again (Gram-Schmidt) so that round-off does not accumulate over turns.
    std::array<Vec3, 3> turned(const std::array<Vec3, 3> &rows, const Vec3 &a)
    {
      // R' applied to v is Q (R v): column c of R' is Q applied to column c of R.
      std::array<Vec3, 3> columns;
      for (unsigned int c = 0; c < 3; ++c)
        columns[c] = rotated(Vec3(rows[0][c], rows[1][c], rows[2][c]), a);
      Vec3 e0 = columns[0], e1 = columns[1];
      e0      = (1. / norm(e0)) * e0;
      e1 -= dot(e1, e0) * e0;
      e1            = (1. / norm(e1)) * e1;
      const Vec3 e2 = cross(e0, e1);
      return {{Vec3(e0.x, e1.x, e2.x), Vec3(e0.y, e1.y, e2.y), Vec3(e0.z, e1.z, e2.z)}};
    }
  } // namespace

  MeshWall::MeshWall(const MeshWallParameters &p, const std::string &scene)
    : name_(p.name), material_(p.material)
  {
    const std::string context = "error in '" + scene + "': entry '" + p.subsection + "/file'";
    MeshPlacement     placement;
    placement.scale  = p.scale;
    placement.axis   = p.rotation_axis;
    placement.angle  = p.rotation_angle;
    placement.offset = p.offset;
    mesh_            = read_triangle_mesh(p.file, placement, p.closed, context);
    initial_vertices_ = mesh_.vertices;
    initial_normals_  = mesh_.normals;
    initial_origin_   = p.motion_origin;
    pose_.origin      = p.motion_origin;
    velocity_fn_ = vector_of_time(p.velocity, p.subsection + "/velocity", p.name, scene);
    angular_velocity_fn_ =
      vector_of_time(p.angular_velocity, p.subsection + "/angular velocity", p.name, scene);
    // The velocities at the start, for the contacts before the first step.
    if (velocity_fn_)
      pose_.velocity = velocity_fn_(0.);
    if (angular_velocity_fn_)
      pose_.angular_velocity = angular_velocity_fn_(0.);
    mark_list_build();
  }

  void MeshWall::move(const double t, const double dt)
  {
    if (!moving())
      return;
    const double t_mid = t + 0.5 * dt;
    if (velocity_fn_)
      {
        pose_.velocity = velocity_fn_(t_mid);
        pose_.origin += dt * pose_.velocity;
      }
    if (angular_velocity_fn_)
      {
        pose_.angular_velocity = angular_velocity_fn_(t_mid);
        pose_.rotation         = turned(pose_.rotation, dt * pose_.angular_velocity);
      }
    place_vertices();
  }

  void MeshWall::place_vertices()
  {
    for (std::size_t v = 0; v < mesh_.vertices.size(); ++v)
      mesh_.vertices[v] = pose_.origin + times(pose_.rotation, initial_vertices_[v] - initial_origin_);
    for (std::size_t t = 0; t < mesh_.normals.size(); ++t)
      mesh_.normals[t] = times(pose_.rotation, initial_normals_[t]);
  }

  double MeshWall::max_displacement_since_build() const
  {
    if (!moving())
      return 0.;
    double largest_2 = 0.;
    for (std::size_t v = 0; v < mesh_.vertices.size(); ++v)
      largest_2 = std::max(largest_2, norm_square(mesh_.vertices[v] - vertices_at_build_[v]));
    return std::sqrt(largest_2);
  }

  void MeshWall::mark_list_build()
  {
    at_build_ = pose_;
    if (moving())
      vertices_at_build_ = mesh_.vertices;
  }

  std::vector<double> MeshWall::state() const
  {
    std::vector<double> numbers;
    for (const Pose *pose : {&pose_, &at_build_})
      {
        std::vector<Vec3> vectors{pose->origin, pose->velocity, pose->angular_velocity};
        vectors.insert(vectors.end(), pose->rotation.begin(), pose->rotation.end());
        for (const Vec3 &v : vectors)
          numbers.insert(numbers.end(), {v.x, v.y, v.z});
      }
    return numbers;
  }

  void MeshWall::set_state(const std::vector<double> &numbers)
  {
    std::size_t k  = 0;
    auto        at = [&]() {
      const Vec3 v(numbers.at(k), numbers.at(k + 1), numbers.at(k + 2));
      k += 3;
      return v;
    };
    for (Pose *pose : {&pose_, &at_build_})
      {
        pose->origin           = at();
        pose->velocity         = at();
        pose->angular_velocity = at();
        for (Vec3 &row : pose->rotation)
          row = at();
      }
    // The vertices at the last build, then now.
    std::swap(pose_, at_build_);
    place_vertices();
    vertices_at_build_ = mesh_.vertices;
    std::swap(pose_, at_build_);
    place_vertices();
  }
} // namespace sluice
