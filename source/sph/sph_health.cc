// The SPH fluid's health after a step (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/sph/sph_health.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace sluice
{
  void check_sph_health(const SphParticles &P, const SphSetup &setup, const double time)
  {
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        if (P.wall[a])
          continue;
        const Vec3        &x    = P.position[a];
        const auto         here = [&]() {
          std::ostringstream where;
          where << std::setprecision(6) << "SPH particle " << P.id[a] << " at (" << x.x << ", "
                << x.y << ", " << x.z << ") m, t = " << time << " s";
          return where.str();
        };
        if (!std::isfinite(norm_square(x)) || !std::isfinite(norm_square(P.velocity[a])) ||
            !std::isfinite(P.density[a]))
          throw SimulationFailure(here() + ": its state is not finite (lower "
                                           "'sph/time step fraction')");
        for (const auto &[d, side] : setup.wall_faces)
          if (side * (x[d] - (side > 0 ? setup.domain_upper[d] : setup.domain_lower[d])) > 0.)
            throw SimulationFailure(
              here() + ": it passed through the wall '" + std::string(1, "xyz"[d]) +
              (side > 0 ? "+" : "-") + "' (raise " +
              (setup.settings.repulsive_walls.empty() ? "'sph/sound speed'" :
                                                        "'sph/lennard-jones strength'") +
              " or lower the step)");
      }
  }

  void check_solid_wall_overlap(const SphSolidWalls &walls, const double spacing,
                                const double time)
  {
    if (walls.max_overlap() < 0.25 * spacing)
      return;
    std::ostringstream msg;
    msg << std::setprecision(4) << "at t = " << time << " s a fluid particle came within "
        << 0.5 * spacing - walls.max_overlap() << " m (less than dx/4) of a solid wall: "
        << "the contact is too soft for this flow; raise 'sph/solid wall stiffness' (now "
        << walls.law().stiffness << " N/m; the automatic step follows it)";
    throw SimulationFailure(msg.str());
  }
} // namespace sluice
