// The momentum side of an SPH step (sph/sph_forces.h):
// - Tait's equation: P(eps rho_0) = 0 and density(pressure(rho)) = rho;
// - momentum: on a jittered periodic lattice with densities, h and
//   velocities all different, sum_a m_a (a_a - g) vanishes to round-off
//   (the pressure and viscous pair terms are antisymmetric);
// - the pressure gradient: a linear pressure P_0 + G . x on an open block
//   gives -G / rho at its centre to round-off (with Omega, as the continuity
//   equation's divergence: sum_b m_b r W' = -3 rho Omega);
// - Morris' viscosity: zero for a linear shear, and nu d2v/dy2 = 2 nu kappa
//   for v_x = kappa y^2 at the centre within 2% (the 0.01 h^2 of the
//   denominator and the lattice, at h = 1.5 dx);
// - Monaghan's signal-velocity viscosity tied to mu (sph_viscosity.h):
//   momentum and angular momentum kept to round-off on a jittered open block
//   with random velocities, a negative viscous power there (Morris' form
//   keeps momentum only: its torque is printed for contrast), no force in a rigid rotation (to round-off, 1e-9
//   of one pair's term; Morris' printed) or a linear shear, and nu d2v/dy2
//   of a parabola within 3% at h = 1.5 dx (the lattice sum of its continuum
//   constant: 0.9963 spline, 0.9783 Wendland);
// - Monaghan's artificial pressure: momentum still kept with particles in
//   tension; for one pair in tension the change of the force is
//   -m_b R f^4 W' d / r with R and f computed here from their definitions;
//   with every pressure positive it changes nothing, to the bit;
// - formulation set II (model A): on the jittered periodic lattice, with a
//   fluid fraction that varies from 0.4 to 0.95 across it, each particle's
//   acceleration less gravity is its fluid fraction times set I's, in both
//   viscous forms (the pair's stresses taken by each side at its own eps);
//   and momentum is then no longer kept among the SPH particles alone.

