// The 'clumps' subsection (see the header).

#include <sluice/core/clump_parameters.h>
#include <sluice/core/parameter_declaration.h>
#include <sluice/core/scene_parameters.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    ClumpShape shape_of(const std::string &s)
    {
      return s == "sphere" ? ClumpShape::sphere :
             s == "rod"    ? ClumpShape::rod :
             s == "cube"   ? ClumpShape::cube :
             s == "list"   ? ClumpShape::list :
             s == "file"   ? ClumpShape::file :
                             ClumpShape::tetrahedron;
    }

    /// 'x, y, z, r' into the template's members; false if it does not parse.
    bool add_member(const std::string &row, ClumpTemplateParameters &t)
    {
      const auto fields = Utilities::split_string_list(row, ',');
      if (fields.size() != 4)
        return false;
      double v[4];
      for (unsigned int k = 0; k < 4; ++k)
        {
          std::istringstream in(fields[k]);
          std::string        rest;
          if (!(in >> v[k]) || (in >> rest) || !std::isfinite(v[k]))
            return false;
        }
      if (!(v[3] > 0.))
        return false;
      t.centres.emplace_back(v[0], v[1], v[2]);
      t.radii.push_back(v[3]);
      return true;
    }
  } // namespace

  void declare_clump_parameters(ParameterHandler &prm, const unsigned int n_templates)
  {
    prm.enter_subsection("clumps");
    declare(prm, "number of templates", "0", Patterns::Integer(0, 16),
            "[-] Clump templates ('template 0', ...). Above 0 every particle is a rigid "
            "clump of spheres of one of them (doc/clumps.md); 0 keeps spheres.");
    declare(prm, "random orientation", "true", Patterns::Bool(),
            "Bodies inserted by 'lattice' or 'random' get uniformly random orientations "
            "(false: the template's principal frame along x, y, z).");
    for (unsigned int k = 0; k < n_templates; ++k)
      {
        prm.enter_subsection("template " + std::to_string(k));
        declare(prm, "shape", "tetrahedron",
                Patterns::Selection("sphere|tetrahedron|rod|cube|list|file"),
                "The members: one sphere, a regular tetrahedron of four, a rod of 'rod "
                "members', a cube of eight (neighbours 2 'member radius' (1 - 'overlap') "
                "apart), the inline 'members' or the CSV 'members file'.");
        declare(prm, "member radius", "0.001", Patterns::Double(0.),
                "[m] Radius of the members of a built-in shape, at scale 1.", "(0, inf)");
        declare(prm, "overlap", "0", Patterns::Double(0., 0.9),
                "[-] Built-in shapes: how far neighbouring members overlap, as a fraction of "
                "their diameter (0: touching).");
        declare(prm, "rod members", "2", Patterns::Integer(1, 64), "[-] Members of a rod.");
        declare(prm, "members", "", Patterns::Anything(),
                "[m] shape = list: 'x, y, z, r; ...', member centres and radii in any frame "
                "(the body frame is the union's principal frame about its centroid).",
                "';'-separated groups of four numbers, r > 0");
        declare(prm, "members file", "", Patterns::Anything(),
                "shape = file: CSV (relative to the .prm), one member per line 'x, y, z, r' "
                "[m]; '#' starts a comment.",
                "a readable file name");
        declare(prm, "scale", "1", Patterns::Double(0.),
                "[-] Linear scale of the bodies (members' positions and radii).", "(0, inf)");
        declare(prm, "scale max", "0", Patterns::Double(0.),
                "[-] If above 'scale': scales uniform in [scale, scale max].");
        declare(prm, "fraction", "1", Patterns::Double(0.),
                "[-] Share of the generated bodies (lattice, random) of this template, "
                "relative to the other templates' fractions.");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }

  ClumpParameters read_clump_parameters(ParameterHandler &prm, const std::string &scene,
                                        const std::string &directory)
  {
    ClumpParameters c;
    prm.enter_subsection("clumps");
    const unsigned int n = prm.get_integer("number of templates");
    c.random_orientation = prm.get_bool("random orientation");
    double total_fraction = 0.;
    for (unsigned int k = 0; k < n; ++k)
      {
        const std::string section = "template " + std::to_string(k);
        const auto        fail    = [&](const std::string &entry, const std::string &what) {
          throw InputError("error in '" + scene + "': entry 'clumps/" + section + "/" + entry +
                           "' " + what);
        };
        prm.enter_subsection(section);
        ClumpTemplateParameters t;
        t.shape         = shape_of(prm.get("shape"));
        t.member_radius = prm.get_double("member radius");
        t.overlap       = prm.get_double("overlap");
        t.rod_members   = prm.get_integer("rod members");
        t.scale         = prm.get_double("scale");
        t.scale_max     = prm.get_double("scale max");
        t.fraction      = prm.get_double("fraction");
        const std::string members = prm.get("members"), file = prm.get("members file");
        prm.leave_subsection();
        if (!(t.member_radius > 0.))
          fail("member radius", "= 0 is outside the allowed range (0, inf)");
        if (!(t.scale > 0.))
          fail("scale", "= 0 is outside the allowed range (0, inf)");
        if (t.shape == ClumpShape::list)
          {
            for (const auto &row : Utilities::split_string_list(members, ';'))
              if (!row.empty() && !add_member(row, t))
                fail("members", "has the group '" + row + "'; expected 'x, y, z, r' with r > 0");
            if (t.radii.empty())
              fail("members", "is empty; 'shape = list' needs at least one member");
          }
        if (t.shape == ClumpShape::file)
          {
            const std::string path = !file.empty() && file[0] == '/' ? file : directory + file;
            std::ifstream     in(path);
            if (file.empty() || !in)
              fail("members file", "names '" + path + "', which cannot be opened");
            std::string  line;
            unsigned int line_no = 0;
            while (std::getline(in, line))
              {
                ++line_no;
                line = Utilities::trim(line.substr(0, line.find('#')));
                if (!line.empty() && !add_member(line, t))
                  fail("members file", "names '" + path + "', whose line " +
                                         std::to_string(line_no) + " '" + line +
                                         "' is not 'x, y, z, r' with r > 0");
              }
            if (t.radii.empty())
              fail("members file", "names '" + path + "', which holds no members");
          }
        total_fraction += t.fraction;
        c.templates.push_back(t);
      }
    prm.leave_subsection();
    if (n > 0 && !(total_fraction > 0.))
      throw InputError("error in '" + scene + "': entries 'clumps/template k/fraction' are all "
                       "0; at least one template must be drawn");
    return c;
  }
} // namespace sluice
