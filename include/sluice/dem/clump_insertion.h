#pragma once
// The bodies of a clump scene at the start (clump_system.h): from
// 'insertion/list' or 'file' rows as given, or a lattice or random fill of the
// region whose sites are those of spheres of the largest bounding radius, so
// that no two bodies overlap whatever their orientation. Each generated body
// draws its template by the templates' fractions, its scale uniformly in
// [scale, scale max] and, with 'clumps/random orientation', an orientation
// uniform over the rotations (Shoemake 1992, Graphics Gems III). Every rank
// draws the same bodies from the seed.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/clump_template.h>

#include <random>
#include <vector>

namespace sluice
{
  /// All bodies in id order; 'radius' of each is its bounding radius.
  std::vector<ParticleRecord> create_clump_bodies(const SceneParameters       &parameters,
                                                  const std::vector<ClumpTemplate> &templates);

  /// Draws a body's template (by the fractions), scale and, with 'clumps/
  /// random orientation', orientation into r, and sets its bounding radius.
  void draw_clump_body(const ClumpParameters &parameters, const std::vector<ClumpTemplate> &templates,
                       std::mt19937_64 &random, ParticleRecord &r);

  /// The mean mass of the bodies drawn so, for material density rho [kg].
  double mean_clump_mass(const ClumpParameters &parameters,
                         const std::vector<ClumpTemplate> &templates, double rho);

  /// The largest bounding radius a body of these templates can have [m].
  double largest_bounding_radius(const ClumpParameters            &parameters,
                                 const std::vector<ClumpTemplate> &templates);
} // namespace sluice