#include <sluice/sph/sph_density.h>
#include <sluice/sph/sph_forces.h>
#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_pairs.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double rho_0 = 1000., dx = 1e-3;

  SphParticles lattice(const unsigned int n, const double jitter)
  {
    std::mt19937                           random(5);
    std::uniform_real_distribution<double> u(-1., 1.);
    SphParticles                           P;
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int i = 0; i < n; ++i)
          P.push_back(P.size(),
                      dx * Vec3(i + 0.5 + jitter * u(random), j + 0.5 + jitter * u(random),
                                k + 0.5 + jitter * u(random)),
                      rho_0 * dx * dx * dx, rho_0, 1.5 * dx);
    P.n_local = P.size();
    return P;
  }

  /// A jittered lattice with random densities (1% about rho_0) and
  /// velocities (up to 1 m/s).
  SphParticles random_state_lattice(const unsigned int n, const unsigned int seed)
  {
    SphParticles                           P = lattice(n, 0.25);
    std::mt19937                           random(seed);
    std::uniform_real_distribution<double> u(-1., 1.);
    for (unsigned int a = 0; a < P.size(); ++a)
      {
        P.density[a]  = rho_0 * (1. + 0.01 * u(random));
        P.velocity[a] = Vec3(u(random), u(random), u(random));
      }
    return P;
  }

  SphForceParameters parameters()
  {
    SphForceParameters p;
    p.state.reference_density = rho_0;
    p.state.sound_speed       = 20.;
    p.viscosity               = 1e-3;
    p.gravity                 = Vec3(0., 0., -9.81);
    return p;
  }

  /// |sum_a m_a (a_a - g)| against sum_a m_a |a_a - g|: zero when the pair
  /// forces are equal and opposite.
  double momentum_imbalance(const SphParticles &P, const Vec3 &gravity)
  {
    Vec3   total;
    double scale = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        total += P.mass[a] * (P.acceleration[a] - gravity);
        scale += P.mass[a] * norm(P.acceleration[a] - gravity);
      }
    return norm(total) / scale;
  }

  void check_state_equation()
  {
    const TaitEquation s = parameters().state;
    check(s.pressure(0.7 * rho_0, 0.7) == 0., "Tait: zero at eps rho_0", s.pressure(700., 0.7), 0.);
    const double rho = 1003.7;
    check(std::abs(s.density(s.pressure(rho, 1.), 1.) - rho) < 1e-12 * rho,
          "Tait: density(pressure(rho)) = rho", s.density(s.pressure(rho, 1.), 1.), rho);
  }

  /// random_state_lattice() of 8^3 in a periodic box, with its pairs, h
  /// and Omega.
  struct PeriodicBlock
  {
    SphParticles P;
    PeriodicBox  box;
    SphPairs     pairs;
  };

  template <typename Kernel>
  PeriodicBlock periodic_block(const unsigned int seed)
  {
    const unsigned int n = 8;
    PeriodicBlock      b{random_state_lattice(n, seed),
                         PeriodicBox(Vec3(), n * dx * Vec3(1., 1., 1.), {{true, true, true}}),
                         {}};
    smoothing_lengths(b.P, 1.5);
    b.pairs.build(b.P, b.box, 0.);
    correction_factors<Kernel>(b.P, b.pairs, b.box);
    return b;
  }

  template <typename Kernel>
  void check_momentum()
  {
    auto [P, box, pairs]       = periodic_block<Kernel>(9);
    const SphForceParameters p = parameters();
    pressures(P, p.state);
    accelerations<Kernel>(P, pairs, box, p, P.velocity);
    const double unbalanced = momentum_imbalance(P, p.gravity);
    std::printf("%s: momentum sum %.2e of the forces\n", Kernel::name, unbalanced);
    check(unbalanced < 1e-14, (std::string(Kernel::name) + ": momentum kept").c_str(), unbalanced,
          0.);
  }

  /// No viscous force in a linear shear, and nu d2v/dy2 = 2 nu kappa for
  /// v_x = kappa y^2 at the centre c of a regular block, within 'bound'.
  template <typename Kernel>
  void check_viscous_profiles(SphParticles &P, const SphPairs &pairs, const PeriodicBox &box,
                              const unsigned int c, SphForceParameters p,
                              const SphViscosityForm form, const double bound)
  {
    p.viscosity_form       = form;
    const std::string name = std::string(Kernel::name) +
                             (form == SphViscosityForm::morris ? ", Morris" : ", signal velocity");
    for (unsigned int a = 0; a < P.size(); ++a)
      P.velocity[a] = Vec3(3. * P.position[a].y, 0., 0.);
    accelerations<Kernel>(P, pairs, box, p, P.velocity);
    check(norm(P.acceleration[c]) < 1e-12, (name + ": no viscous force in a shear").c_str(),
          norm(P.acceleration[c]), 0.);
    const double kappa = 400.; // [1/(m s)]
    for (unsigned int a = 0; a < P.size(); ++a)
      P.velocity[a] = Vec3(kappa * P.position[a].y * P.position[a].y, 0., 0.);
    accelerations<Kernel>(P, pairs, box, p, P.velocity);
    const double laplacian = 2. * kappa * p.viscosity / P.density[c];
    std::printf("%s: viscous acceleration %.6g, nu d2v/dy2 %.6g (ratio %.4f)\n", name.c_str(),
                P.acceleration[c].x, laplacian, P.acceleration[c].x / laplacian);
    check(std::abs(P.acceleration[c].x / laplacian - 1.) < bound,
          (name + ": viscous force of a parabola").c_str(), P.acceleration[c].x, laplacian);
  }

  template <typename Kernel>
  void check_gradients()
  {
    const std::string  name = Kernel::name;
    const unsigned int n    = 15;
    SphParticles       P    = lattice(n, 0.);
    const PeriodicBox  box(Vec3(-dx, -dx, -dx), (n + 1) * dx * Vec3(1., 1., 1.),
                           {{false, false, false}});
    SphPairs           pairs;
    pairs.build(P, box, 0.);
    summation_density<Kernel>(P, pairs, box);
    correction_factors<Kernel>(P, pairs, box);
    SphForceParameters p = parameters();
    p.gravity            = Vec3();
    p.viscosity          = 0.;
    const Vec3 G(2e3, -5e2, 1e3); // [Pa/m]
    for (unsigned int a = 0; a < P.size(); ++a)
      P.pressure[a] = 1e4 + dot(G, P.position[a]);
    accelerations<Kernel>(P, pairs, box, p, P.velocity);
    const unsigned int c     = (n / 2) * (1 + n + n * n);
    const Vec3         exact = (-1. / P.density[c]) * G;
    std::printf("%s: pressure gradient (%.9g, %.9g, %.9g), exact (%.9g, %.9g, %.9g)\n",
                Kernel::name, P.acceleration[c].x, P.acceleration[c].y, P.acceleration[c].z,
                exact.x, exact.y, exact.z);
    check(norm(P.acceleration[c] - exact) < 1e-10 * norm(exact),
          (name + ": a linear pressure's gradient").c_str(), norm(P.acceleration[c] - exact), 0.);

    // The viscous forms on a shear and on a parabola.
    p.viscosity = 1e-3;
    for (unsigned int a = 0; a < P.size(); ++a)
      P.pressure[a] = 0.;
    check_viscous_profiles<Kernel>(P, pairs, box, c, p, SphViscosityForm::morris, 0.02);
    check_viscous_profiles<Kernel>(P, pairs, box, c, p, SphViscosityForm::signal_velocity, 0.03);
  }

  /// |sum_a m_a x_a x (a_a - g)| against sum_a m_a |x_a| |a_a - g|.
  double torque_imbalance(const SphParticles &P, const Vec3 &gravity)
  {
    Vec3   total;
    double scale = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        total += P.mass[a] * cross(P.position[a], P.acceleration[a] - gravity);
        scale += P.mass[a] * norm(P.position[a]) * norm(P.acceleration[a] - gravity);
      }
    return norm(total) / scale;
  }

  template <typename Kernel>
  void check_signal_velocity_viscosity()
  {
    const std::string name = Kernel::name;
    // An open jittered block with random velocities and densities.
    const unsigned int n = 8;
    SphParticles       P = random_state_lattice(n, 11);
    const PeriodicBox open(-dx * Vec3(1., 1., 1.), (n + 1) * dx * Vec3(1., 1., 1.),
                           {{false, false, false}});
    smoothing_lengths(P, 1.5);
    SphPairs pairs;
    pairs.build(P, open, 0.);
    correction_factors<Kernel>(P, pairs, open);
    SphForceParameters p = parameters();
    pressures(P, p.state);
    p.viscosity_form = SphViscosityForm::morris;
    accelerations<Kernel>(P, pairs, open, p, P.velocity);
    const double morris_torque = torque_imbalance(P, p.gravity);
    p.viscosity_form = SphViscosityForm::signal_velocity;
    accelerations<Kernel>(P, pairs, open, p, P.velocity);
    const double unbalanced = momentum_imbalance(P, p.gravity);
    const double torque     = torque_imbalance(P, p.gravity);
    std::printf("%s: signal velocity: momentum %.2e, angular momentum %.2e (Morris' %.2e)\n",
                Kernel::name, unbalanced, torque, morris_torque);
    check(unbalanced < 1e-14, (name + ": signal velocity keeps momentum").c_str(), unbalanced,
          0.);
    check(torque < 1e-14, (name + ": signal velocity keeps angular momentum").c_str(), torque,
          0.);

    // With the pressures off: the viscous forces only take kinetic energy
    // out, sum_a m_a a_a . v_a <= 0 (each pair's power is C W' w^2, W' <= 0);
    // and a rigid rotation feels nothing (a linear shear:
    // check_viscous_profiles).
    p.gravity = Vec3();
    for (unsigned int a = 0; a < P.size(); ++a)
      P.pressure[a] = 0.;
    accelerations<Kernel>(P, pairs, open, p, P.velocity);
    double power = 0., power_scale = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        power += P.mass[a] * dot(P.acceleration[a], P.velocity[a]);
        power_scale += P.mass[a] * norm(P.acceleration[a]) * norm(P.velocity[a]);
      }
    std::printf("%s: signal velocity: viscous power %.3g of sum m |a| |v|\n", Kernel::name,
                power / power_scale);
    check(power < 0., (name + ": signal velocity only dissipates").c_str(), power / power_scale,
          0.);
    const Vec3 omega(30., -20., 50.); // [1/s]
    for (unsigned int a = 0; a < P.size(); ++a)
      P.velocity[a] = cross(omega, P.position[a]);
    const auto accelerations_without_pressure = [&](const SphViscosityForm form) {
      p.viscosity_form = form;
      for (unsigned int a = 0; a < P.n_local; ++a)
        P.acceleration[a] = Vec3();
      accelerations<Kernel>(P, pairs, open, p, P.velocity);
      double largest = 0.;
      for (unsigned int a = 0; a < P.n_local; ++a)
        largest = std::max(largest, norm(P.acceleration[a]));
      return largest;
    };
    // The scale: one pair's term, mu |omega| dx / (rho^2 h^4) m.
    const double scale = p.viscosity * norm(omega) * dx * rho_0 * dx * dx * dx /
                         (rho_0 * rho_0 * std::pow(1.5 * dx, 4));
    // (Round-off: the velocities are up to 10 |omega| dx, the pairs about 100.)
    const double morris   = accelerations_without_pressure(SphViscosityForm::morris);
    const double rotation = accelerations_without_pressure(SphViscosityForm::signal_velocity);
    check(rotation < 1e-9 * scale, (name + ": no viscous force in a rigid rotation").c_str(),
          rotation, 0.);
    std::printf("%s: rigid rotation: largest %.2e against a pair's %.2e (Morris' %.2e)\n",
                Kernel::name, rotation, scale, morris);
  }
} // namespace

