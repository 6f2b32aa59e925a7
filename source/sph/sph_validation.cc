// What an SPH scene's validation case measures (see the header).

#include <sluice/sph/sph_validation.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sluice
{
  SphResult hydrostatic_result(const SphParticles &P, const SceneParameters &p,
                               const SphSetup &setup, const double mean_density_start,
                               const double mean_density_end, const double max_speed_end)
  {
    const double g = norm(p.gravity), dx = p.sph.spacing;
    const Vec3   down = (1. / g) * p.gravity;
    // The bottom layer: the fluid particles whose depth is within dx/2 of the deepest.
    double deepest = -1e300;
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a] && a < setup.n_fluid)
        deepest = std::max(deepest, dot(down, P.position[a]));
    double       pressure = 0., depth = 0.;
    unsigned int n = 0;
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a] && dot(down, P.position[a]) > deepest - 0.5 * dx)
        pressure += P.pressure[a], depth += dot(down, P.position[a]), ++n;
    pressure /= n, depth /= n;
    // The surface: the top of the fluid block (its particles fill it to dx/2).
    double               surface = 1e300;
    const SphParameters &s       = p.sph;
    for (unsigned int c = 0; c < 8; ++c)
      surface = std::min(surface, dot(down, Vec3((c & 1 ? s.fluid_upper : s.fluid_lower).x,
                                                 (c & 2 ? s.fluid_upper : s.fluid_lower).y,
                                                 (c & 4 ? s.fluid_upper : s.fluid_lower).z)));
    SphResult r;
    r.name      = "sph_hydrostatic";
    r.value     = pressure;
    r.reference = s.density * g * (depth - surface);
    r.error     = std::abs(r.value - r.reference) / r.reference;
    std::ostringstream check;
    check.precision(p.summary_precision);
    check << "check: hydrostatic mean_density_drift=" << mean_density_end / mean_density_start - 1.
          << " max_speed_over_sqrt_gH=" << max_speed_end / std::sqrt(g * setup.column_height)
          << " bottom_layer_particles=" << n;
    // Lennard-Jones walls carry the column by their force alone: at rest it
    // equals the column's weight.
    const RepulsiveWalls &walls = setup.settings.repulsive_walls;
    if (!walls.empty())
      {
        double lift = 0., weight = 0.;
        for (unsigned int a = 0; a < P.n_local; ++a)
          if (!P.wall[a])
            {
              lift -= P.mass[a] * dot(down, walls.acceleration(P.position[a]));
              weight += P.mass[a] * g;
            }
        check << " wall_force_over_weight=" << lift / weight;
      }
    r.checks.push_back(check.str());
    return r;
  }

  double poiseuille_series(const double y, const double t, const double width, const double force,
                           const double nu)
  {
    const double pi = M_PI, scale = force * width * width / nu;
    double       v  = 0.5 * scale * (y / width) * (1. - y / width);
    for (unsigned int k = 1; k < 400001; k += 2)
      {
        const double amplitude = 4. / (pi * pi * pi * k * k * k) *
                                 std::exp(-double(k) * k * pi * pi * nu * t / (width * width));
        v -= scale * amplitude * std::sin(k * pi * y / width);
        if (amplitude < 1e-16)
          break;
      }
    return v;
  }

  PoiseuilleProbe::PoiseuilleProbe(const SceneParameters &p, const double end_time)
    : dx(p.sph.spacing)
  {
    const auto fail = [&](const std::string &entry, const std::string &what) {
      throw InputError("error in '" + p.file_name + "': entry '" + entry + "' " + what +
                       " ('sph/validation' = poiseuille: a channel between two walls, doc/sph.md)");
    };
    const std::vector<std::string> &walls = p.sph.walls;
    if (walls.size() != 2 || walls[0][0] != walls[1][0] || walls[0][1] == walls[1][1])
      fail("sph/walls", "must name the two faces of one direction, e.g. 'y-, y+'");
    normal = walls[0][0] - 'x';
    for (unsigned int d = 0; d < 3; ++d)
      if (std::abs(p.sph.fluid_lower[d] - p.lower_corner[d]) > 1e-9 * dx ||
          std::abs(p.sph.fluid_upper[d] - p.upper_corner[d]) > 1e-9 * dx)
        fail("sph/fluid lower corner", "and 'fluid upper corner' must be the domain's corners");
    force = norm(p.gravity);
    if (!(force > 0.))
      fail("simulation/gravity", "is zero: it is the body force that drives the flow");
    flow = (1. / force) * p.gravity;
    for (unsigned int d = 0; d < 3; ++d)
      if (!p.periodic[d] && std::abs(flow[d]) > 1e-12)
        fail("simulation/gravity", "must lie along periodic directions, parallel to the walls");
    if (!(p.sph.viscosity > 0.))
      fail("sph/viscosity", "is zero");
    nu    = p.sph.viscosity / p.sph.density;
    lower = p.lower_corner[normal];
    width = p.upper_corner[normal] - lower;
    for (const double tau : {0.0225, 0.045, 0.1125})
      if (tau * width * width / nu < end_time)
        times.push_back(tau * width * width / nu);
    times.push_back(end_time);
  }

  void PoiseuilleProbe::measure_if_due(const SphParticles &P, const double time, const double dt)
  {
    if (!due(time, dt))
      return;
    // The layers the particles started in: their y within [j dx, (j+1) dx).
    const unsigned int  n_layers = std::max(1, static_cast<int>(std::lround(width / dx)));
    std::vector<double> sum_y(n_layers, 0.), sum_v(n_layers, 0.);
    std::vector<unsigned int> count(n_layers, 0);
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        {
          const double y = P.position[a][normal] - lower;
          const auto   j = std::min<long>(n_layers - 1, std::max(0L, std::lround(y / dx - 0.5)));
          sum_y[j] += y, sum_v[j] += dot(flow, P.velocity[a]), ++count[j];
        }
    double deviation = 0., centre = 0., centre_series = 0.;
    for (unsigned int j = 0; j < n_layers; ++j)
      if (count[j] > 0)
        {
          const double y = sum_y[j] / count[j], v = sum_v[j] / count[j];
          const double series = poiseuille_series(y, time, width, force, nu);
          deviation = std::max(deviation, std::abs(v - series));
          if (j == n_layers / 2)
            centre = v, centre_series = series;
        }
    measured.push_back({time, deviation, centre, centre_series});
  }

  SphResult PoiseuilleProbe::result(const int precision) const
  {
    SphResult r;
    r.name      = "sph_poiseuille_startup";
    r.reference = force * width * width / (8. * nu);
    for (const std::vector<double> &m : measured)
      {
        r.value = std::max(r.value, m[1]);
        std::ostringstream check;
        check.precision(precision);
        check << "check: poiseuille t=" << m[0] << " nu_t_over_L2=" << nu * m[0] / (width * width)
              << " centre_velocity=" << m[2] << " series=" << m[3]
              << " max_layer_deviation_over_v0=" << m[1] / r.reference;
        r.checks.push_back(check.str());
      }
    r.error = r.value / r.reference;
    return r;
  }

  void PoiseuilleProbe::save(SceneRecords &records) const
  {
    for (const std::vector<double> &m : measured)
      {
        std::string line;
        for (const double v : m)
          line += (line.empty() ? "" : " ") + exact_text(v);
        records.add_all("poiseuille_profile", {line});
      }
  }

  void PoiseuilleProbe::restore(const SceneRecords &records)
  {
    measured.clear();
    for (const std::string &line : records.all("poiseuille_profile"))
      {
        std::istringstream  in(line);
        std::vector<double> m;
        for (double v; in >> v;)
          m.push_back(v);
        measured.push_back(m);
      }
  }
} // namespace sluice
