#pragma once
// What an SPH scene starts from (the 'sph' subsection): the fluid block on a
// lattice, at the hydrostatic density of its depth under gravity (its component
// along non-periodic directions; along a periodic one it only drives), and the
// wall particles in layers outside the wall faces of the domain, enough to
// fill a kernel's support (2h), or with 'wall model = lennard_jones' the
// faces' repulsive boundary particles (sph_repulsive_walls.h); the box the
// particles live in (the domain, extended by the layers in its non-periodic
// directions) and the solver's settings, the sound speed among them.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_particles.h>
#include <sluice/sph/sph_solver.h>

#include <string>
#include <vector>

namespace sluice
{
  struct SphSetup
  {
    SphParticles particles;
    PeriodicBox  box;
    Vec3         domain_lower, domain_upper; // the domain, inside the walls [m]
    double       spacing = 0.;               // the lattice's dx [m]
    SphSettings  settings;
    double       column_height = 0.; // the fluid block's height along gravity [m]
    unsigned int n_fluid = 0, n_walls = 0;
    unsigned int n_cut_by_walls = 0; // lattice points the solid walls cut off (sph_fluid_trim.h)
    // The wall faces, as (direction, +1 or -1): a fluid particle beyond one has leaked.
    std::vector<std::pair<unsigned int, int>> wall_faces;
    std::string  sound_speed_origin; // what set c_s, for the header
  };

  /// Throws InputError naming the entry for a scene that cannot be set up.
  SphSetup make_sph_setup(const SceneParameters &parameters);

  /// The solid walls' contact ('sph/solid walls'): R = dx/2, k as given or
  /// rho_0 c_s^2 dx / 4 (sph_solid_walls.h), zeta from the restitution.
  SolidWallLaw solid_wall_law(const SceneParameters &parameters, const SphSetup &setup);
} // namespace sluice