namespace
{
  template <typename Kernel>
  void check_artificial_pressure()
  {
    const std::string name = Kernel::name;
    // Momentum, with densities below rho_0: every pressure negative.
    const unsigned int n = 8;
    SphParticles       P = lattice(n, 0.25);
    std::mt19937       random(4);
    std::uniform_real_distribution<double> u(-1., 1.);
    for (unsigned int a = 0; a < P.size(); ++a)
      P.density[a] = rho_0 * (0.99 + 0.005 * u(random));
    const PeriodicBox box(Vec3(), n * dx * Vec3(1., 1., 1.), {{true, true, true}});
    smoothing_lengths(P, 1.5);
    SphPairs pairs;
    pairs.build(P, box, 0.);
    correction_factors<Kernel>(P, pairs, box);
    SphForceParameters p = parameters();
    p.artificial_pressure = 0.2;
    pressures(P, p.state);
    accelerations<Kernel>(P, pairs, box, p, P.velocity);
    const double unbalanced = momentum_imbalance(P, p.gravity);
    check(P.pressure[0] < 0. && unbalanced < 1e-14, (name + ": momentum kept in tension").c_str(),
          unbalanced, 0.);

    // One pair in tension, in an open box.
    SphParticles Q;
    Q.push_back(0, Vec3(0., 0., 0.), rho_0 * dx * dx * dx, 995., 1.5 * dx);
    Q.push_back(1, Vec3(0.6 * dx, 0.5 * dx, 0.), rho_0 * dx * dx * dx, 998., 1.6 * dx);
    Q.n_local = 2;
    const PeriodicBox open(-5. * dx * Vec3(1., 1., 1.), 5. * dx * Vec3(1., 1., 1.),
                           {{false, false, false}});
    SphPairs          pair;
    pair.build(Q, open, 0.);
    correction_factors<Kernel>(Q, pair, open);
    pressures(Q, p.state);
    p.gravity   = Vec3();
    p.viscosity = 0.;
    accelerations<Kernel>(Q, pair, open, p, Q.velocity);
    const Vec3 with = Q.acceleration[0];
    p.artificial_pressure = 0.;
    accelerations<Kernel>(Q, pair, open, p, Q.velocity);
    const Vec3   d = Q.position[0] - Q.position[1];
    const double r = norm(d), h = 0.5 * (1.5 + 1.6) * dx;
    const double R = 0.2 * (-Q.pressure[0] / (995. * 995.) - Q.pressure[1] / (998. * 998.));
    const double f = kernel_value<Kernel>(r, h) / kernel_value<Kernel>(h / 1.5, h);
    const Vec3   expected =
      (-Q.mass[1] * R * std::pow(f, 4) * kernel_radial_derivative<Kernel>(r, h) / r) * d;
    std::printf("%s: artificial pressure on a pair %.9g, expected %.9g\n", Kernel::name,
                (with - Q.acceleration[0]).x, expected.x);
    check(norm(with - Q.acceleration[0] - expected) < 1e-9 * norm(expected) &&
            dot(expected, d) > 0.,
          (name + ": a pair in tension repels").c_str(), (with - Q.acceleration[0]).x,
          expected.x);

    // Positive pressures: no change at all.
    for (unsigned int a = 0; a < P.size(); ++a)
      P.density[a] = rho_0 * (1.01 + 0.005 * u(random));
    pressures(P, p.state);
    p = parameters();
    accelerations<Kernel>(P, pairs, box, p, P.velocity);
    const std::vector<Vec3> without = P.acceleration;
    p.artificial_pressure = 0.2;
    accelerations<Kernel>(P, pairs, box, p, P.velocity);
    bool same = true;
    for (unsigned int a = 0; a < P.n_local; ++a)
      same = same && P.acceleration[a].x == without[a].x && P.acceleration[a].y == without[a].y &&
             P.acceleration[a].z == without[a].z;
    check(same, (name + ": no change under compression").c_str(), same, 1.);
  }

