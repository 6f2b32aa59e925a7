// Declares every .prm entry with its default, unit and range, reads a scene file and
// checks it. Nothing is written to disk here, so a bad file leaves no trace.

#include <sluice/core/names.h>
#include <sluice/core/parameter_declaration.h>
#include <sluice/core/scene_parameters.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <tuple>

namespace sluice
{
  using dealii::ParameterHandler;
  using dealii::Patterns::Bool;
  using dealii::Patterns::Double;
  using dealii::Patterns::Integer;
  using dealii::Patterns::List;
  using dealii::Patterns::Selection;
  namespace Patterns = dealii::Patterns;

  namespace
  {
    const double max_double = std::numeric_limits<double>::max();
    // The lower bound of entries that refuse zero (deal.II's ranges are closed).
    const double min_positive = std::numeric_limits<double>::min();

    Patterns::List point_pattern()
    {
      return Patterns::List(Patterns::Double(), 3, 3, ",");
    }

    /// The 'simulation' and 'domain' subsections.
    void declare_simulation_and_domain(ParameterHandler &prm)
    {
      prm.enter_subsection("simulation");
      {
        declare(prm, "physics", "dem", Selection(names<Physics>().selection()),
                "What the scene simulates: 'dem' (particles only; no fluid is built), "
                "'fluid' (the volume-averaged Navier-Stokes equations with a given "
                "porosity; no particles are built), 'cfd-dem' (both, coupled: the "
                "'cfd-dem' subsection) or 'sph' (an SPH fluid alone: the 'sph' subsection, "
                "doc/sph.md).");
        declare(prm, "end time", "1", Double(0, max_double),
                          "[s] Simulated time at which the run stops.");
        declare(prm, "time step", "auto", Patterns::Anything(),
                          "[s] DEM time step, or 'auto' for (time step fraction) times the "
                          "shortest contact time of any material pair present, or the step "
                          "that resolves the strongest dashpot to the 'restitution "
                          "accuracy', whichever is shorter. An explicit step above "
                          "(maximum time step ratio) times that contact time is refused; "
                          "one that under-resolves the damping is run with a warning.",
                "'auto' or a number > 0");
        declare(prm, "time step fraction", "0.02", Double(1e-6, 0.1),
                          "[-] With 'time step = auto': dt = fraction * t_c (Gao & Sun "
                          "recommend t_c/50).");
        declare(prm, "restitution accuracy", "0.005", Double(1e-6, 0.5),
                          "[-] Relative error of the realised restitution that the "
                          "automatic step allows from the dashpot's half-step lag in "
                          "velocity Verlet (doc/dem.md, section 6): dt <= 4 accuracy "
                          "tau_d (1 - zeta^2) / |ln e|, tau_d = m*/c_n. Matters for strong "
                          "damping only (e below about 0.5).");
        declare(prm, "maximum overlap", "0.2", Double(1e-6, 1),
                "[-] The deepest overlap allowed during the run, as a fraction of the "
                "smaller radius (Hertz theory holds for a few percent); beyond it the run "
                "stops with exit code 5, naming the particles. A non-finite state, and a "
                "particle that moves more than half the smallest radius in one step, stop "
                "it the same way.");
        declare(prm, "maximum time step ratio", "0.1", Double(1e-6, 0.3),
                          "[-] The largest dt / t_c accepted; velocity Verlet is unstable "
                          "for a linear spring above dt = t_c * 2/pi and inaccurate well "
                          "before.");
        declare(prm, "gravity", "0, 0, -9.81", point_pattern(),
                          "[m/s^2] Gravitational acceleration.");
        declare(prm, "characteristic velocity", "1", Double(1e-12, max_double),
                          "[m/s] Impact speed used for the Hertz contact time (time-step "
                          "limit) and for the linear stiffness derived from E*.");
      }
      prm.leave_subsection();

      prm.enter_subsection("domain");
      {
        declare(prm, "lower corner", "0, 0, 0", point_pattern(),
                          "[m] Lower corner of the box that holds the particles.");
        declare(prm, "upper corner", "1, 1, 1", point_pattern(),
                          "[m] Upper corner of the box that holds the particles.");
        declare(prm, "periodic x", "false", Bool(),
                          "Periodic in x (no box walls on the x faces).");
        declare(prm, "periodic y", "false", Bool(),
                          "Periodic in y (no box walls on the y faces).");
        declare(prm, "periodic z", "false", Bool(),
                          "Periodic in z (no box walls on the z faces).");
        declare(prm, "outlet", "false", Bool(),
                "Whether particles may leave the domain (an open face, a hopper "
                "outlet): they are removed and counted either way, but without an "
                "outlet the first one to leave is reported as a warning.");
      }
      prm.leave_subsection();
    }

