#pragma once
// How the fluid sees each of the DEM's coupling particles (the handler's
// particles, DemSystem::handler_particles()): a sphere by its volume and
// diameter; a clump body (dem/clump_system.h) by the volume of its members'
// union (overlaps counted once), its volume-equivalent diameter and, for the
// drag, its three sphericities along the slip in its current orientation
// (dem/clump_sphericities.h: the crosswise one computed each time, the
// lengthwise one from a table built once per template). A one-member clump
// is a sphere to the last bit, so that a sphere scene run with clumps
// reproduces its own reference output.
//
// At zero slip the sphericities are those along gravity, where a slip from
// rest begins. The drag acts at the centroid: the correlations give no
// torque, so a body's orientation changes only by its contacts
// (doc/clumps.md).

#include <sluice/core/vector3.h>
#include <sluice/dem/clump_sphericities.h>
#include <sluice/dem/dem_system.h>

#include <memory>
#include <vector>

namespace sluice
{
  /// One particle as the fluid-particle forces take it.
  struct FluidShape
  {
    double       volume = 0.;   // [m^3]
    double       diameter = 0.; // volume-equivalent [m]
    Sphericities sphericities;  // along the slip (all 1 for a sphere)
  };

  class FluidShapes
  {
  public:
    /// Tabulates each multi-member template's lengthwise sphericity (clump
    /// scenes).
    explicit FluidShapes(const DemSystem &dem);

    /// Particle i of dem.handler_particles() for a slip along 'slip' (world
    /// frame).
    FluidShape shape(unsigned int i, const Vec3 &slip) const;
    /// The same with the sphericities computed directly rather than
    /// interpolated in the table (for a validation's reference).
    FluidShape exact_shape(unsigned int i, const Vec3 &slip) const;
    /// Its volume alone [m^3].
    double volume(unsigned int i) const;

    /// Collective: the largest extent of a particle over all ranks, which the
    /// projection kernel must cover (a body's bounding diameter) [m].
    double largest_extent() const;

  private:
    FluidShape shape_of(unsigned int i, const Vec3 &slip, bool exact) const;

    const DemSystem &dem;
    Vec3             at_rest; // the direction taken at zero slip
    // Per template; null for a one-member template (a sphere).
    std::vector<std::unique_ptr<SphericityTable>> tables;
  };
} // namespace sluice
