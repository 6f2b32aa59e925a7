#pragma once
// Solid walls as repulsive boundary particles: Monaghan's (1994, J. Comput.
// Phys. 110, 399) Lennard-Jones boundary force, the alternative to the layers
// of wall particles with Adami's boundary condition (sph_boundary.h).
//
// One layer of boundary particles lies on each wall face, in the plane half a
// spacing outside the domain (where the first layer of wall particles would
// be), on a square lattice of 'spacing' along the face. A boundary particle
// at x_b pushes a fluid particle at distance r = |x_a - x_b| < r_0 with the
// force per unit mass
//   f = D [(r_0 / r)^12 - (r_0 / r)^4] (x_a - x_b) / r^2,
// the gradient of the potential
//   phi(r) = D [((r_0 / r)^12 - 1) / 12 - ((r_0 / r)^4 - 1) / 4],
// and not at all beyond r_0. The force is central and conservative: a
// particle leaves the wall with the energy it met it with, and phi grows
// without bound, so no finite energy carries a particle through. With r_0 the
// fluid's spacing the first layer starts at r_0 from the plane, force-free.
// The boundary particles take no part in the fluid's sums: the wall is
// free-slip and the fluid's kernels are cut at it as at a free surface.
// D is of the order of the largest speed squared (Monaghan: 5 g H for a
// dam break).

#include <sluice/core/vector3.h>
#include <sluice/sph/sph_particles.h>

#include <array>
#include <utility>
#include <vector>

namespace sluice
{
  struct LennardJonesLaw
  {
    double strength = 0.; // D [m^2/s^2]
    double range    = 0.; // r_0 [m]
    double spacing  = 0.; // of the boundary particles along a face [m]

    /// The force per unit mass at separation 'r' = x_a - x_b.
    Vec3 acceleration(const Vec3 &r) const;
    /// phi at separation 'r'.
    double potential(const Vec3 &r) const;
  };

  class RepulsiveWalls
  {
  public:
    /// No walls.
    RepulsiveWalls() = default;
    /// Boundary particles on the 'faces' (direction, +1 or -1) of the domain
    /// [lower, upper], in their planes moved 'offset' outward. Along a
    /// periodic direction of the face the lattice repeats; along another it
    /// spans the face edge to edge.
    RepulsiveWalls(const std::vector<std::pair<unsigned int, int>> &faces, const Vec3 &lower,
                   const Vec3 &upper, const std::array<bool, 3> &periodic, double offset,
                   const LennardJonesLaw &law);

    bool                   empty() const { return faces.empty(); }
    const LennardJonesLaw &law() const { return law_; }

    /// The walls' force per unit mass on a fluid particle at x.
    Vec3 acceleration(const Vec3 &x) const;
    /// Its potential energy per unit mass at x.
    double potential(const Vec3 &x) const;
    /// Adds the walls' force per unit mass to every owned fluid particle's
    /// acceleration.
    void add_accelerations(SphParticles &P) const;
    /// Every boundary particle, each periodic lattice once (for tests).
    std::vector<Vec3> boundary_particles() const;

  private:
    struct Face
    {
      unsigned int normal;        // the direction across the face
      double       plane;         // the boundary particles' coordinate along it
      unsigned int along[2];      // the two directions in the face
      double       origin[2], step[2];
      int          n_steps[2];    // lattice points 0 .. n (n - 1 if periodic)
      bool         periodic[2];
    };
    /// Calls f(x - x_b) for every boundary particle within r_0 of x,
    /// periodic images included.
    template <typename Function>
    void for_each_in_reach(const Vec3 &x, const Function &f) const;

    std::vector<Face> faces;
    LennardJonesLaw   law_;
  };
} // namespace sluice
