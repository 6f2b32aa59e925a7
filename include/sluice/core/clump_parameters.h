#pragma once
// The 'clumps' subsection: non-spherical grains as rigid clumps of spheres
// (Bell, Yu & Mucha 2005; doc/clumps.md). 'number of templates' > 0 makes
// every particle of the scene a clump of one of the templates, declared in
// the subsections 'template 0', 'template 1', ...; 0 (the default) keeps the
// spheres, and nothing of the clumps is built or paid for.

#include <sluice/core/vector3.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace sluice
{
  enum class ClumpShape
  {
    sphere,      // one member: the sphere scenes, as a clump
    tetrahedron, // four members on a regular tetrahedron
    rod,         // 'rod members' in a row
    cube,        // eight members on the corners of a cube
    list,        // 'members', inline
    file         // 'members file', CSV
  };

  /// One template: its members at scale 1, and how bodies of it are drawn.
  struct ClumpTemplateParameters
  {
    ClumpShape   shape         = ClumpShape::tetrahedron;
    double       member_radius = 0.001; // [m] built-in shapes
    double       overlap       = 0.;    // [-] of a member's diameter
    unsigned int rod_members   = 2;
    // 'list' and 'file': member centres and radii [m], in any frame.
    std::vector<Vec3>   centres;
    std::vector<double> radii;
    double              scale = 1., scale_max = 0.; // [-]; > scale: uniform in between
    double              fraction = 1.;              // [-] share of the generated bodies
  };

  struct ClumpParameters
  {
    std::vector<ClumpTemplateParameters> templates;
    bool random_orientation = true; // generated bodies (lattice, random)

    bool active() const { return !templates.empty(); }
  };

  /// Declares 'clumps' with n_templates template subsections.
  void declare_clump_parameters(dealii::ParameterHandler &prm, unsigned int n_templates);
  /// Reads them. Throws InputError naming the entry. 'directory' is the scene's,
  /// for a 'members file' given relative to it.
  ClumpParameters read_clump_parameters(dealii::ParameterHandler &prm, const std::string &scene,
                                        const std::string &directory);
} // namespace sluice
