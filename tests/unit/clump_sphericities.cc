// The sphericities Hoelzer & Sommerfeld's drag takes (dem/clump_sphericities.h):
// - one sphere: all three are 1 from any side;
// - a dimer of touching spheres (closed forms, d_v = 2 R 2^(1/3), S = 8 pi R^2):
//   phi = 2^(2/3) / 2; along its axis phi_perp = 2^(2/3) (the shadow is one
//   disk) and phi_par = 2^(2/3) / 2 (seen across, always two disks); across
//   its axis phi_perp = 2^(2/3) / 2 and phi_par from the mean of the shadows
//   2 pi R^2 - lens(2 R sin a) over the directions across the flow,
//   integrated here by 20,000 midpoints (the code uses 32);
// - a rod of three seen end-on (its members' disks twins to round-off, the
//   body frame off the axis by 1e-21 m): phi_perp = (d_v / 2R)^2;
// - the table against the direct values over 2000 random directions, for a
//   tetrahedron and a rod of three (crosswise: computed, so to round-off;
//   lengthwise: interpolated), and n against -n.

#include <sluice/dem/clump_sphericities.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace sluice;
using sluice::unit::check;

namespace
{
  double relative(const double a, const double b) { return std::abs(a - b) / std::abs(b); }

  void check_sphere()
  {
    const ClumpTemplate t = make_clump_template("one", {Vec3(0.1, 0, 0)}, {0.5});
    for (const Vec3 n : {Vec3(0, 0, 1), Vec3(1, 2, 3), Vec3(-1, 0, 0.2)})
      {
        const Sphericities s = clump_sphericities(t, n);
        check(std::abs(s.sphericity - 1.) < 1e-9 && std::abs(s.crosswise - 1.) < 1e-10 &&
                std::abs(s.lengthwise - 1.) < 1e-9,
              "one sphere: all sphericities 1", s.lengthwise, 1.);
      }
  }

  void check_dimer()
  {
    const double        R = 1.;
    const ClumpTemplate t = rod_clump(2, R, 0.); // along the body frame's first axis
    const double        c = std::cbrt(4.);       // 2^(2/3)
    const Vec3          axis(1, 0, 0);
    const Sphericities  along  = clump_sphericities(t, axis);
    const Sphericities  across = clump_sphericities(t, Vec3(0, 1, 0));
    check(relative(along.sphericity, 0.5 * c) < 1e-8, "dimer: sphericity", along.sphericity,
          0.5 * c);
    check(relative(along.crosswise, c) < 1e-10, "dimer: crosswise along the axis", along.crosswise,
          c);
    check(relative(along.lengthwise, 0.5 * c) < 1e-8, "dimer: lengthwise along the axis",
          along.lengthwise, 0.5 * c);
    check(relative(across.crosswise, 0.5 * c) < 1e-10, "dimer: crosswise across the axis",
          across.crosswise, 0.5 * c);
    // Across (flow along y): the views across it make angles a in [0, pi)
    // with the axis; two disks 2 R |sin a| apart.
    const auto lens = [&](const double d) {
      return d >= 2. * R ? 0. : 2. * R * R * std::acos(d / (2. * R)) - 0.5 * d * std::sqrt(4. * R * R - d * d);
    };
    const unsigned int n    = 20000;
    double             mean = 0.;
    for (unsigned int k = 0; k < n; ++k)
      mean += (2. * M_PI * R * R - lens(2. * R * std::abs(std::sin(M_PI * (k + 0.5) / n)))) / n;
    const double exact = M_PI * R * R * c / (4. * M_PI * R * R - mean);
    std::printf("dimer across its axis: lengthwise sphericity %.8f (32 directions), %.8f "
                "(20,000)\n", across.lengthwise, exact);
    check(relative(across.lengthwise, exact) < 3e-4, "dimer: lengthwise across the axis",
          across.lengthwise, exact);
  }

  void check_rod_end_on()
  {
    const double        R = 0.4;
    const ClumpTemplate t = rod_clump(3, R, 0.2);
    const double        d_v = t.volume_equivalent_diameter(), exact = d_v * d_v / (4. * R * R);
    for (const double tilt : {0., 1e-17, 1e-14})
      check(relative(clump_sphericities(t, Vec3(1., tilt, 0.)).crosswise, exact) < 1e-12,
            "rod end-on: crosswise", clump_sphericities(t, Vec3(1., tilt, 0.)).crosswise, exact);
  }

  void check_table(const ClumpTemplate &t, const char *name, const double bound)
  {
    const SphericityTable           table(t);
    std::mt19937                    random(7);
    std::normal_distribution<double> normal;
    double worst_cross = 0., worst_length = 0., worst_flip = 0.;
    for (unsigned int k = 0; k < 2000; ++k)
      {
        const Vec3         n(normal(random), normal(random), normal(random));
        const Sphericities exact = clump_sphericities(t, n), table_value = table(n);
        worst_cross  = std::max(worst_cross, relative(table_value.crosswise, exact.crosswise));
        worst_length = std::max(worst_length, relative(table_value.lengthwise, exact.lengthwise));
        worst_flip   = std::max(worst_flip, relative(table(-1. * n).crosswise, table_value.crosswise));
      }
    std::printf("%s: table against direct, largest relative error crosswise %.2e, lengthwise "
                "%.2e\n", name, worst_cross, worst_length);
    check(worst_cross < 1e-14, (std::string(name) + ": table crosswise").c_str(), worst_cross,
          0.);
    check(worst_length < bound, (std::string(name) + ": table lengthwise").c_str(), worst_length,
          bound);
    check(worst_flip < 1e-12, (std::string(name) + ": n and -n").c_str(), worst_flip, 0.);
  }
} // namespace

int main()
{
  check_sphere();
  check_dimer();
  check_rod_end_on();
  check_table(tetrahedron_clump(1., 0.25), "tetrahedron", 3e-3);
  check_table(rod_clump(3, 1., 0.2), "rod of three", 3e-3);
  if (sluice::unit::failures == 0)
    std::printf("clump sphericities: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
