// Builds the coarse fluid mesh, attaches periodicity, checks boundary ids.

#include <sluice/core/scene_parameters.h>
#include <sluice/fluid/fluid_mesh.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <fstream>
#include <set>
#include <sstream>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    std::string directory_of(const std::string &file)
    {
      const auto slash = file.rfind('/');
      return slash == std::string::npos ? "" : file.substr(0, slash + 1);
    }
  } // namespace

  void make_fluid_mesh(parallel::distributed::Triangulation<3> &tria, const FluidParameters &p,
                       const std::string &prm_file, const bool coarse_only)
  {
    const std::string entry = "error in '" + prm_file + "': entry ";
    switch (p.mesh_type)
      {
        case FluidMeshType::box:
          {
            const std::vector<unsigned int> n(p.subdivisions.begin(), p.subdivisions.end());
            GridGenerator::subdivided_hyper_rectangle(
              tria, n, Point<3>(p.lower_corner[0], p.lower_corner[1], p.lower_corner[2]),
              Point<3>(p.upper_corner[0], p.upper_corner[1], p.upper_corner[2]), true);
            break;
          }
        case FluidMeshType::cylinder:
          GridGenerator::cylinder(tria, p.cylinder_radius, p.cylinder_half_length);
          break;
        case FluidMeshType::channel_with_cylinder:
          GridGenerator::channel_with_cylinder(tria, 0.03, 2, 2.0, true);
          break;
        case FluidMeshType::gmsh:
          {
            const std::string path = !p.mesh_file.empty() && p.mesh_file[0] == '/' ?
                                       p.mesh_file :
                                       directory_of(prm_file) + p.mesh_file;
            std::ifstream in(path);
            if (!in)
              throw InputError(entry + "'fluid mesh/file' names '" + path +
                               "', which cannot be opened");
            GridIn<3> grid_in;
            grid_in.attach_triangulation(tria);
            try
              {
                grid_in.read_msh(in);
              }
            catch (const ExceptionBase &e)
              {
                std::ostringstream info;
                e.print_info(info);
                throw InputError(entry + "'fluid mesh/file': '" + path +
                                 "' is not a readable gmsh file:\n" + info.str());
              }
            break;
          }
      }

    // Every boundary id of the mesh needs a condition, and every condition's ids
    // must exist: a misnumbered inlet would otherwise silently become a wall.
    const std::vector<types::boundary_id> ids = tria.get_boundary_ids();
    const std::set<types::boundary_id>    present(ids.begin(), ids.end());
    std::set<types::boundary_id>          covered;
    for (const auto &bc : p.boundaries)
      for (const auto id : bc.ids)
        {
          if (present.count(id) == 0)
            {
              std::string list;
              for (const auto i : present)
                list += (list.empty() ? "" : " ") + std::to_string(i);
              throw InputError(entry + "'fluid boundaries/conditions' gives the id " +
                               std::to_string(id) + " to '" + bc.name +
                               "', but the mesh has only the boundary ids " + list);
            }
          covered.insert(id);
        }
    for (const auto id : present)
      if (covered.count(id) == 0)
        throw InputError(entry + "'fluid boundaries/conditions' has no condition for the mesh's "
                         "boundary id " + std::to_string(id));

    for (const auto &bc : p.boundaries)
      if (bc.type == BoundaryType::periodic)
        {
          std::vector<GridTools::PeriodicFacePair<
            parallel::distributed::Triangulation<3>::cell_iterator>>
            pairs;
          GridTools::collect_periodic_faces(tria, bc.ids[0], bc.ids[1], bc.direction, pairs);
          if (pairs.empty())
            throw InputError(entry + "'fluid boundaries/conditions': the periodic pair '" +
                             bc.name + "' matches no faces along its direction");
          tria.add_periodicity(pairs);
        }
    if (!coarse_only)
      tria.refine_global(p.initial_refinement);
  }
} // namespace sluice
