#pragma once
// The triangle-mesh walls of a scene as the .prm describes them: one
// subsection 'walls/mesh k' for k = 0 ... 'walls/number of meshes' - 1, each
// with its file, placement, material and motion (doc/geometry.md).
//
// deal.II's ParameterHandler knows only declared subsections, so a scene file
// is read twice: once for the number of meshes (everything else skipped),
// then strictly with that many mesh subsections declared.

#include <sluice/core/vector3.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace sluice
{
  struct MeshWallParameters
  {
    std::string  file;         // as found (relative to the .prm resolved)
    std::string  name;         // in the .csv columns and output file names
    std::string  subsection;   // 'walls/mesh k', for messages
    unsigned int material = 0;
    bool         closed   = false; // an open edge is an error
    // Placement of the file's coordinates: x = R(axis, angle) (scale x_file) + offset.
    double scale = 1.;
    Vec3   rotation_axis{0., 0., 1.};
    double rotation_angle = 0.;
    Vec3   offset;
    // Motion: the origin moves with 'velocity', the mesh turns about the moving
    // origin with 'angular velocity' (expressions in t; empty: none).
    Vec3        motion_origin;
    std::string velocity, angular_velocity;
  };

  /// 'walls/number of meshes' and the subsections 'walls/mesh 0' ... 'mesh n-1'
  /// (call inside subsection 'walls'; --print-parameters shows one as the example).
  void declare_mesh_walls(dealii::ParameterHandler &prm, unsigned int n_meshes);

  /// Reads them (inside subsection 'walls'); 'scene' is the .prm's name, for
  /// messages and relative file names; 'default_material' the walls' material.
  /// Throws InputError naming the entry.
  std::vector<MeshWallParameters> read_mesh_walls(dealii::ParameterHandler &prm,
                                                  const std::string &scene,
                                                  unsigned int default_material,
                                                  unsigned int n_materials);
} // namespace sluice