    /// The 'materials' and 'contact' subsections.
    void declare_materials_and_contact(ParameterHandler &prm)
    {
      prm.enter_subsection("materials");
      {
        declare(prm, "density", "2500", List(Double(min_positive, max_double), 1),
                          "[kg/m^3] Particle density, one value per material type "
                          "(the number of values sets the number of types), > 0.",
                "a comma-separated list of numbers > 0");
        declare(prm, "young modulus", "1e7", List(Double(min_positive, max_double), 1),
                          "[Pa] Young's modulus per material type, > 0.",
                "a comma-separated list of numbers > 0, as many as densities");
        declare(prm, "poisson ratio", "0.3", List(Double(-1, 0.5), 1),
                          "[-] Poisson ratio per material type, in (-1, 0.5].",
                "a comma-separated list of numbers in (-1, 0.5], as many as densities");
      }
      prm.leave_subsection();

      prm.enter_subsection("contact");
      {
        declare(prm, "model", "hertz_mindlin", Selection(names<NormalContactModel>().selection()),
                          "Contact law: 'linear' spring-dashpot (Gao & Sun Eqs. 4-11) or "
                          "'hertz_mindlin' (Hertz normal, Mindlin no-slip tangential).");
        declare(prm, "restitution", "0.5", Double(min_positive, 1),
                          "[-] Normal coefficient of restitution of every pair, in (0, 1].",
                "a number in (0, 1]");
        declare(prm, "friction", "0.5", Double(0, max_double),
                          "[-] Coulomb sliding friction of every pair, >= 0. Zero makes the "
                          "scene frictionless: no tangential history is kept.");
        declare(prm, "rolling friction", "0", Double(0, max_double),
                          "[-] Rolling friction coefficient of every pair, >= 0.");
        declare(prm, "rolling model", "constant_torque",
                          Selection(names<RollingResistanceModel>().selection({RollingResistanceModel::none})),
                          "Rolling resistance (active when a rolling friction is > 0): "
                          "'constant_torque' M = -mu_r R* |F_n| w/|w|, or 'viscous' "
                          "M = -mu_r R* |F_n| (R*|w| / v_char) w/|w|.");
        declare(prm, "restitution pairs", "", Patterns::Anything(),
                          "Per-pair overrides 'a-b: value, c-d: value' with material "
                          "types a, b, c, d; range as 'restitution'.",
                "empty, or a comma-separated list of 'a-b: value' with value in (0, 1]");
        declare(prm, "friction pairs", "", Patterns::Anything(),
                          "Per-pair overrides of 'friction', same format.",
                "empty, or 'a-b: value' items with value >= 0");
        declare(prm, "rolling friction pairs", "", Patterns::Anything(),
                          "Per-pair overrides of 'rolling friction', same format.",
                "empty, or 'a-b: value' items with value >= 0");
        declare(prm, "normal stiffness", "0", Double(0, max_double),
                          "[N/m] Linear law only: k_n. 0 derives k_n per pair from E*, R*, "
                          "m* so that the maximum overlap at the characteristic velocity "
                          "equals Hertz's.");
        declare(prm, "tangential stiffness ratio", "0.285714285714", Double(0, 1),
                          "[-] Linear law only: k_t / k_n (2/7 makes the normal and "
                          "tangential oscillation periods of a sphere equal).");
        declare(prm, "neighbour skin", "0", Double(0, max_double),
                          "[m] Verlet-list skin; lists are rebuilt when a particle moved "
                          "more than half of it. 0 picks 0.2 times the largest radius.");
      }
      prm.leave_subsection();
    }

    /// The 'walls' and 'insertion' subsections.
    void declare_walls_and_insertion(ParameterHandler &prm, const unsigned int n_meshes)
    {
      prm.enter_subsection("walls");
      {
        declare(prm, "box", "true", Bool(),
                          "Plane walls on the domain faces of every non-periodic direction.");
        declare(prm, "material", "0", Integer(0),
                          "Material type of the walls (sets E, nu and the pair properties).");
        declare(prm, "planes", "", Patterns::Anything(),
                          "[m] Extra plane walls 'px, py, pz, nx, ny, nz; ...' (a point and "
                          "the normal pointing into the particles).",
                "empty, or ';'-separated groups of six numbers with a nonzero normal");
        declare(prm, "plane materials", "", Patterns::Anything(),
                "Material type of each extra plane, 'm0, m1, ...' in the order of 'planes'; "
                "empty: every plane has 'walls/material'.",
                "empty, or one material type 0..(number of materials - 1) per plane");
        declare(prm, "plane velocities", "", Patterns::Anything(),
                "[m/s] Translational velocity of each extra plane as expressions in the time "
                "t [s], 'vx(t), vy(t), vz(t); ...' in the order of 'planes' (muparser syntax, "
                "pi known; an empty group keeps that plane at rest). A plane moves rigidly: "
                "its point with this velocity, its surface with v + w x (x - point).",
                "empty, or one group of three expressions (or an empty group) per plane");
        declare(prm, "plane angular velocities", "", Patterns::Anything(),
                "[rad/s] Angular velocity of each extra plane about its (moving) point, as "
                "expressions in t, 'wx(t), wy(t), wz(t); ...' in the order of 'planes'.",
                "empty, or one group of three expressions (or an empty group) per plane");
        declare_mesh_walls(prm, n_meshes);
      }
      prm.leave_subsection();

      prm.enter_subsection("insertion");
      {
        declare(prm, "method", "lattice", Selection(names<InsertionMethod>().selection()),
                          "How the particles are created: a jittered 'lattice' or 'random' "
                          "(no overlap) fill of the region, a CSV 'file', or an inline 'list'.");
        declare(prm, "number of particles", "1000", Integer(0),
                          "[-] Particles to insert (lattice and random).");
        declare(prm, "region lower corner", "0, 0, 0", point_pattern(),
                          "[m] Lower corner of the insertion region.");
        declare(prm, "region upper corner", "1, 1, 1", point_pattern(),
                          "[m] Upper corner of the insertion region.");
        declare(prm, "radius", "0.001", Double(min_positive, max_double),
                          "[m] Particle radius (the smallest one when 'radius max' is set), > 0.",
                "a number > 0");
        declare(prm, "radius max", "0", Double(0, max_double),
                          "[m] If larger than 'radius': radii uniform in [radius, radius max].");
        declare(prm, "type", "0", Integer(0), "Material type of inserted particles.");
        declare(prm, "size classes", "", Patterns::Anything(),
                "A discrete mixture for 'lattice' and 'random' instead of 'radius' and "
                "'type': 'radius: mass fraction: type' items separated by ';' (radius [m] "
                "> 0, mass fraction > 0, an existing material type; the fractions are "
                "normalised). Each class gets the number of particles nearest its mass "
                "share, and the classes are shuffled over the sites at random (a perfectly "
                "mixed start). Example: '7.5e-4: 0.5: 0; 1.25e-3: 0.5: 1'.",
                "empty, or ';'-separated 'radius: mass fraction: type' with radius > 0, "
                "fraction > 0, type an existing material");
        declare(prm, "velocity", "0, 0, 0", point_pattern(),
                          "[m/s] Initial velocity of inserted particles.");
        declare(prm, "angular velocity", "0, 0, 0", point_pattern(),
                          "[rad/s] Initial angular velocity of inserted particles.");
        declare(prm, "lattice spacing", "0", Double(0, max_double),
                "[m] Lattice: distance between neighbouring sites; 0 gives 2.1 largest "
                "radii. Below two radii the spheres overlap (only sensible with "
                "'cfd-dem/fixed particles').");
        declare(prm, "maximum initial overlap", "0.05", Double(0, 1),
                "[-] The deepest overlap of two particles, or of a particle and a wall, "
                "accepted at the start, as a fraction of the smaller radius; beyond it, "
                "and for coincident particles or a centre behind a wall, the scene is "
                "refused with the particle ids. Not checked with 'cfd-dem/fixed "
                "particles'.");
        declare(prm, "lattice jitter", "0.1", Double(0, 1),
                          "[-] Random displacement on the lattice, as a fraction of the gap "
                          "between neighbouring spheres.");
        declare(prm, "seed", "1", Integer(0), "Random seed (insertion is reproducible).");
        declare(prm, "file", "", Patterns::Anything(),
                          "CSV file (relative to the .prm), one particle per line: x, y, z, "
                          "radius, type, vx, vy, vz[, wx, wy, wz]; '#' starts a comment. In a clump "
                          "scene a row is a body: x, y, z, template, scale, type, qw, qx, qy, qz, "
                          "vx, vy, vz[, wx, wy, wz] (x: its centroid; q: its orientation).",
                "a readable file name (with 'method = file')");
        declare(prm, "list", "", Patterns::Anything(),
                          "Inline particles, rows as in 'file' separated by ';'.",
                "';'-separated rows of 8 or 11 numbers (clumps: 13 or 16), radius > 0, type an "
                "existing material");
      }
      prm.leave_subsection();
    }

