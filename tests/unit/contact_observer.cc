// The contact observer sees what the contact law does, through the DEM's own
// step (DemSystem::advance):
// - two spheres meeting head on: one contact start, one impact record per
//   sphere, each with 1/2 m_eff v_n^2 of the approach (exact: nothing acts on
//   them before they touch), and none while they touch or after;
// - a sphere striking a floor: one impact with 1/2 m v^2, counted on that wall;
// - a sphere sliding on a floor until it rolls (and one set down on a belt):
//   the shear work recorded on the wall equals the sliding and spin energy
//   the sphere lost (in the belt's frame), m U^2 / 7 by Coulomb's law;
// - detached, it records nothing; its sums survive a checkpoint round trip;
// - on a triangulated floor (a mesh wall), the same impact and the same
//   sliding to rolling: the per-triangle sums add up to the wall's to
//   round-off, the slide wears several triangles, and the wear statistics
//   (wear_and_breakage.h) turn them into depths, spectra and breakage
//   probabilities by their definitions.

#include <sluice/dem/dem_system.h>
#include <sluice/dem/wear_and_breakage.h>

#include <deal.II/base/mpi.h>

#include "check.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  /// A scene file with the given walls, insertion list and gravity.
  SceneParameters scene(const std::string &name, const std::string &walls,
                        const std::string &list, const std::string &gravity)
  {
    const std::string file = "contact_observer_" + name + ".prm";
    std::ofstream(file) << "subsection simulation\n  set end time = 1\n  set gravity = "
                        << gravity << "\nend\n"
                        << "subsection domain\n  set lower corner = -0.05, -0.3, 0\n"
                           "  set upper corner = 0.05, 0.3, 0.05\nend\n"
                        << "subsection materials\n  set density = 2500\n"
                           "  set young modulus = 1e8\n  set poisson ratio = 0.25\nend\n"
                        << "subsection contact\n  set model = hertz_mindlin\n"
                           "  set restitution = 0.5\n  set friction = 0.3\nend\n"
                        << "subsection walls\n" << walls << "end\n"
                        << "subsection insertion\n  set method = list\n  set list = " << list
                        << "\nend\n";
    return read_scene_parameters(file);
  }

  /// The plane z = 0 over the domain as an ASCII STL of 4 x 40 cells, each cut
  /// into two triangles along alternating diagonals; its subsection.
  std::string mesh_floor()
  {
    std::ofstream stl("contact_observer_floor.stl");
    stl << "solid floor\n";
    const double x0 = -0.05, y0 = -0.3, dx = 0.025, dy = 0.015;
    auto vertex = [&](const int i, const int j) {
      stl << "   vertex " << x0 + i * dx << " " << y0 + j * dy << " 0\n";
    };
    auto facet = [&](const int a[2], const int b[2], const int c[2]) {
      stl << " facet normal 0 0 1\n  outer loop\n";
      vertex(a[0], a[1]);
      vertex(b[0], b[1]);
      vertex(c[0], c[1]);
      stl << "  endloop\n endfacet\n";
    };
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 40; ++j)
        {
          const int p00[2] = {i, j}, p10[2] = {i + 1, j}, p01[2] = {i, j + 1},
                    p11[2] = {i + 1, j + 1};
          if ((i + j) % 2 == 0)
            facet(p00, p10, p11), facet(p00, p11, p01);
          else
            facet(p00, p10, p01), facet(p10, p11, p01);
        }
    stl << "endsolid floor\n";
    return "  set box = false\n  set number of meshes = 1\n  subsection mesh 0\n"
           "    set file = contact_observer_floor.stl\n    set name = floor\n  end\n";
  }

  double sum_of(const std::vector<ImpactRecord> &records)
  {
    double e = 0.;
    for (const auto &r : records)
      e += r.energy;
    return e;
  }

  /// Horizontal translational plus rotational energy, in the frame moving
  /// with 'frame_velocity'.
  double sliding_energy(const ParticleStorage &P, const Vec3 &frame_velocity)
  {
    const double R = P.radius[0], m = P.mass[0];
    Vec3         v = P.velocity[0] - frame_velocity;
    v.z            = 0.;
    return 0.5 * m * norm_square(v) + 0.5 * (0.4 * m * R * R) * norm_square(P.angular_velocity[0]);
  }

  void head_on_pair()
  {
    const SceneParameters p = scene("pair", "  set box = false\n",
                                    "-0.006, 0, 0.02, 0.005, 0, 0.1, 0, 0; "
                                    "0.006, 0, 0.02, 0.005, 0, -0.1, 0, 0",
                                    "0, 0, 0");
    DemSystem       dem(p, MPI_COMM_WORLD);
    ContactObserver observer(dem.walls.n_walls());
    dem.observe(&observer);
    const double m_eff = 0.5 * dem.particles.mass[0];
    std::vector<ImpactRecord> impacts;
    for (unsigned int s = 0; s < 20000; ++s) // 0.012 m apart -> touch, bounce, part
      {
        dem.advance(GravityKick{p.gravity});
        for (const auto &r : observer.take_impacts())
          impacts.push_back(r);
      }
    const double expected = 0.5 * m_eff * 0.2 * 0.2;
    check(impacts.size() == 2, "impact records of a head-on pair (one per sphere)",
          impacts.size(), 2);
    check(impacts.size() == 2 && impacts[0].id != impacts[1].id && !impacts[0].wall,
          "the two records name both spheres", 0, 0);
    for (const auto &r : impacts)
      check(std::abs(r.energy - expected) < 1e-12 * expected,
            "impact energy 1/2 m_eff v_n^2 of the pair", r.energy, expected);
    check(dem.particles.velocity[0].x < 0., "the pair has bounced apart",
          dem.particles.velocity[0].x, -0.05);
    std::printf("pair: %zu impact records, energy %.15g J (expected %.15g J)\n", impacts.size(),
                impacts.empty() ? 0. : impacts[0].energy, expected);
  }

  void floor_impact()
  {
    const SceneParameters p = scene("floor", "  set box = false\n  set planes = 0, 0, 0, 0, 0, 1\n",
                                    "0, 0, 0.006, 0.005, 0, 0, 0, -0.3", "0, 0, 0");
    DemSystem       dem(p, MPI_COMM_WORLD);
    ContactObserver observer(dem.walls.n_walls());
    dem.observe(&observer);
    std::vector<ImpactRecord> impacts;
    for (unsigned int s = 0; s < 20000; ++s)
      {
        dem.advance(GravityKick{p.gravity});
        for (const auto &r : observer.take_impacts())
          impacts.push_back(r);
      }
    const double expected = 0.5 * dem.particles.mass[0] * 0.3 * 0.3;
    check(impacts.size() == 1 && impacts[0].wall && impacts[0].partner == 0,
          "one impact record on the floor", impacts.size(), 1);
    check(std::abs(sum_of(impacts) - expected) < 1e-12 * expected,
          "impact energy 1/2 m v^2 on the floor", sum_of(impacts), expected);
    check(observer.wall_impact_energy[0] == sum_of(impacts),
          "the floor's cumulative impact energy", observer.wall_impact_energy[0], expected);
    check(observer.wall_shear_work[0] == 0., "no shear work in a head-on impact",
          observer.wall_shear_work[0], 0.);
    std::printf("floor: %zu impact, %.15g J (expected %.15g J)\n", impacts.size(),
                sum_of(impacts), expected);

    // Detached: a second approach records nothing.
    dem.observe(nullptr);
    dem.particles.position[0].z = 0.006;
    dem.particles.velocity[0]   = Vec3(0., 0., -0.3);
    for (unsigned int s = 0; s < 20000; ++s)
      dem.advance(GravityKick{p.gravity});
    check(observer.take_impacts().empty(), "a detached observer records nothing", 0, 0);

    // Its sums as a checkpoint keeps them.
    ContactObserver copy(dem.walls.n_walls());
    check(copy.set_state(observer.state()) && copy.state() == observer.state(),
          "observer sums restored exactly", 0, 0);
    check(!copy.set_state({1.}), "sums for other walls are refused", 0, 0);
  }

  /// A sphere sliding at U relative to the floor (or set down at rest on a
  /// belt moving at U) ends rolling: the shear work is the energy it lost.
  void sliding_to_rolling(const bool belt)
  {
    const double    U = 1.;
    const SceneParameters p =
      belt ? scene("belt",
                   "  set box = false\n  set planes = 0, 0, 0, 0, 0, 1\n"
                   "  set plane velocities = 0, 1, 0\n",
                   "0, 0, 0.004999, 0.005, 0, 0, 0, 0, 0, 0, 0", "0, 0, -9.81") :
             scene("slide", "  set box = false\n  set planes = 0, 0, 0, 0, 0, 1\n",
                   "0, 0, 0.004999, 0.005, 0, 0, -1, 0, 0, 0, 0", "0, 0, -9.81");
    const Vec3      frame = belt ? Vec3(0., U, 0.) : Vec3();
    DemSystem       dem(p, MPI_COMM_WORLD);
    ContactObserver observer(dem.walls.n_walls());
    dem.observe(&observer);
    const double E0 = sliding_energy(dem.particles, frame);
    // Sliding stops after U / (3.5 mu g) = 0.097 s; run to 0.2 s.
    const auto n_steps = static_cast<unsigned int>(0.2 / dem.dt);
    for (unsigned int s = 0; s < n_steps; ++s)
      dem.advance(GravityKick{p.gravity});
    const double lost   = E0 - sliding_energy(dem.particles, frame);
    const double work   = observer.wall_shear_work[0];
    const double coulomb = dem.particles.mass[0] * U * U / 7.;
    std::printf("%s: shear work %.9g J, energy lost %.9g J (m U^2 / 7 = %.9g J), "
                "ratio %.6f\n",
                belt ? "belt" : "slide", work, lost, coulomb, work / lost);
    check(std::abs(work - lost) < 2e-3 * lost, "shear work = sliding energy lost", work, lost);
    check(std::abs(work - coulomb) < 1e-2 * coulomb, "shear work = m U^2 / 7", work, coulomb);
  }
  double sum(const std::vector<double> &v)
  {
    double s = 0.;
    for (const double x : v)
      s += x;
    return s;
  }

  /// The floor impact on the triangulated floor, with the wear statistics.
  void mesh_floor_impact()
  {
    SceneParameters p = scene("mesh_floor", mesh_floor(), "0.0125, 0.01, 0.006, 0.005, 0, 0, 0, -0.3",
                              "0, 0, 0");
    p.wear.collect               = true;
    p.wear.breakage_coefficients = {20.};
    ParticleFieldRegistry fields;
    WearAndBreakage::declare_fields(p, fields);
    DemSystem       dem(p, MPI_COMM_WORLD, fields);
    WearAndBreakage wear(p, dem);
    for (unsigned int s = 0; s < 20000; ++s)
      {
        dem.advance(GravityKick{p.gravity});
        wear.after_step(dem);
      }
    const ContactObserver &o        = *dem.observer();
    const double           m        = dem.particles.mass[0];
    const double           expected = 0.5 * m * 0.3 * 0.3;
    check(std::abs(o.wall_impact_energy[0] - expected) < 1e-12 * expected,
          "impact energy 1/2 m v^2 on the mesh floor", o.wall_impact_energy[0], expected);
    check(sum(o.triangle_impact_energy) == o.wall_impact_energy[0],
          "the triangles' impact energies add up to the mesh's", sum(o.triangle_impact_energy),
          o.wall_impact_energy[0]);
    // Br = C_br E_imp / m (Gao & Sun Eq. 13) with E_imp / m = v^2 / 2.
    std::ostringstream summary;
    summary << std::setprecision(15);
    wear.finish(summary, dem, ".", "contact_observer_mesh");
    const std::string text = summary.str();
    const auto        at   = text.find("mean_breakage=");
    const double      Br   = at == std::string::npos ? 0. : std::stod(text.substr(at + 14));
    check(std::abs(Br - 20. * 0.045) < 1e-12, "breakage probability C_br v^2 / 2", Br, 0.9);
    std::printf("mesh floor: impact %.15g J (expected %.15g J), Br %.15g (expected 0.9)\n",
                o.wall_impact_energy[0], expected, Br);
  }

  /// Sliding to rolling on the triangulated floor, and the wear it leaves.
  void mesh_sliding_to_rolling(const WearModel model)
  {
    // Sliding at 1 m/s along -y, without spin.
    SceneParameters p = scene("mesh_slide", mesh_floor(),
                              "0.0125, 0.1, 0.004999, 0.005, 0, 0, -1, 0, 0, 0, 0", "0, 0, -9.81");
    p.wear.collect          = true;
    p.wear.model            = model;
    p.wear.wear_coefficient = 2e-12;
    ParticleFieldRegistry fields;
    WearAndBreakage::declare_fields(p, fields);
    DemSystem       dem(p, MPI_COMM_WORLD, fields);
    WearAndBreakage wear(p, dem);
    const double    E0      = sliding_energy(dem.particles, Vec3());
    const auto      n_steps = static_cast<unsigned int>(0.2 / dem.dt);
    for (unsigned int s = 0; s < n_steps; ++s)
      {
        dem.advance(GravityKick{p.gravity});
        wear.after_step(dem);
      }
    const ContactObserver &o    = *dem.observer();
    const double           lost = E0 - sliding_energy(dem.particles, Vec3());
    const double           work = o.wall_shear_work[0];
    check(std::abs(work - lost) < 2e-3 * lost, "mesh: shear work = sliding energy lost", work,
          lost);
    check(std::abs(sum(o.triangle_shear_work) - work) < 1e-12 * work,
          "the triangles' shear work adds up to the mesh's", sum(o.triangle_shear_work), work);
    unsigned int worn = 0;
    for (const double w : o.triangle_shear_work)
      worn += w != 0.;
    check(worn >= 5, "the slide wears several triangles", worn, 5);
    // Depths by their definitions: sum dh A = C_wr E_sh (Eq. 12), or k sum F_n s / H;
    // while sliding F_t = mu F_n, so mu sum F_n s is the shear work.
    const auto fields_of_floor = wear.mesh_fields(dem.walls, MPI_COMM_WORLD)[0];
    double     volume = 0.;
    for (unsigned int t = 0; t < dem.walls.meshes()[0].mesh().size(); ++t)
      volume += fields_of_floor[2].second[t] * dem.walls.meshes()[0].mesh().areas[t];
    const double load_slip = sum(o.triangle_load_slip);
    const double expected  = model == WearModel::archard ? p.wear.archard_coefficient *
                                                            load_slip / p.wear.hardness :
                                                          p.wear.wear_coefficient * work;
    check(std::abs(volume - expected) < 1e-12 * expected, "worn volume by the wear model", volume,
          expected);
    check(std::abs(0.3 * load_slip - work) < 2e-3 * work, "mu F_n s = shear work while sliding",
          0.3 * load_slip, work);
    std::printf("mesh slide (%s): shear work %.9g J on %u triangles, energy lost %.9g J, "
                "mu F_n s %.9g J, worn volume %.6g m^3\n",
                model == WearModel::archard ? "archard" : "shear energy", work, worn, lost,
                0.3 * load_slip, volume);
  }
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  head_on_pair();
  floor_impact();
  sliding_to_rolling(false);
  sliding_to_rolling(true);
  mesh_floor_impact();
  mesh_sliding_to_rolling(WearModel::shear_energy);
  mesh_sliding_to_rolling(WearModel::archard);
  return sluice::unit::failures == 0 ? 0 : 1;
}
