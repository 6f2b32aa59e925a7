// What an SPH scene starts from (see the header).

#include <sluice/dem/contact_properties.h>
#include <sluice/sph/sph_setup.h>

#include <algorithm>
#include <cmath>

namespace sluice
{
  namespace
  {
    [[noreturn]] void fail(const SceneParameters &p, const std::string &entry,
                           const std::string &what)
    {
      throw InputError("error in '" + p.file_name + "': entry '" + entry + "' " + what);
    }

    /// Lattice points lower + (i + 1/2) dx inside [lower, upper) along one
    /// axis; a length short of whole spacings by less than 1e-3 dx (a
    /// spacing written to a few digits) counts as whole.
    unsigned int n_points(const double lower, const double upper, const double dx)
    {
      return static_cast<unsigned int>(std::max(0., std::floor((upper - lower) / dx + 1e-3)));
    }
  } // namespace

  SphSetup make_sph_setup(const SceneParameters &p)
  {
    const SphParameters &s  = p.sph;
    const double         dx = s.spacing, m = s.density * dx * dx * dx;
    SphSetup             setup;

    // The wall faces and the layers they need: a support of 2h, h = sigma dx.
    // Lennard-Jones walls need no layers: their boundary particles are no SPH particles.
    const bool         repulsive = s.wall_model == "lennard_jones";
    const unsigned int layers =
      repulsive ? 0 : static_cast<unsigned int>(std::ceil(2. * s.smoothing_factor));
    Vec3               lower = p.lower_corner, upper = p.upper_corner;
    for (const std::string &face : s.walls)
      {
        const unsigned int d    = face[0] - 'x';
        const int          side = face[1] == '+' ? 1 : -1;
        if (p.periodic[d])
          fail(p, "sph/walls", "has '" + face + "', but 'domain/periodic " + face.substr(0, 1) +
                                 "' is true: a periodic face cannot be a wall");
        setup.wall_faces.emplace_back(d, side);
        (side > 0 ? upper : lower)[d] += side * (layers * dx);
      }
    // The box: the domain with the wall layers, and a cell more beyond them.
    Vec3 box_lower = lower, box_upper = upper;
    for (unsigned int d = 0; d < 3; ++d)
      if (!p.periodic[d])
        box_lower[d] -= dx, box_upper[d] += dx;
      else if (p.upper_corner[d] - p.lower_corner[d] < 2.4 * 2. * s.smoothing_factor * dx)
        fail(p, "domain/periodic " + std::string(1, "xyz"[d]),
             "is true, but the domain is shorter there than 2.4 kernel supports (" +
               to_text(4.8 * s.smoothing_factor * dx) + " m)");
    setup.box          = PeriodicBox(box_lower, box_upper, p.periodic);
    setup.domain_lower = p.lower_corner;
    setup.domain_upper = p.upper_corner;
    setup.spacing      = dx;

    // The fluid block, at the hydrostatic density of its depth.
    for (unsigned int d = 0; d < 3; ++d)
      if (s.fluid_lower[d] < p.lower_corner[d] - 1e-12 || s.fluid_upper[d] > p.upper_corner[d] + 1e-12 ||
          !(s.fluid_upper[d] > s.fluid_lower[d]))
        fail(p, "sph/fluid upper corner", "and 'fluid lower corner' must span a block inside the "
                                          "domain");
    // Across a periodic direction the block closes on itself: it must hold
    // whole spacings, or the seam has a gap (or a crowd) that collapses.
    for (unsigned int d = 0; d < 3; ++d)
      {
        const double length = p.upper_corner[d] - p.lower_corner[d];
        const double n      = length / dx;
        if (p.periodic[d] && s.fluid_upper[d] - s.fluid_lower[d] > length - 1e-9 * length &&
            std::abs(n - std::round(n)) > 1e-3)
          fail(p, "sph/particle spacing",
               "= " + to_text(dx) + " m fills the periodic length " + to_text(length) +
                 " m along " + std::string(1, "xyz"[d]) + " with " + to_text(n) +
                 " spacings, not a whole number: the fluid would have a gap at the seam; use "
                 "the length over a whole number, e.g. " +
                 to_text(length / std::max(1., std::round(n))) + " m");
      }
    // Gravity along a periodic direction is a body force with no hydrostatic
    // pressure (it drives a channel's flow): only its other components stratify.
    Vec3 stratifying = p.gravity;
    for (unsigned int d = 0; d < 3; ++d)
      if (p.periodic[d])
        stratifying[d] = 0.;
    const double g     = norm(stratifying);
    const Vec3   down  = g > 0. ? (1. / g) * stratifying : Vec3();
    double       top   = -1e300, bottom = 1e300;
    for (unsigned int c = 0; c < 8; ++c)
      {
        const Vec3 corner((c & 1 ? s.fluid_upper : s.fluid_lower).x,
                          (c & 2 ? s.fluid_upper : s.fluid_lower).y,
                          (c & 4 ? s.fluid_upper : s.fluid_lower).z);
        top    = std::max(top, -dot(down, corner));
        bottom = std::min(bottom, -dot(down, corner));
      }
    setup.column_height = g > 0. ? top - bottom : 0.;

    // Tait's equation: c_s keeps the density within 1% of rho_0.
    SphSettings &settings                  = setup.settings;
    settings.kernel                        = s.kernel == "cubic_spline" ? SphKernel::cubic_spline :
                                                                          SphKernel::wendland_c2;
    settings.smoothing_factor              = s.smoothing_factor;
    settings.fixed_smoothing_length        = s.fixed_smoothing_length;
    settings.forces.state.reference_density = s.density;
    settings.forces.viscosity              = s.viscosity;
    settings.forces.viscosity_form         = s.viscosity_form == "signal_velocity" ?
                                               SphViscosityForm::signal_velocity :
                                               SphViscosityForm::morris;
    settings.forces.artificial_viscosity   = s.artificial_viscosity;
    settings.forces.artificial_pressure    = s.artificial_pressure;
    settings.forces.smoothing_factor       = s.smoothing_factor;
    settings.forces.gravity                = p.gravity;
    if (s.sound_speed > 0.)
      {
        settings.forces.state.sound_speed = s.sound_speed;
        setup.sound_speed_origin          = "given";
      }
    else
      {
        const double fall = std::sqrt(2. * g * setup.column_height);
        if (!(std::max(fall, s.characteristic_velocity) > 0.))
          fail(p, "sph/sound speed", "is 0 (automatic), but neither gravity with a fluid "
                                     "height nor 'sph/characteristic velocity' sets a speed: "
                                     "give one of them");
        settings.forces.state.sound_speed = 10. * std::max(fall, s.characteristic_velocity);
        setup.sound_speed_origin = fall >= s.characteristic_velocity ?
                                     "10 sqrt(2 g H)" :
                                     "10 x 'sph/characteristic velocity'";
      }

    if (repulsive)
      {
        // The first fluid layer starts force-free, at r_0 = dx from the plane.
        const double c_s = settings.forces.state.sound_speed;
        const double D   = s.lennard_jones_strength > 0. ? s.lennard_jones_strength :
                                                              c_s * c_s / 40.;
        settings.repulsive_walls = RepulsiveWalls(setup.wall_faces, p.lower_corner, p.upper_corner,
                                                  p.periodic, 0.5 * dx, {D, dx, 0.5 * dx});
      }

    settings.summation_density           = s.summation_density;
    settings.xsph                        = s.xsph;
    settings.integrator                  = s.time_integration == "predictor_corrector" ?
                                             SphIntegrator::predictor_corrector :
                                             SphIntegrator::leap_frog;
    settings.diffusion.delta             = s.density_diffusion;
    settings.diffusion.sound_speed       = settings.forces.state.sound_speed;
    settings.diffusion.reference_density = s.density;
    settings.diffusion.gravity           = stratifying;

    SphParticles &P = setup.particles;
    const unsigned int n[3] = {n_points(s.fluid_lower.x, s.fluid_upper.x, dx),
                               n_points(s.fluid_lower.y, s.fluid_upper.y, dx),
                               n_points(s.fluid_lower.z, s.fluid_upper.z, dx)};
    for (unsigned int k = 0; k < n[2]; ++k)
      for (unsigned int j = 0; j < n[1]; ++j)
        for (unsigned int i = 0; i < n[0]; ++i)
          {
            const Vec3   x        = s.fluid_lower + dx * Vec3(i + 0.5, j + 0.5, k + 0.5);
            const double pressure = g > 0. ? s.density * g * (top + dot(down, x)) : 0.;
            P.push_back(P.size(), x, m, settings.forces.state.density(pressure, 1.),
                        s.smoothing_factor * dx);
          }
    setup.n_fluid = P.size();
    if (setup.n_fluid == 0)
      fail(p, "sph/fluid upper corner", "gives a block without a single particle spacing");

    // The wall particles: the lattice of the extended domain outside the domain.
    const unsigned int w[3] = {n_points(lower.x, upper.x, dx), n_points(lower.y, upper.y, dx),
                               n_points(lower.z, upper.z, dx)};
    for (unsigned int k = 0; k < w[2]; ++k)
      for (unsigned int j = 0; j < w[1]; ++j)
        for (unsigned int i = 0; i < w[0]; ++i)
          {
            const Vec3 x = lower + dx * Vec3(i + 0.5, j + 0.5, k + 0.5);
            bool       outside = false;
            for (unsigned int d = 0; d < 3; ++d)
              outside = outside || x[d] < p.lower_corner[d] || x[d] > p.upper_corner[d];
            if (outside)
              P.push_back(P.size(), x, m, s.density, s.smoothing_factor * dx, true);
          }
    setup.n_walls = P.size() - setup.n_fluid;
    P.n_local     = P.size();
    return setup;
  }

  SolidWallLaw solid_wall_law(const SceneParameters &p, const SphSetup &setup)
  {
    const SphParameters &s = p.sph;
    const double         c = setup.settings.forces.state.sound_speed;
    SolidWallLaw         law;
    law.radius        = 0.5 * setup.spacing;
    law.stiffness     = s.solid_wall_stiffness > 0. ? s.solid_wall_stiffness :
                                                      0.25 * s.density * c * c * setup.spacing;
    law.damping_ratio = damping_ratio_from_restitution(s.solid_wall_restitution);
    return law;
  }
} // namespace sluice