    /// The 'output', 'checkpoint', 'validation' and 'parallel' subsections.
    void declare_output_and_control(ParameterHandler &prm)
    {
      prm.enter_subsection("output");
      {
        declare(prm, "directory", "output", Patterns::Anything(),
                          "Where .pvd/.vtu and .csv files go (relative to the working "
                          "directory).",
                "a directory name; created if missing");
        declare(prm, "base name", "particles", Patterns::Anything(),
                          "Prefix of the output files.",
                "a non-empty file name prefix without '/'");
        declare(prm, "if exists", "new", Selection(names<IfOutputExists>().selection()),
                "What a scene (of any physics) does when its output directory holds an "
                "earlier run's series (<base name>.pvd or .csv): 'stop' refuses to run "
                "(exit 2, nothing touched), 'overwrite' removes that series first, 'new' "
                "writes into <directory>-2 (or -3, ...) and says so. A restart always "
                "continues its own series.");
        declare(prm, "vtu interval", "0", Double(0, max_double),
                          "[s] Simulated time between particle snapshots, and one at a "
                          "stop (exit 4 or 5); 0 writes none.");
        declare(prm, "csv interval", "0", Double(0, max_double),
                          "[s] Simulated time between rows of the .csv time series; 0 writes "
                          "none.");
        declare(prm, "particle csv interval", "0", Double(0, max_double),
                "[s] Simulated time between plain-text dumps of every particle, "
                "<base name>_state_NNNNN.csv (id, type, radius, position, velocity, "
                "angular velocity, force; sorted by id), and one more at the end or at a "
                "stop (exit 4 or 5); 0 writes none.");
        declare(prm, "progress", "true", Bool(),
                          "Show the progress line (on standard error).");
        declare(prm, "summary precision", "8", Integer(1, 17),
                          "[digits] Significant digits of the numbers in the final summary.");
      }
      prm.leave_subsection();

      prm.enter_subsection("checkpoint");
      {
        declare(prm, "step interval", "0", Integer(0),
                "[steps] Write a checkpoint every this many DEM steps, in a cfd-dem scene "
                "fluid steps (0: none). A checkpoint is a directory <output directory>/"
                "<base name>-checkpoint-<step> holding everything the run needs to continue "
                "as if never stopped (in a cfd-dem scene the fluid and the coupling too); it "
                "is written under a temporary name and renamed when complete.");
        declare(prm, "time interval", "0", Double(0, max_double),
                "[s] Write a checkpoint every this much simulated time (0: none); "
                "exclusive with 'step interval'.");
        declare(prm, "keep last", "2", Integer(1),
                "How many of the newest checkpoints are kept; older ones are removed "
                "once a newer one is complete.");
        declare(prm, "restart from", "", Patterns::Anything(),
                "Continue from a checkpoint directory, or 'latest' for the newest complete "
                "one in the output directory. The scene must be the one that wrote it "
                "(particles, materials, contact law, domain, walls, time step; fluid and "
                "coupling entries in a cfd-dem scene); the output series continue.",
                "empty, 'latest' or a checkpoint directory");
      }
      prm.leave_subsection();

      prm.enter_subsection("validation");
      {
        declare(prm, "case", "none",
                          Selection(names<ValidationCase>().selection()),
                          "Which analytical reference this scene is checked against; the "
                          "last line printed is then 'result: <case> value=.. reference=.. "
                          "error=.. wall_s=..'.");
        declare(prm, "tolerance", "0", Double(0, max_double),
                          "[-] If > 0, exit with code 3 when the relative error exceeds it.");
        declare(prm, "packing fraction min", "0.55", Double(0, 1),
                          "[-] settle: lower end of the accepted packing fraction.");
        declare(prm, "packing fraction max", "0.64", Double(0, 1),
                          "[-] settle: upper end of the accepted packing fraction.");
        declare(prm, "kinetic energy threshold", "1e-6", Double(0, max_double),
                          "[J] settle: total kinetic energy below which the bed counts as "
                          "settled.");
      }
      prm.leave_subsection();

      prm.enter_subsection("parallel");
      {
        declare(prm, "maximum contacts per particle", "24", Integer(1, 1000),
                          "[-] Not used any more: with several MPI ranks a particle that "
                          "changes rank now finds the tangential histories of all its "
                          "contacts on its new rank, however many. Accepted so that older "
                          "scene files still run.");
      }
      prm.leave_subsection();
    }
    void declare_parameters(ParameterHandler &prm, const unsigned int n_meshes,
                            const unsigned int n_templates)
    {
      declare_simulation_and_domain(prm);
      declare_materials_and_contact(prm);
      declare_walls_and_insertion(prm, n_meshes);
      declare_output_and_control(prm);
      declare_wear_parameters(prm);
      declare_stream_parameters(prm);
      declare_clump_parameters(prm, n_templates);
      declare_imported_field_parameters(prm);
      declare_sph_parameters(prm);

      declare_fluid_parameters(prm);
      declare_coupling_parameters(prm);
    }

