#pragma once
// Between Sluice's Vec3 (the particle arrays' type) and Eigen's vectors (the
// rigid-body linear algebra of the clumps).

#include <sluice/core/vector3.h>

#include <Eigen/Dense>

namespace sluice
{
  inline Eigen::Vector3d to_eigen(const Vec3 &v) { return Eigen::Vector3d(v.x, v.y, v.z); }
  inline Vec3            to_vec3(const Eigen::Vector3d &v) { return Vec3(v.x(), v.y(), v.z()); }
} // namespace sluice
