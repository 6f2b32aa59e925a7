#pragma once
// The DEM's walls - its planes and triangle meshes, moving or not - as
// obstacles to the SPH fluid, by the spring-dashpot contact Gao & Sun (§4)
// put between SPH particles and walls (doc/sph.md).
//
// Each fluid particle is a sphere of radius R = dx/2. A wall closer than R
// (the contact points of mesh_contact.h: one per contact patch, not one per
// triangle) pushes it along the contact normal n with
//   F = max(0, k delta - c v_n) n,
// delta = R - distance the overlap, v_n = (v_a - v_wall) . n the normal
// relative velocity at the contact point, and c = 2 zeta sqrt(k m_a) from a
// restitution e (damping_ratio_from_restitution, as the DEM's linear law).
// There is no tangential force: the wall is free slip, and the fluid's
// kernel sums are cut at it as at a free surface (as with the Lennard-Jones
// walls). The wall takes -F: the walls' load is kept per wall. Walls are met
// where they are, without periodic images: a mesh across a periodic seam is
// not seen from the other side.
//
// The default stiffness k = rho_0 c_s^2 dx / 4 lets a particle hold the
// pressure p on its face dx^2 at delta / dx = 4 p / (rho_0 c_s^2): about 4%
// of dx at the 1% density variation the sound speed is chosen for. Its
// period 2 pi sqrt(m / k) = 4 pi dx / c_s spans some 30 steps of the CFL
// step 0.375 dx / c_s.

#include <sluice/core/vector3.h>
#include <sluice/dem/mesh_contact.h>
#include <sluice/dem/triangle_bins.h>
#include <sluice/dem/wall_set.h>
#include <sluice/sph/sph_particles.h>

#include <vector>

namespace sluice
{
  struct SolidWallLaw
  {
    double stiffness     = 0.; // k [N/m]
    double damping_ratio = 0.; // zeta [-]
    double radius        = 0.; // R of a fluid particle [m]
  };

  class SphSolidWalls
  {
  public:
    /// No walls.
    SphSolidWalls() = default;
    /// The walls of 'walls' (kept by reference: it must outlive this, and is
    /// moved by its owner), for particles in the box [lower, upper].
    SphSolidWalls(const WallSet &walls, const SolidWallLaw &law, const Vec3 &lower,
                  const Vec3 &upper);

    bool                empty() const { return walls_ == nullptr; }
    const SolidWallLaw &law() const { return law_; }
    /// Meets the same walls in another WallSet from now on (a copy's, moved
    /// by the copy's owner). It must describe the same walls.
    void rebind(const WallSet &walls);

    /// Adds the walls' forces per unit mass on every owned fluid particle, at
    /// its position and velocity now, to its acceleration; keeps each wall's
    /// load and the largest overlap. Sorts moving meshes' triangles afresh.
    void add_accelerations(SphParticles &P);

    /// The force of the fluid on each wall (numbered as in the WallSet), its
    /// torque about the wall's motion origin (a plane's: the coordinates'
    /// origin), and the power each wall gives the fluid, sum F_a . v_wall at
    /// the contact points, at the last add_accelerations().
    const std::vector<Vec3>   &wall_forces() const { return force_; }
    const std::vector<Vec3>   &wall_torques() const { return torque_; }
    const std::vector<double> &wall_powers() const { return power_; }
    /// The largest overlap at the last add_accelerations() [m].
    double max_overlap() const { return max_overlap_; }

    /// The largest step that resolves the contact: 0.2 sqrt(m / k) for the
    /// lightest fluid particle (its period in 31 steps).
    double stable_time_step(const SphParticles &P) const;

  private:
    /// The force on particle a from one contact at 'point' (its lever about
    /// the wall's origin: 'lever'), added to the wall's load.
    Vec3 contact_force(const SphParticles &P, unsigned int a, unsigned int wall,
                       const Vec3 &normal, double overlap, const Vec3 &wall_velocity,
                       const Vec3 &lever);

    const WallSet            *walls_ = nullptr;
    SolidWallLaw              law_;
    std::vector<TriangleBins> bins_; // per mesh
    std::vector<Vec3>         force_, torque_;
    std::vector<double>       power_;
    double                    max_overlap_ = 0.;
    // Scratch per particle.
    std::vector<unsigned int> candidates_;
    std::vector<MeshContact>  contacts_;
  };
} // namespace sluice