    [[noreturn]] void fail(const SceneParameters &p, const std::string &entry,
                           const std::string &what)
    {
      throw InputError("error in '" + p.file_name + "': entry '" + entry + "' " + what);
    }

    std::vector<double> get_list(ParameterHandler &prm, const std::string &name)
    {
      return dealii::Utilities::string_to_double(
        dealii::Utilities::split_string_list(prm.get(name), ','));
    }

    double to_number(const SceneParameters &p, const std::string &entry,
                     const std::string &text)
    {
      std::istringstream in(text);
      double             v;
      std::string        rest;
      if (!(in >> v) || (in >> rest))
        fail(p, entry, "has '" + text + "', which is not a number");
      return v;
    }

    /// 'insertion/size classes': 'radius: mass fraction: type; ...'.
    std::vector<SizeClass> parse_size_classes(const SceneParameters &p, const std::string &text)
    {
      const std::string      entry = "insertion/size classes";
      std::vector<SizeClass> classes;
      double                 total = 0.;
      for (const auto &item : dealii::Utilities::split_string_list(text, ';'))
        {
          if (item.empty())
            continue;
          const auto fields = dealii::Utilities::split_string_list(item, ':');
          if (fields.size() != 3)
            fail(p, entry, "has '" + item + "', which is not 'radius: mass fraction: type'");
          SizeClass c;
          c.radius        = to_number(p, entry, fields[0]);
          c.mass_fraction = to_number(p, entry, fields[1]);
          const double type = to_number(p, entry, fields[2]);
          if (!(c.radius > 0.))
            fail(p, entry, "has the radius " + fields[0] + ": it must be > 0");
          if (!(c.mass_fraction > 0.) || !std::isfinite(c.mass_fraction))
            fail(p, entry, "has the mass fraction " + fields[1] + ": it must be > 0");
          if (type < 0. || type != std::floor(type) || type >= p.n_materials())
            fail(p, entry, "has the type " + fields[2] + ", outside the material types 0.." +
                             std::to_string(p.n_materials() - 1));
          c.type = static_cast<unsigned int>(type);
          total += c.mass_fraction;
          classes.push_back(c);
        }
      for (SizeClass &c : classes)
        c.mass_fraction /= total;
      return classes;
    }

    /// The per-plane entries of 'walls': materials and motions of the last
    /// n_planes walls (the extra planes, after the box faces).
    void set_plane_properties(SceneParameters &p, const std::size_t n_planes,
                              const std::string &materials, const std::string &velocities,
                              const std::string &angular_velocities)
    {
      const std::size_t first = p.walls.size() - n_planes;
      const auto        count = [&](const std::string &entry, const std::size_t n) {
        if (n != n_planes)
          fail(p, entry, "has " + std::to_string(n) + " groups for " + std::to_string(n_planes) +
                           " plane(s) in 'walls/planes'; give one per plane, in their order");
      };
      if (materials.find_first_not_of(" \t") != std::string::npos)
        {
          const auto list = dealii::Utilities::split_string_list(materials, ',');
          count("walls/plane materials", list.size());
          for (std::size_t k = 0; k < n_planes; ++k)
            {
              const double m = to_number(p, "walls/plane materials", list[k]);
              if (!(m >= 0. && m < p.n_materials() && m == std::floor(m)))
                fail(p, "walls/plane materials",
                     "has '" + list[k] + "'; allowed: material types 0.." +
                       std::to_string(p.n_materials() - 1));
              p.walls[first + k].material = static_cast<unsigned int>(m);
            }
        }
      // Groups are kept as text; the DEM parses them (wall_set.cc) before the
      // first step and names this entry if one does not parse.
      const auto groups = [](const std::string &text) {
        std::vector<std::string> g(1);
        for (const char ch : text)
          if (ch == ';')
            g.emplace_back();
          else
            g.back() += ch;
        return g;
      };
      for (const auto &[text, entry, member] :
           {std::make_tuple(&velocities, "walls/plane velocities", &PlaneWall::velocity),
            std::make_tuple(&angular_velocities, "walls/plane angular velocities",
                            &PlaneWall::angular_velocity)})
        if (text->find_first_not_of(" \t") != std::string::npos)
          {
            const std::vector<std::string> g = groups(*text);
            count(entry, g.size());
            for (std::size_t k = 0; k < n_planes; ++k)
              p.walls[first + k].*member = g[k];
          }
    }


    std::vector<PairOverride> parse_pairs(const SceneParameters &p, const std::string &entry,
                                          const std::string &text, const double lo,
                                          const double hi, const bool lo_open)
    {
      std::vector<PairOverride> pairs;
      for (const auto &item : dealii::Utilities::split_string_list(text, ','))
        {
          if (item.empty())
            continue;
          const auto colon = item.find(':');
          const auto dash  = item.find('-');
          if (colon == std::string::npos || dash == std::string::npos || dash > colon)
            fail(p, entry, "has '" + item + "'; expected 'a-b: value' with material types a, b");
          PairOverride o;
          o.type_a = static_cast<unsigned int>(
            to_number(p, entry, dealii::Utilities::trim(item.substr(0, dash))));
          o.type_b = static_cast<unsigned int>(
            to_number(p, entry, dealii::Utilities::trim(item.substr(dash + 1, colon - dash - 1))));
          o.value  = to_number(p, entry, dealii::Utilities::trim(item.substr(colon + 1)));
          if (o.type_a >= p.n_materials() || o.type_b >= p.n_materials())
            fail(p, entry, "names material type " + std::to_string(std::max(o.type_a, o.type_b)) +
                             ", but only types 0.." + std::to_string(p.n_materials() - 1) +
                             " exist");
          if ((lo_open ? o.value <= lo : o.value < lo) || o.value > hi)
            fail(p, entry, "= " + to_text(o.value) + " is outside the allowed range " +
                             (lo_open ? "(" : "[") + to_text(lo) + ", " +
                             (hi == max_double ? std::string("inf)") : to_text(hi) + "]"));
          pairs.push_back(o);
        }
      return pairs;
    }

