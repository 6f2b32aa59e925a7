// The particles as the fluid sees them (see the header).

#include <sluice/core/sphere.h>
#include <sluice/coupling/fluid_shapes.h>
#include <sluice/dem/eigen_conversion.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace sluice
{
  FluidShapes::FluidShapes(const DemSystem &dem)
    : dem(dem)
    , at_rest(norm(dem.p.gravity) > 0. ? dem.p.gravity : Vec3(0., 0., 1.))
  {
    if (dem.clumps)
      for (const ClumpTemplate &t : dem.clumps->templates)
        tables.push_back(t.members.size() == 1 ? nullptr : std::make_unique<SphericityTable>(t));
  }

  double FluidShapes::volume(const unsigned int i) const
  {
    const ParticleStorage &P = dem.handler_particles();
    if (!dem.clumps)
      return sphere_volume(P.radius[i]);
    const ClumpTemplate &t = dem.clumps->template_of(i);
    const double         s = dem.clumps->scale_of(i);
    // A one-member clump's volume as its sphere's, to the last bit.
    return t.members.size() == 1 ? sphere_volume(s * t.radii[0]) : s * s * s * t.volume;
  }

  FluidShape FluidShapes::shape(const unsigned int i, const Vec3 &slip) const
  {
    return shape_of(i, slip, false);
  }

  FluidShape FluidShapes::exact_shape(const unsigned int i, const Vec3 &slip) const
  {
    return shape_of(i, slip, true);
  }

  FluidShape FluidShapes::shape_of(const unsigned int i, const Vec3 &slip, const bool exact) const
  {
    const ParticleStorage &P = dem.handler_particles();
    FluidShape             f;
    f.volume = volume(i);
    if (!dem.clumps)
      {
        f.diameter = 2. * P.radius[i];
        return f;
      }
    const ClumpTemplate &t = dem.clumps->template_of(i);
    const double         s = dem.clumps->scale_of(i);
    if (t.members.size() == 1)
      {
        f.diameter = 2. * s * t.radii[0];
        return f;
      }
    f.diameter = s * t.volume_equivalent_diameter();
    // The slip in the body frame: R^T slip.
    const Vec3               along = norm(slip) > 0. ? slip : at_rest;
    const Eigen::Quaterniond q     = dem.clumps->rotation_of(i).orientation;
    const Vec3               n     = to_vec3(q.conjugate() * to_eigen(along));
    f.sphericities = exact ? clump_sphericities(t, n) : (*tables[dem.clumps->template_index(i)])(n);
    return f;
  }

  double FluidShapes::largest_extent() const
  {
    double extent = 2. * (dem.clumps ? dem.body_radius_max : dem.r_max);
    MPI_Allreduce(MPI_IN_PLACE, &extent, 1, MPI_DOUBLE, MPI_MAX, dem.comm);
    return extent;
  }
} // namespace sluice
