#pragma once
// The .csv columns of a mesh wall's load: its torque about its motion origin
// and the power it puts in, named and written the same way by every scene
// that has meshes (dem/scene_series.cc; the coupled scene adds the fluid's
// share under the part name "fluid").

#include <sluice/core/vector3.h>

#include <ostream>
#include <string>

namespace sluice
{
  /// ",<mesh>_torque_x,<mesh>_torque_y,<mesh>_torque_z,<mesh>_power", with
  /// "_<part>" after the mesh's name when 'part' is not empty.
  inline std::string mesh_load_header(const std::string &mesh, const std::string &part = "")
  {
    const std::string n = part.empty() ? mesh : mesh + "_" + part;
    return "," + n + "_torque_x," + n + "_torque_y," + n + "_torque_z," + n + "_power";
  }

  /// The values of mesh_load_header()'s columns.
  inline void write_mesh_load(std::ostream &row, const Vec3 &torque, const double power)
  {
    row << "," << torque.x << "," << torque.y << "," << torque.z << "," << power;
  }
} // namespace sluice