    /// The fields of a row as finite numbers. Throws InputError "error in
    /// <where>: the <what> '<row>' has '<field>' in field k, which is not a
    /// finite number".
    std::vector<double> row_numbers(const std::string &where, const std::string &what,
                                    const std::string &row, const std::vector<std::string> &fields)
    {
      std::vector<double> v;
      for (const auto &f : fields)
        {
          std::istringstream in(f);
          double             x;
          std::string        rest;
          if (!(in >> x) || (in >> rest) || !std::isfinite(x))
            throw InputError("error in " + where + ": the " + what + " '" + row + "' has '" + f +
                             "' in field " + std::to_string(v.size() + 1) +
                             ", which is not a finite number");
          v.push_back(x);
        }
      return v;
    }

    /// One particle 'x, y, z, radius, type, vx, vy, vz[, wx, wy, wz]'. 'where'
    /// says where the row is, e.g. "'scene.prm', entry 'insertion/list'".
    ParticleRecord parse_particle_row(const SceneParameters &p, const std::string &where,
                                      const std::string &row)
    {
      const auto fields = dealii::Utilities::split_string_list(row, ',');
      if (fields.size() != 8 && fields.size() != 11)
        throw InputError("error in " + where + ": the row '" + row + "' has " +
                         std::to_string(fields.size()) +
                         " fields; expected x, y, z, radius, type, vx, vy, vz[, wx, wy, wz]");
      const std::vector<double> v = row_numbers(where, "row", row, fields);
      ParticleRecord r;
      r.position = {v[0], v[1], v[2]};
      r.radius   = v[3];
      if (!(r.radius > 0.))
        throw InputError("error in " + where + ": the row '" + row +
                         "' has radius " + fields[3] + "; the radius must be > 0");
      if (v[4] < 0 || v[4] != std::floor(v[4]) || v[4] >= p.n_materials())
        throw InputError("error in " + where + ": the row '" + row + "' has type " +
                         fields[4] + "; types are 0.." + std::to_string(p.n_materials() - 1));
      r.type     = static_cast<unsigned int>(v[4]);
      r.velocity = {v[5], v[6], v[7]};
      if (v.size() == 11)
        r.angular_velocity = {v[8], v[9], v[10]};
      return r;
    }

    /// One clump 'x, y, z, template, scale, type, qw, qx, qy, qz, vx, vy, vz[,
    /// wx, wy, wz]' (the orientation need not be normalised).
    ParticleRecord parse_clump_row(const SceneParameters &p, const std::string &where,
                                   const std::string &row)
    {
      const auto fields = dealii::Utilities::split_string_list(row, ',');
      const auto bad    = [&](const std::string &what) {
        throw InputError("error in " + where + ": the clump row '" + row + "' " + what);
      };
      if (fields.size() != 13 && fields.size() != 16)
        bad("has " + std::to_string(fields.size()) +
            " fields; expected x, y, z, template, scale, type, qw, qx, qy, qz, vx, vy, vz[, "
            "wx, wy, wz]");
      const std::vector<double> v = row_numbers(where, "clump row", row, fields);
      const double n_templates = p.clumps.templates.size();
      if (v[3] < 0 || v[3] != std::floor(v[3]) || v[3] >= n_templates)
        bad("has template " + fields[3] + "; templates are 0.." +
            std::to_string(p.clumps.templates.size() - 1));
      if (!(v[4] > 0.))
        bad("has scale " + fields[4] + "; the scale must be > 0");
      if (v[5] < 0 || v[5] != std::floor(v[5]) || v[5] >= p.n_materials())
        bad("has type " + fields[5] + "; types are 0.." + std::to_string(p.n_materials() - 1));
      const double q_norm = std::sqrt(v[6] * v[6] + v[7] * v[7] + v[8] * v[8] + v[9] * v[9]);
      if (!(q_norm > 0.))
        bad("has the orientation 0, 0, 0, 0; give a quaternion qw, qx, qy, qz (1, 0, 0, 0: "
            "the template's frame)");
      ParticleRecord r;
      r.position       = {v[0], v[1], v[2]};
      r.clump_template = static_cast<unsigned int>(v[3]);
      r.clump_scale    = v[4];
      r.type           = static_cast<unsigned int>(v[5]);
      for (unsigned int k = 0; k < 4; ++k)
        r.orientation[k] = v[6 + k] / q_norm;
      r.velocity = {v[10], v[11], v[12]};
      if (v.size() == 16)
        r.angular_velocity = {v[13], v[14], v[15]};
      return r;
    }

    /// A row of 'insertion/list' or 'insertion/file': a sphere, or a clump
    /// in a clump scene.
    ParticleRecord parse_row(const SceneParameters &p, const std::string &where,
                             const std::string &row)
    {
      return p.clumps.active() ? parse_clump_row(p, where, row) : parse_particle_row(p, where, row);
    }

    std::string directory_of(const std::string &file)
    {
      const auto slash = file.rfind('/');
      return slash == std::string::npos ? std::string() : file.substr(0, slash + 1);
    }

