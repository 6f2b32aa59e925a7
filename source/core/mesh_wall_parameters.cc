// The 'walls/mesh k' subsections (see the header).

#include <sluice/core/mesh_wall_parameters.h>
#include <sluice/core/parameter_declaration.h>
#include <sluice/core/scene_parameters.h>

#include <filesystem>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    std::string subsection_name(const unsigned int k) { return "mesh " + std::to_string(k); }

  } // namespace

  void declare_mesh_walls(ParameterHandler &prm, const unsigned int n_meshes)
  {
    declare(prm, "number of meshes", "0", Patterns::Integer(0),
            "[-] Triangle-mesh walls, each described in a subsection 'mesh 0', 'mesh 1', ... "
            "(shown here as 'mesh 0').");
    const Patterns::List three_numbers(Patterns::Double(), 3, 3, ",");
    for (unsigned int k = 0; k < n_meshes; ++k)
      {
        prm.enter_subsection(subsection_name(k));
        declare(prm, "file", "", Patterns::Anything(),
                "Surface mesh: STL (ASCII or binary) or gmsh .msh (2.2 or 4.1 ASCII, its "
                "triangles), relative to the .prm.",
                "a file name");
        declare(prm, "name", "", Patterns::Anything(),
                "Name of the wall in the .csv columns and output files; empty: 'mesh_k'.",
                "empty, or letters, digits and '_'");
        declare(prm, "material", "-1", Patterns::Integer(-1),
                "Material type of the wall; -1: 'walls/material'.",
                "-1, or a material type 0..(number of materials - 1)");
        declare(prm, "closed", "false", Patterns::Bool(),
                "Whether the surface must be closed: an edge with one triangle stops the "
                "scene, naming the facet.");
        declare(prm, "scale", "1", Patterns::Double(0.),
                "[-] Factor from the file's units to metres (0.001 for a file in mm).",
                "(0, inf)");
        declare(prm, "rotation axis", "0, 0, 1", three_numbers,
                "[-] Axis of the rotation applied to the scaled file coordinates.",
                "three numbers, not all zero");
        declare(prm, "rotation angle", "0", Patterns::Double(),
                "[rad] Angle of that rotation (right-handed about the axis).");
        declare(prm, "offset", "0, 0, 0", three_numbers,
                "[m] Translation applied after the scale and the rotation.");
        declare(prm, "motion origin", "0, 0, 0", three_numbers,
                "[m] The point (in the scene, at t = 0) the mesh turns about; it moves with "
                "'velocity'.");
        declare(prm, "velocity", "", Patterns::Anything(),
                "[m/s] Translational velocity as expressions in t [s], 'vx(t), vy(t), vz(t)' "
                "(muparser syntax, pi known); empty: none.",
                "empty, or three expressions in t");
        declare(prm, "angular velocity", "", Patterns::Anything(),
                "[rad/s] Angular velocity about the motion origin, 'wx(t), wy(t), wz(t)'; "
                "empty: none. The wall's surface moves with v + w x (x - origin).",
                "empty, or three expressions in t");
        prm.leave_subsection();
      }
  }

  std::vector<MeshWallParameters> read_mesh_walls(ParameterHandler &prm, const std::string &scene,
                                                  const unsigned int default_material,
                                                  const unsigned int n_materials)
  {
    const unsigned int              n = prm.get_integer("number of meshes");
    std::vector<MeshWallParameters> meshes(n);
    const std::string               directory = std::filesystem::path(scene).parent_path();
    for (unsigned int k = 0; k < n; ++k)
      {
        MeshWallParameters &m     = meshes[k];
        m.subsection              = "walls/" + subsection_name(k);
        const std::string   entry = m.subsection + "/";
        const auto fail = [&](const std::string &name, const std::string &what) {
          throw InputError("error in '" + scene + "': entry '" + entry + name + "' " + what);
        };
        prm.enter_subsection(subsection_name(k));
        m.file = prm.get("file");
        if (m.file.empty())
          fail("file", "is empty; each mesh wall needs its surface mesh");
        if (m.file[0] != '/' && !directory.empty())
          m.file = directory + "/" + m.file;
        m.name = prm.get("name");
        if (m.name.empty())
          m.name = "mesh_" + std::to_string(k);
        if (m.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                     "0123456789_") != std::string::npos)
          fail("name", "= '" + m.name + "' is not allowed: letters, digits and '_' only");
        const int material = prm.get_integer("material");
        m.material         = material < 0 ? default_material : material;
        // (An invalid 'walls/material' is reported under its own name.)
        if (material >= 0 && m.material >= n_materials)
          fail("material", "= " + std::to_string(material) +
                             " is outside the allowed range: material types 0.." +
                             std::to_string(n_materials - 1));
        m.closed         = prm.get_bool("closed");
        m.scale          = prm.get_double("scale");
        if (!(m.scale > 0.))
          fail("scale", "= 0 is outside the allowed range (0, inf)");
        m.rotation_axis  = get_vector(prm, "rotation axis");
        if (!(norm(m.rotation_axis) > 0.))
          fail("rotation axis", "is the zero vector");
        m.rotation_angle = prm.get_double("rotation angle");
        m.offset         = get_vector(prm, "offset");
        m.motion_origin  = get_vector(prm, "motion origin");
        m.velocity         = prm.get("velocity");
        m.angular_velocity = prm.get("angular velocity");
        prm.leave_subsection();
      }
    return meshes;
  }
} // namespace sluice
