// The dam break of Martin & Moyce (1952) (see the header).

#include <sluice/sph/sph_dam_break.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sluice
{
  namespace
  {
    // Martin & Moyce (1952), Fig. 3, n^2 = 2, a = 2.25 in: (T, Z).
    const double martin_moyce[][2] = {
      {0.832, 1.217}, {1.219, 1.474}, {1.997, 2.292}, {2.547, 2.995}, {3.345, 4.134},
      {4.034, 4.944}, {4.418, 5.881}, {5.091, 6.980}, {5.685, 7.945}, {6.306, 8.966},
      {6.822, 9.986}, {7.439, 10.963}, {8.031, 11.977}, {8.633, 13.005}, {9.237, 13.970}};
  } // namespace

  DamBreakProbe::DamBreakProbe(const SceneParameters &p, const double end_time)
    : dx(p.sph.spacing)
  {
    const auto fail = [&](const std::string &entry, const std::string &what) {
      throw InputError("error in '" + p.file_name + "': entry '" + entry + "' " + what +
                       " ('sph/validation' = dam_break: Martin & Moyce's column, doc/sph.md)");
    };
    const std::vector<std::string> &walls = p.sph.walls;
    for (const std::string face : {"x-", "z-"})
      if (std::find(walls.begin(), walls.end(), face) == walls.end())
        fail("sph/walls", std::string("must include '") + face + "'");
    const double g = -p.gravity.z;
    if (!(g > 0.) || p.gravity.x != 0. || p.gravity.y != 0.)
      fail("simulation/gravity", "must point along -z");
    const SphParameters &s = p.sph;
    if (std::abs(s.fluid_lower.x - p.lower_corner.x) > 1e-9 * dx ||
        std::abs(s.fluid_lower.z - p.lower_corner.z) > 1e-9 * dx)
      fail("sph/fluid lower corner", "must lie on the x- wall and the z- floor");
    wall  = p.lower_corner.x;
    width = s.fluid_upper.x - s.fluid_lower.x;
    if (std::abs(s.fluid_upper.z - s.fluid_lower.z - 2. * width) > 1e-9 * width)
      fail("sph/fluid upper corner", "must make the column twice as high (z) as wide (x)");
    time_scale = std::sqrt(width / (2. * g));
    for (const auto &point : martin_moyce)
      if (point[0] * time_scale <= end_time * (1. + 1e-12))
        reference_T.push_back(point[0]), reference_Z.push_back(point[1]);
    if (reference_T.empty())
      fail("simulation/end time", "ends before the first measurement (T = 0.832)");
  }

  double DamBreakProbe::front(const SphParticles &P) const
  {
    double x = wall;
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        x = std::max(x, P.position[a].x);
    return (x + 0.5 * dx - wall) / width;
  }

  void DamBreakProbe::measure_if_due(const SphParticles &P, const double time, const double dt)
  {
    if (due(time, dt))
      measured_Z.push_back(front(P));
  }

  SphResult DamBreakProbe::result(const int precision) const
  {
    SphResult r;
    r.name = "sph_dam_break_front";
    for (std::size_t k = 0; k < measured_Z.size(); ++k)
      {
        const double error = std::abs(measured_Z[k] / reference_Z[k] - 1.);
        if (error >= r.error)
          r.error = error, r.value = measured_Z[k], r.reference = reference_Z[k];
        std::ostringstream check;
        check.precision(precision);
        check << "check: dam_break T=" << reference_T[k] << " t=" << reference_T[k] * time_scale
              << " Z=" << measured_Z[k] << " Z_martin_moyce=" << reference_Z[k]
              << " relative_error=" << measured_Z[k] / reference_Z[k] - 1.;
        r.checks.push_back(check.str());
      }
    return r;
  }

  void DamBreakProbe::save(SceneRecords &records) const
  {
    for (const double z : measured_Z)
      records.add_all("dam_break_front", {exact_text(z)});
  }

  void DamBreakProbe::restore(const SceneRecords &records)
  {
    measured_Z.clear();
    for (const std::string &line : records.all("dam_break_front"))
      measured_Z.push_back(std::stod(line));
  }
} // namespace sluice