    void read_values(ParameterHandler &prm, SceneParameters &p)
    {
      prm.enter_subsection("simulation");
      p.physics = value_of<Physics>(prm.get("physics"));
      p.end_time                = prm.get_double("end time");
      p.time_step_fraction      = prm.get_double("time step fraction");
      p.maximum_time_step_ratio = prm.get_double("maximum time step ratio");
      p.restitution_accuracy    = prm.get_double("restitution accuracy");
      p.maximum_overlap         = prm.get_double("maximum overlap");
      {
        const std::string dt = dealii::Utilities::trim(prm.get("time step"));
        p.automatic_time_step = (dt == "auto");
        if (!p.automatic_time_step)
          {
            p.time_step = to_number(p, "simulation/time step", dt);
            if (!(p.time_step > 0.))
              fail(p, "simulation/time step",
                   "= " + dt + " is outside the allowed range: 'auto' or a number > 0");
          }
      }
      p.gravity                 = get_vector(prm, "gravity");
      p.characteristic_velocity = prm.get_double("characteristic velocity");
      prm.leave_subsection();

      prm.enter_subsection("domain");
      p.lower_corner = get_vector(prm, "lower corner");
      p.upper_corner = get_vector(prm, "upper corner");
      p.periodic     = {{prm.get_bool("periodic x"), prm.get_bool("periodic y"),
                         prm.get_bool("periodic z")}};
      p.outlet       = prm.get_bool("outlet");
      prm.leave_subsection();
      for (unsigned int d = 0; d < 3; ++d)
        if (!(p.upper_corner[d] > p.lower_corner[d]))
          fail(p, "domain/upper corner", "must be above 'lower corner' in every direction");

      prm.enter_subsection("materials");
      p.density       = get_list(prm, "density");
      p.young_modulus = get_list(prm, "young modulus");
      p.poisson_ratio = get_list(prm, "poisson ratio");
      prm.leave_subsection();
      for (const double rho : p.density)
        if (!(rho > 0.))
          fail(p, "materials/density", "= 0 is outside the allowed range (0, inf)");
      for (const double E : p.young_modulus)
        if (!(E > 0.))
          fail(p, "materials/young modulus", "= 0 is outside the allowed range (0, inf)");
      for (const double nu : p.poisson_ratio)
        if (!(nu > -1.))
          fail(p, "materials/poisson ratio", "= -1 is outside the allowed range (-1, 0.5]");
      if (p.young_modulus.size() != p.density.size() ||
          p.poisson_ratio.size() != p.density.size())
        fail(p, "materials/young modulus",
             "and 'poisson ratio' must have as many values as 'density' (" +
               std::to_string(p.density.size()) + ", one per material type)");

      prm.enter_subsection("contact");
      p.normal_model = value_of<NormalContactModel>(prm.get("model"));
      p.restitution = prm.get_double("restitution");
      if (!(p.restitution > 0.))
        fail(p, "contact/restitution", "= 0 is outside the allowed range (0, 1]");
      p.friction         = prm.get_double("friction");
      p.rolling_friction = prm.get_double("rolling friction");
      p.restitution_pairs =
        parse_pairs(p, "contact/restitution pairs", prm.get("restitution pairs"), 0., 1., true);
      p.friction_pairs =
        parse_pairs(p, "contact/friction pairs", prm.get("friction pairs"), 0., max_double, false);
      p.rolling_friction_pairs = parse_pairs(p, "contact/rolling friction pairs",
                                             prm.get("rolling friction pairs"), 0., max_double,
                                             false);
      p.rolling_model = p.any_rolling_friction() ?
                          value_of<RollingResistanceModel>(prm.get("rolling model")) :
                          RollingResistanceModel::none;
      p.linear_normal_stiffness    = prm.get_double("normal stiffness");
      p.tangential_stiffness_ratio = prm.get_double("tangential stiffness ratio");
      p.neighbour_skin             = prm.get_double("neighbour skin");
      prm.leave_subsection();

      prm.enter_subsection("walls");
      p.box_walls     = prm.get_bool("box");
      p.wall_material = prm.get_integer("material");
      const std::string planes = prm.get("planes");
      const std::string plane_materials = prm.get("plane materials");
      const std::string plane_velocities = prm.get("plane velocities");
      const std::string plane_angular_velocities = prm.get("plane angular velocities");
      p.meshes = read_mesh_walls(prm, p.file_name, p.wall_material, p.n_materials());
      prm.leave_subsection();
      if (p.wall_material >= p.n_materials())
        fail(p, "walls/material", "= " + std::to_string(p.wall_material) +
                                    " is outside the allowed range: material types 0.." +
                                    std::to_string(p.n_materials() - 1));
      if (p.box_walls)
        {
          const char *axis[3] = {"x", "y", "z"};
          for (unsigned int d = 0; d < 3; ++d)
            if (!p.periodic[d])
              for (const int side : {0, 1})
                {
                  PlaneWall w;
                  w.point     = side == 0 ? p.lower_corner : p.upper_corner;
                  w.normal[d] = side == 0 ? 1. : -1.;
                  w.material  = p.wall_material;
                  w.name      = std::string(axis[d]) + (side == 0 ? "_min" : "_max");
                  p.walls.push_back(w);
                }
        }
      const std::size_t n_box_walls = p.walls.size();
      for (const auto &plane : dealii::Utilities::split_string_list(planes, ';'))
        {
          if (plane.empty())
            continue;
          const auto f = dealii::Utilities::split_string_list(plane, ',');
          if (f.size() != 6)
            fail(p, "walls/planes", "has '" + plane + "'; expected 'px, py, pz, nx, ny, nz'");
          std::vector<double> v;
          for (const auto &s : f)
            v.push_back(to_number(p, "walls/planes", s));
          PlaneWall w;
          w.point        = {v[0], v[1], v[2]};
          const Vec3 n   = {v[3], v[4], v[5]};
          const double l = norm(n);
          if (!(l > 0.))
            fail(p, "walls/planes", "has the zero normal in '" + plane + "'");
          w.normal   = (1. / l) * n;
          w.material = p.wall_material;
          w.name     = "plane_" + std::to_string(p.walls.size());
          p.walls.push_back(w);
        }
      set_plane_properties(p, p.walls.size() - n_box_walls, plane_materials,
                           plane_velocities, plane_angular_velocities);

      // The clumps first: they decide what a row of 'insertion/list' holds.
      p.clumps = read_clump_parameters(prm, p.file_name, directory_of(p.file_name));
      prm.enter_subsection("insertion");
      p.insertion_method = value_of<InsertionMethod>(prm.get("method"));
      p.n_particles              = prm.get_integer("number of particles");
      p.region_lower             = get_vector(prm, "region lower corner");
      p.region_upper             = get_vector(prm, "region upper corner");
      p.radius                   = prm.get_double("radius");
      p.radius_max               = prm.get_double("radius max");
      p.particle_type            = prm.get_integer("type");
      p.initial_velocity         = get_vector(prm, "velocity");
      p.initial_angular_velocity = get_vector(prm, "angular velocity");
      p.lattice_jitter           = prm.get_double("lattice jitter");
      p.maximum_initial_overlap  = prm.get_double("maximum initial overlap");
      p.lattice_spacing          = prm.get_double("lattice spacing");
      p.seed                     = prm.get_integer("seed");
      p.particle_file            = prm.get("file");
      const std::string list     = prm.get("list");
      const std::string classes  = prm.get("size classes");
      prm.leave_subsection();
      p.size_classes = parse_size_classes(p, classes);
      if (!p.size_classes.empty() && p.insertion_method != InsertionMethod::lattice &&
          p.insertion_method != InsertionMethod::random)
        fail(p, "insertion/size classes",
             "is set, but 'insertion/method' is neither 'lattice' nor 'random'");
      if (!p.size_classes.empty() && p.radius_max > p.radius)
        fail(p, "insertion/size classes",
             "and 'insertion/radius max' are both set: give the sizes one way");
      if (!p.size_classes.empty() && p.clumps.active())
        fail(p, "insertion/size classes", "is set in a clump scene: clumps have templates");
      if (!(p.radius > 0.))
        fail(p, "insertion/radius", "= 0 is outside the allowed range (0, inf)");
      if (p.particle_type >= p.n_materials())
        fail(p, "insertion/type", "= " + std::to_string(p.particle_type) +
                                    " is outside the allowed range: material types 0.." +
                                    std::to_string(p.n_materials() - 1));
      if (p.insertion_method == InsertionMethod::list)
        for (const auto &row : dealii::Utilities::split_string_list(list, ';'))
          if (!row.empty())
            p.particle_list.push_back(
              parse_row(p, "'" + p.file_name + "', entry 'insertion/list'", row));
      if (p.insertion_method == InsertionMethod::file)
        {
          const std::string path = p.particle_file.size() && p.particle_file[0] == '/' ?
                                     p.particle_file :
                                     directory_of(p.file_name) + p.particle_file;
          std::error_code ec;
          if (p.particle_file.empty())
            fail(p, "insertion/file", "is empty; 'insertion/method = file' needs a CSV file");
          if (std::filesystem::is_directory(path, ec))
            fail(p, "insertion/file", "names '" + path + "', which is a directory");
          std::ifstream in(path);
          if (!in)
            fail(p, "insertion/file", "names '" + path + "', which cannot be opened");
          std::string line;
          unsigned int line_no = 0;
          while (std::getline(in, line))
            {
              ++line_no;
              line = dealii::Utilities::trim(line.substr(0, line.find('#')));
              if (!line.empty())
                p.particle_list.push_back(parse_row(
                  p,
                  "'" + path + "', line " + std::to_string(line_no) + " (entry 'insertion/file')",
                  line));
            }
          if (p.particle_list.empty())
            fail(p, "insertion/file", "names '" + path + "', which holds no particle rows");
        }
      if (p.insertion_method == InsertionMethod::lattice ||
          p.insertion_method == InsertionMethod::random)
        for (unsigned int d = 0; d < 3; ++d)
          if (!(p.region_upper[d] > p.region_lower[d]))
            fail(p, "insertion/region upper corner",
                 "must be above 'region lower corner' in every direction");

      prm.enter_subsection("output");
      p.output_directory  = prm.get("directory");
      p.base_name         = prm.get("base name");
      p.if_output_exists  = value_of<IfOutputExists>(prm.get("if exists"));
      if (p.base_name.empty() || p.base_name.find('/') != std::string::npos)
        fail(p, "output/base name",
             "= '" + p.base_name +
               "' is not allowed: a non-empty file name prefix without '/' (directories go "
               "in 'output/directory')");
      p.vtu_interval      = prm.get_double("vtu interval");
      p.particle_csv_interval = prm.get_double("particle csv interval");
      p.csv_interval      = prm.get_double("csv interval");
      p.progress          = prm.get_bool("progress");
      p.summary_precision = prm.get_integer("summary precision");
      prm.leave_subsection();

      prm.enter_subsection("checkpoint");
      p.checkpoint_step_interval = prm.get_integer("step interval");
      p.checkpoint_time_interval = prm.get_double("time interval");
      p.checkpoints_kept         = prm.get_integer("keep last");
      p.restart_from             = prm.get("restart from");
      prm.leave_subsection();
      if (p.checkpoint_step_interval > 0 && p.checkpoint_time_interval > 0.)
        fail(p, "checkpoint/time interval",
             "and 'checkpoint/step interval' are both set; give one of them");

      prm.enter_subsection("validation");
      p.validation = value_of<ValidationCase>(prm.get("case"));
      p.validation_tolerance     = prm.get_double("tolerance");
      p.packing_fraction_min     = prm.get_double("packing fraction min");
      p.packing_fraction_max     = prm.get_double("packing fraction max");
      p.kinetic_energy_threshold = prm.get_double("kinetic energy threshold");
      prm.leave_subsection();

      p.wear   = read_wear_parameters(prm, p.file_name, p.n_materials());
      p.stream = read_stream_parameters(prm, p.file_name, p.n_materials());
      p.imported_field = read_imported_field_parameters(prm, p.file_name);
      if (p.imported_field.active() && p.physics != Physics::dem)
        throw InputError("error in '" + p.file_name + "': entry 'imported field/file' is set "
                         "in a '" + name_of(p.physics) + "' scene; an imported field drives "
                         "the particles of a 'dem' scene");

      if (!p.clumps.active() && (p.validation == ValidationCase::clump_impact ||
                                 p.validation == ValidationCase::clump_rotation))
        fail(p, "validation/case", "= " + name_of(p.validation) +
                                     " measures a clump; set 'clumps/number of templates'");

      read_fluid_parameters(prm, p.file_name, p.fluid);
      read_coupling_parameters(prm, p.file_name, p.coupling);
      p.sph = read_sph_parameters(prm, p.file_name);
      if (p.clumps.active())
        {
          // What clumps do not take part in: say so rather than run spheres.
          const auto refuse = [&](const std::string &entry, const std::string &what) {
            throw InputError("error in '" + p.file_name + "': entry 'clumps/number of "
                             "templates' > 0 with " + entry + ": " + what);
          };
          if (p.validation == ValidationCase::mesh_plane_equivalence ||
              p.validation == ValidationCase::energy_balance)
            refuse("'validation/case = " + name_of(p.validation) + "'",
                   "this validation runs spheres only");
          if (p.physics == Physics::cfd_dem &&
              p.coupling.validation != CouplingValidationCase::none &&
              p.coupling.validation != CouplingValidationCase::sedimentation)
            refuse("'cfd-dem validation/case = " + name_of(p.coupling.validation) + "'",
                   "this validation places and measures spheres");
          // A body's drag turns with its slip around the orbit: no closed form.
          if (p.imported_field.check == FieldCheck::solid_body_vortex)
            refuse("'imported field/check = solid_body_vortex'",
                   "the orbit's closed form is a sphere's; use 'uniform_stream'");
        }
    }
  } // namespace

