// A triangulated plane against the plane, step by step (see the header).

#include <sluice/core/result_line.h>
#include <sluice/dem/dem_system.h>
#include <sluice/dem/mesh_contact.h>
#include <sluice/dem/mesh_plane_equivalence.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>

namespace sluice
{
  namespace
  {
    /// How the mesh run's contacts met the surface, summed over steps and
    /// particles: contacts with one triangle within the radius, and those with
    /// several (over a shared edge or vertex), and the most contacts one
    /// particle had at once.
    struct SurfaceVisits
    {
      unsigned long long one_triangle = 0, shared = 0;
      std::size_t        most_contacts = 0;

      void count(const DemSystem &dem)
      {
        std::vector<MeshContact> contacts;
        for (unsigned int i = 0; i < dem.particles.n_local; ++i)
          {
            std::vector<unsigned int> within;
            const Vec3               &x = dem.particles.position[i];
            const double              r = dem.particles.radius[i];
            contacts.clear();
            for (const MeshWall &wall : dem.walls.meshes())
              {
                const TriangleMesh &mesh = wall.mesh();
                within.clear();
                for (unsigned int t = 0; t < mesh.size(); ++t)
                  {
                    const auto &v = mesh.triangles[t];
                    if (norm_square(x - closest_point_on_triangle(x, mesh.vertices[v[0]],
                                                                  mesh.vertices[v[1]],
                                                                  mesh.vertices[v[2]])
                                          .point) < r * r)
                      within.push_back(t);
                  }
                mesh_contacts(mesh, x, r, within, contacts);
                if (within.size() == 1)
                  ++one_triangle;
                else if (within.size() > 1)
                  ++shared;
              }
            most_contacts = std::max(most_contacts, contacts.size());
          }
      }
    };

    /// Largest differences over the run, and the plane run's largest magnitudes.
    struct Differences
    {
      double position = 0., velocity = 0., spin = 0., force = 0.;
      double speed = 0., spin_rate = 0., force_size = 0.;

      void compare(const ParticleStorage &mesh, const ParticleStorage &plane)
      {
        for (unsigned int i = 0; i < plane.n_local; ++i)
          {
            position = std::max(position, norm(mesh.position[i] - plane.position[i]) /
                                            plane.radius[i]);
            velocity   = std::max(velocity, norm(mesh.velocity[i] - plane.velocity[i]));
            spin       = std::max(spin, norm(mesh.angular_velocity[i] - plane.angular_velocity[i]));
            force      = std::max(force, norm(mesh.force[i] - plane.force[i]));
            speed      = std::max(speed, norm(plane.velocity[i]));
            spin_rate  = std::max(spin_rate, norm(plane.angular_velocity[i]));
            force_size = std::max(force_size, norm(plane.force[i]));
          }
      }
      static double relative(const double d, const double scale)
      {
        return scale > 0. ? d / scale : d;
      }
      double largest() const
      {
        return std::max({position, relative(velocity, speed), relative(spin, spin_rate),
                         relative(force, force_size)});
      }
    };

    /// The two variants of the scene.
    SceneParameters with_meshes_only(const SceneParameters &p, const std::size_t n_box_walls)
    {
      SceneParameters q = p;
      q.walls.resize(n_box_walls);
      return q;
    }
    SceneParameters with_planes_only(const SceneParameters &p)
    {
      SceneParameters q = p;
      q.meshes.clear();
      return q;
    }
  } // namespace

  int run_mesh_plane_equivalence(const SceneParameters &p, MPI_Comm comm)
  {
    const auto start = std::chrono::steady_clock::now();
    int        n_ranks, rank;
    MPI_Comm_size(comm, &n_ranks);
    MPI_Comm_rank(comm, &rank);
    const std::string where = "error in '" + p.file_name + "': 'validation/case = " +
                              "mesh_plane_equivalence' ";
    if (n_ranks > 1)
      throw InputError(where + "compares the two runs particle by particle on one MPI rank");
    std::size_t n_box_walls = 0;
    if (p.box_walls)
      for (unsigned int d = 0; d < 3; ++d)
        n_box_walls += p.periodic[d] ? 0 : 2;
    if (p.meshes.empty() || p.walls.size() == n_box_walls)
      throw InputError(where + "needs mesh walls and the planes they are compared with "
                               "('walls/planes')");

    // (A DemSystem keeps a reference to its parameters.)
    const SceneParameters meshes_only = with_meshes_only(p, n_box_walls);
    const SceneParameters planes_only = with_planes_only(p);
    DemSystem             mesh(meshes_only, comm);
    DemSystem             plane(planes_only, comm);
    const unsigned long long n_steps =
      static_cast<unsigned long long>(std::ceil(p.end_time / mesh.dt - 1e-9));
    std::cout << "Sluice DEM - mesh against plane - scene " << p.file_name << "\n"
              << "  particles: " << mesh.n_inserted << ", mesh walls: " << p.meshes.size()
              << " (" << [&]() {
                   unsigned int n = 0;
                   for (const MeshWall &w : mesh.walls.meshes())
                     n += w.mesh().size();
                   return n;
                 }()
              << " triangles), planes: " << p.walls.size() - n_box_walls << ", steps: " << n_steps
              << ", time step = " << std::setprecision(4) << mesh.dt << " s\n";

    Differences   d;
    SurfaceVisits visits;
    d.compare(mesh.particles, plane.particles);
    const GravityKick kick{p.gravity};
    for (unsigned long long step = 1; step <= n_steps; ++step)
      {
        mesh.advance(kick);
        plane.advance(kick);
        d.compare(mesh.particles, plane.particles);
        visits.count(mesh);
      }
    const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double error = d.largest();
    if (rank == 0)
      {
        std::cout << std::setprecision(p.summary_precision)
                  << "check: contact steps on one triangle=" << visits.one_triangle
                  << " over shared edges or vertices=" << visits.shared
                  << " most contacts of one particle=" << visits.most_contacts << " (expected 1)\n"
                  << std::setprecision(3) << "check: largest difference position/radius="
                  << d.position << " velocity=" << Differences::relative(d.velocity, d.speed)
                  << " angular_velocity=" << Differences::relative(d.spin, d.spin_rate)
                  << " contact_force=" << Differences::relative(d.force, d.force_size) << "\n";
        std::cout << std::setprecision(3);
        write_result_line(std::cout, "mesh_plane_equivalence", error, 0., error, wall_s);
      }
    // Several contacts at once, or no contact over an edge or vertex at all,
    // would fail the comparison's purpose however small the differences.
    const bool exercised = visits.shared > 0 && visits.most_contacts == 1;
    if (!exercised && rank == 0)
      std::cerr << "sluice: validation: the spheres must cross shared edges or vertices and "
                   "keep one contact each\n";
    if (!exercised || (p.validation_tolerance > 0. && error > p.validation_tolerance))
      {
        if (rank == 0 && exercised)
          std::cerr << "sluice: validation error " << error << " exceeds the tolerance "
                    << p.validation_tolerance << " set in 'validation/tolerance'\n";
        return 3;
      }
    return 0;
  }
} // namespace sluice
