#pragma once
// A clump's sphericities as Hoelzer & Sommerfeld's drag correlation (2008,
// Powder Technol. 184, 361, Eq. 9) takes them, for a flow along a direction
// n given in the body frame (d_v: the volume-equivalent diameter, S: the
// union's surface area):
//   sphericity  phi      = pi d_v^2 / S                   (Wadell; no direction)
//   crosswise   phi_perp = (pi d_v^2 / 4) / A_perp(n)     A_perp: the shadow along n
//   lengthwise  phi_par  = (pi d_v^2 / 4) / (S / 2 - A_par(n))
// where A_par is the mean shadow seen across the flow, over the directions
// perpendicular to n. All three are 1 for a sphere and none depends on the
// clump's scale. The shadows are exact (sphere_union.h); A_par is the
// midpoint rule over 32 directions across n (a periodic integrand).
//
// The drag needs them for every body at every fluid step, in whatever
// orientation it has. The crosswise sphericity is one shadow, computed
// directly each time: it has a cusp where members line up along the flow,
// which no interpolation resolves. The lengthwise one, a mean over 32
// shadows and smooth, SphericityTable computes once per template on a grid
// of directions over a half sphere (n and -n cast the same shadows) and
// interpolates bilinearly; unit.clump_sphericities bounds both errors.

#include <sluice/core/vector3.h>
#include <sluice/dem/clump_template.h>

#include <vector>

namespace sluice
{
  struct Sphericities
  {
    double sphericity = 1., crosswise = 1., lengthwise = 1.;

    bool spherical() const { return sphericity == 1. && crosswise == 1. && lengthwise == 1.; }
  };

  /// The sphericities of the template for a flow along 'direction' (body
  /// frame, any length > 0), computed directly.
  Sphericities clump_sphericities(const ClumpTemplate &clump, const Vec3 &direction);

  class SphericityTable
  {
  public:
    /// Tabulates the lengthwise sphericity on n_polar polar angles in
    /// [0, pi/2] times n_azimuth azimuths in [0, 2 pi).
    explicit SphericityTable(const ClumpTemplate &clump, unsigned int n_polar = 31,
                             unsigned int n_azimuth = 64);
    /// For a flow along 'direction' (body frame, length > 0): the crosswise
    /// sphericity computed, the lengthwise one interpolated.
    Sphericities operator()(const Vec3 &direction) const;

  private:
    const ClumpTemplate &clump; // outlives the table (the scene's templates)
    unsigned int         n_polar, n_azimuth;
    double               sphericity, equivalent_shadow;
    std::vector<double>  lengthwise; // per node, polar-major
  };
} // namespace sluice