  void declare(ParameterHandler &prm, const std::string &name, const std::string &default_value,
               const Patterns::PatternBase &pattern, const std::string &documentation,
               const std::string &allowed)
  {
    std::string range = allowed;
    if (range.empty())
      {
        range = pattern.description(Patterns::PatternBase::Text);
        const std::string max = "MAX_DOUBLE";
        for (std::size_t at; (at = range.find(max)) != std::string::npos;)
          range.replace(at, max.size(), "inf");
      }
    prm.declare_entry(name, default_value, pattern, documentation + " Allowed: " + range + ".");
  }

  double unbounded()
  {
    return std::numeric_limits<double>::max();
  }

  Vec3 get_vector(ParameterHandler &prm, const std::string &name)
  {
    const auto v = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get(name), ','));
    return {v[0], v[1], v[2]};
  }

  std::string to_text(const double value)
  {
    std::ostringstream s;
    s << value;
    return s.str();
  }

  double SceneParameters::largest_radius() const
  {
    double r = size_classes.empty() ? std::max(radius, radius_max) : 0.;
    for (const SizeClass &c : size_classes)
      r = std::max(r, c.radius);
    if (insertion_method == InsertionMethod::file || insertion_method == InsertionMethod::list)
      {
        r = 0.;
        for (const auto &rec : particle_list)
          r = std::max(r, rec.radius);
      }
    return r;
  }

  namespace
  {
    /// deal.II describes a range as '[Double 0...MAX_DOUBLE (inclusive)]'; say
    /// it as a person would: 'a number in [0, inf)', and 'a number > 0' for the
    /// entries that refuse zero (declared from the smallest positive double).
    std::string readable_ranges(const std::string &text)
    {
      const std::regex range(R"(\[Double (\S+?)\.\.\.(\S+) \(inclusive\)\])");
      std::string      out;
      auto             begin = text.cbegin();
      std::smatch      m;
      while (std::regex_search(begin, text.cend(), m, range))
        {
          out.append(begin, m[0].first);
          const std::string lo = m[1].str(), hi = m[2].str() == "MAX_DOUBLE" ? "inf" : m[2].str();
          const double      lo_value = std::atof(lo.c_str());
          if (lo_value > 0. && lo_value <= 1e-300)
            out += hi == "inf" ? "a number > 0" : "a number in (0, " + hi + "]";
          else
            out += "a number in [" + lo + ", " + hi + (hi == "inf" ? ")" : "]");
          begin = m[0].second;
        }
      out.append(begin, text.cend());
      return out;
    }

    /// A scene file must be a readable, non-empty text file: a directory or an
    /// empty file would otherwise run the built-in defaults, and a binary file
    /// would be echoed back in deal.II's message.
    void check_scene_file(const std::string &file_name)
    {
      std::error_code ec;
      if (std::filesystem::is_directory(file_name, ec))
        throw InputError("error: the scene file '" + file_name + "' is a directory");
      std::ifstream probe(file_name, std::ios::binary);
      if (!probe)
        throw InputError("error: cannot open the scene file '" + file_name + "'");
      const std::string content((std::istreambuf_iterator<char>(probe)),
                                std::istreambuf_iterator<char>());
      if (probe.bad())
        throw InputError("error: cannot read the scene file '" + file_name + "'");
      if (content.find_first_not_of(" \t\r\n") == std::string::npos)
        throw InputError("error: the scene file '" + file_name +
                         "' is empty; a scene sets at least one entry (see 'sluice "
                         "--print-parameters')");
      for (std::size_t k = 0; k < content.size(); ++k)
        {
          const unsigned char c = content[k];
          if (c == 0 || (c < 32 && c != '\t' && c != '\n' && c != '\r' && c != '\f'))
            throw InputError("error: the scene file '" + file_name +
                             "' is not a text file (byte " + std::to_string(k) +
                             " is a control character); a scene is a deal.II parameter file");
        }
    }
  } // namespace

  namespace
  {
    /// Parses the scene into prm; deal.II's message, made readable, as an
    /// InputError. With skip_undefined, undeclared entries are ignored.
    void parse_scene(ParameterHandler &prm, const std::string &file_name,
                     const bool skip_undefined)
    {
      try
        {
          prm.parse_input(file_name, "", skip_undefined);
        }
      catch (const dealii::ExceptionBase &e)
        {
          // deal.II's message names the line, the entry and the pattern (the range).
          // (deal.II 9.4 leaves the '>' after the file name out.)
          std::ostringstream info;
          e.print_info(info);
          std::string       text   = info.str();
          const std::string broken = "of file <" + file_name + ":";
          for (auto at = text.find(broken); at != std::string::npos; at = text.find(broken, at))
            text.replace(at, broken.size(), "of file <" + file_name + ">:");
          text = readable_ranges(text);
          throw InputError("error in '" + file_name + "':\n" + text);
        }
    }
  } // namespace

  SceneParameters read_scene_parameters(const std::string &file_name)
  {
    SceneParameters p;
    p.file_name = file_name;
    check_scene_file(file_name);
    // First the number of mesh walls, then everything with their subsections
    // declared (mesh_wall_parameters.h).
    unsigned int n_meshes = 0, n_templates = 0;
    {
      ParameterHandler count;
      declare_parameters(count, 0, 0);
      parse_scene(count, file_name, true);
      count.enter_subsection("walls");
      n_meshes = count.get_integer("number of meshes");
      count.leave_subsection();
      count.enter_subsection("clumps");
      n_templates = count.get_integer("number of templates");
      count.leave_subsection();
    }
    ParameterHandler prm;
    declare_parameters(prm, n_meshes, n_templates);
    parse_scene(prm, file_name, false);
    read_values(prm, p);
    return p;
  }

  void print_scene_parameters(std::ostream &out)
  {
    ParameterHandler prm;
    declare_parameters(prm, 1, 1); // one mesh and one template subsection, as examples
    prm.print_parameters(out, ParameterHandler::OutputStyle::PRM |
                                ParameterHandler::OutputStyle::KeepDeclarationOrder);
  }
} // namespace sluice