  /// Set II: a_a - g = eps_a (a_a - g of set I) for every particle a.
  template <typename Kernel>
  void check_model_a()
  {
    auto [P, box, pairs] = periodic_block<Kernel>(13);
    const double L       = box.length.x;
    SphForceParameters p = parameters();
    pressures(P, p.state); // (at eps = 1: pressures of 1% compressions)
    for (unsigned int a = 0; a < P.size(); ++a)
      P.porosity[a] = 0.4 + 0.55 * P.position[a].x / L;
    for (const auto form : {SphViscosityForm::morris, SphViscosityForm::signal_velocity})
      {
        p.viscosity_form              = form;
        p.stress_times_fluid_fraction = false;
        accelerations<Kernel>(P, pairs, box, p, P.velocity);
        const std::vector<Vec3> set_i = P.acceleration;
        p.stress_times_fluid_fraction = true;
        accelerations<Kernel>(P, pairs, box, p, P.velocity);
        double largest = 0., off = 0.;
        for (unsigned int a = 0; a < P.n_local; ++a)
          {
            const Vec3 expected = P.porosity[a] * (set_i[a] - p.gravity);
            largest             = std::max(largest, norm(set_i[a] - p.gravity));
            off = std::max(off, norm(P.acceleration[a] - p.gravity - expected));
          }
        const std::string name = std::string(Kernel::name) + ", " +
                                 (form == SphViscosityForm::morris ? "Morris" : "signal velocity");
        std::printf("%s: set II against eps times set I: %.2e of the largest acceleration; "
                    "momentum sum %.2e\n",
                    name.c_str(), off / largest, momentum_imbalance(P, p.gravity));
        check(off < 1e-13 * largest, (name + ": set II is eps times set I").c_str(),
              off / largest, 0.);
        check(momentum_imbalance(P, p.gravity) > 1e-3,
              (name + ": set II exchanges momentum with the grains").c_str(),
              momentum_imbalance(P, p.gravity), 1e-3);
      }
  }
} // namespace

int main()
{
  check_state_equation();
  check_momentum<CubicSplineKernel>();
  check_momentum<WendlandC2Kernel>();
  check_gradients<CubicSplineKernel>();
  check_gradients<WendlandC2Kernel>();
  check_signal_velocity_viscosity<CubicSplineKernel>();
  check_signal_velocity_viscosity<WendlandC2Kernel>();
  check_artificial_pressure<CubicSplineKernel>();
  check_artificial_pressure<WendlandC2Kernel>();
  check_model_a<CubicSplineKernel>();
  check_model_a<WendlandC2Kernel>();
  if (sluice::unit::failures == 0)
    std::printf("sph forces: all checks passed\n");
  return sluice::unit::failures == 0 ? 0 : 1;
}
