// One SPH fluid advanced in time (see the header).

#include <sluice/core/mpi_extremum.h>
#include <sluice/sph/sph_density.h>
#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_solver.h>
#include <sluice/sph/sph_xsph.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// The cells of several ranks hold the pairs of smoothing lengths up to
    /// a quarter above the largest at the start (sph_exchange.h).
    double ghost_reach(const SphParticles &P, const SphSettings &settings)
    {
      double h_max = 0.;
      for (unsigned int a = 0; a < P.n_local; ++a)
        h_max = std::max(h_max, settings.smoothing_factor * std::cbrt(P.mass[a] / P.density[a]));
      return 1.25 * (WendlandC2Kernel::support + settings.skin_fraction) * h_max;
    }

    /// A record of SphSolver::stable_step_limit() (step, which bound, id, x,
    /// y, z, value) in words.
    std::string step_bound_text(const std::array<double, 7> &least)
    {
      const int which = static_cast<int>(least[1]);
      if (which == 3)
        return "the solid walls' contact bound 0.2 sqrt(m / k)";
      if (which < 0)
        return "no bound (no fluid particle)";
      const char *const bound[] = {"the speed bound 0.25 h / (c_s + |v|)",
                                   "the viscous bound 0.125 h^2 rho / mu",
                                   "the force bound 0.25 sqrt(h / |a|)"};
      const char *const value[] = {"|v| = ", "rho = ", "|a| = "};
      const char *const unit[]  = {" m/s", " kg/m^3", " m/s^2"};
      std::ostringstream text;
      text << std::setprecision(6) << bound[which] << " at fluid particle "
           << static_cast<std::uint64_t>(least[2]) << " at (" << least[3] << ", " << least[4]
           << ", " << least[5] << "), " << value[which] << least[6] << unit[which];
      return text.str();
    }
  } // namespace

  SphSolver::SphSolver(SphParticles particles, const PeriodicBox &box, const SphSettings &settings,
                       MPI_Comm communicator)
    : P(std::move(particles)), box_(box), settings(settings), communicator(communicator)
    , exchange(std::make_shared<SphExchange>(communicator, box, ghost_reach(P, settings), P))
  {
    exchange->keep_own(P);
    smoothing_lengths(P, settings.smoothing_factor);
    rebuild_pairs_if_needed();
    evaluate_rates();
  }

  void SphSolver::rebuild_pairs_if_needed(const SphExchange::Attachments &moving)
  {
    double h_max = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      h_max = std::max(h_max, P.smoothing[a]);
    if (exchange->active())
      h_max = dealii::Utilities::MPI::max(h_max, communicator);
    bool due = builds == 0;
    if (!due)
      {
        // A pair enters the support when the particles close in by the skin
        // (each moving half of it) or the larger support grows into it.
        double moved_2 = 0.;
        for (unsigned int a = 0; a < P.n_local; ++a)
          moved_2 = std::max(moved_2, norm_square(box_.minimum_image(P.position[a] -
                                                                     position_at_build[a])));
        if (exchange->active())
          moved_2 = dealii::Utilities::MPI::max(moved_2, communicator);
        due = 2. * std::sqrt(moved_2) + 2. * std::max(h_max - h_at_build, 0.) > skin;
      }
    if (!due)
      {
        exchange->refresh_motion(P);
        return;
      }
    if (exchange->active())
      {
        // A particle costs a step about its pairs' share of the pair passes
        // (listed at the last build, for the particles that have not moved
        // since) and its own.
        std::vector<unsigned int> cost(P.n_local, 1);
        if (pairs.offset.size() > P.n_local)
          for (unsigned int a = 0; a < P.n_local; ++a)
            cost[a] += pairs.offset[a + 1] - pairs.offset[a];
        exchange->fit(P, (WendlandC2Kernel::support + settings.skin_fraction) * h_max, cost);
      }
    rebuild_pairs(h_max, moving);
  }

  void SphSolver::rebuild_pairs(const double h_max, const SphExchange::Attachments &moving)
  {
    for (unsigned int a = 0; a < P.n_local; ++a)
      P.position[a] = box_.wrap(P.position[a]);
    // A coupled scene's forces stay with their particles over its fluid step.
    SphExchange::Attachments attached = moving;
    if (!external.empty())
      attached.vectors.push_back(&external);
    exchange->redistribute(P, attached);
    skin = settings.skin_fraction * h_max;
    pairs.build(P, box_, skin);
    position_at_build.assign(P.position.begin(), P.position.begin() + P.n_local);
    h_at_build = h_max;
    ++builds;
  }

  template <typename Kernel>
  void SphSolver::evaluate_rates_with()
  {
    // Summation density: h from the last step's density (one fixed-point
    // iteration a step), then the fluid particles' densities from it.
    if (settings.summation_density)
      {
        summation_density<Kernel>(P, pairs, box_);
        exchange->refresh_density(P);
      }
    const bool grad_h = !settings.fixed_smoothing_length;
    if (grad_h)
      smoothing_lengths(P, settings.smoothing_factor);
    // The continuity equation's sums need only velocities (a wall's is its
    // own, whatever the walls' update extrapolates), so they share Omega's pass.
    // Each pair's kernel derivatives, kept for the accelerations below.
    if (settings.summation_density)
      {
        correction_factors<Kernel>(P, pairs, box_, grad_h);
        pair_kernels<Kernel>(P, pairs, box_, kernels);
      }
    else
      correction_factors_and_density_rates<Kernel>(P, pairs, box_, kernels, grad_h);
    pressures(P, settings.forces.state);
    walls.update<Kernel>(P, pairs, box_, settings.forces.state, settings.forces.gravity);
    exchange->refresh_rates_inputs(P, walls.no_slip);
    if (!settings.summation_density && settings.diffusion.delta > 0.)
      add_density_diffusion<Kernel>(P, pairs, box_, settings.diffusion);
    accelerations<Kernel>(P, pairs, box_, settings.forces, walls.no_slip, kernels);
    settings.repulsive_walls.add_accelerations(P);
    settings.solid_walls.add_accelerations(P);
  }

  void SphSolver::evaluate_rates()
  {
    if (settings.kernel == SphKernel::wendland_c2)
      evaluate_rates_with<WendlandC2Kernel>();
    else
      evaluate_rates_with<CubicSplineKernel>();
  }

  void SphSolver::step(const double dt)
  {
    if (settings.kernel == SphKernel::wendland_c2)
      step_with<WendlandC2Kernel>(dt);
    else
      step_with<CubicSplineKernel>(dt);
  }

  template <typename Kernel>
  void SphSolver::step_with(const double dt)
  {
    if (settings.integrator == SphIntegrator::predictor_corrector)
      {
        predictor_corrector_step_with<Kernel>(dt);
        return;
      }
    const double       h = 0.5 * dt;
    const unsigned int n = P.n_local;
    std::vector<Vec3>   half_velocity(P.velocity.begin(), P.velocity.begin() + n);
    std::vector<double> half_density(n);
    for (unsigned int a = 0; a < n; ++a)
      if (!P.wall[a])
        {
          half_velocity[a] += h * total_acceleration(a);
          half_density[a] = P.density[a] + h * P.density_rate[a];
        }
    // XSPH drifts with v_1/2 plus its correction; without it, with v_1/2 itself.
    std::vector<Vec3> correction;
    if (settings.xsph > 0.)
      {
        exchange->extend(P, half_velocity);
        xsph_corrections<Kernel>(P, pairs, box_, settings.xsph, half_velocity, correction);
        half_velocity.resize(n);
      }
    for (unsigned int a = 0; a < n; ++a)
      {
        if (P.wall[a])
          continue;
        const Vec3 drift = correction.empty() ? half_velocity[a] : half_velocity[a] + correction[a];
        P.position[a] += dt * drift;
        // The predicted state the new rates are taken at.
        P.velocity[a] = half_velocity[a] + h * total_acceleration(a);
        if (!settings.summation_density)
          P.density[a] = half_density[a] + h * P.density_rate[a];
      }
    rebuild_pairs_if_needed({{&half_velocity}, {&half_density}});
    evaluate_rates_with<Kernel>();
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        if (P.wall[a])
          continue;
        P.velocity[a] = half_velocity[a] + h * total_acceleration(a);
        if (!settings.summation_density)
          P.density[a] = half_density[a] + h * P.density_rate[a];
      }
  }

  template <typename Kernel>
  void SphSolver::predictor_corrector_step_with(const double dt)
  {
    const unsigned int  n = P.n_local;
    std::vector<Vec3>   x0(P.position.begin(), P.position.begin() + n);
    std::vector<Vec3>   v0(P.velocity.begin(), P.velocity.begin() + n);
    std::vector<double> rho0(P.density.begin(), P.density.begin() + n);
    // Predictor: half a step with the rates at the start.
    advance_from<Kernel>(x0, v0, rho0, v0, 0.5 * dt, 0.5 * dt);
    rebuild_pairs_if_needed({{&x0, &v0}, {&rho0}});
    evaluate_rates_with<Kernel>();
    // Corrector: the whole step with the half step's rates; x with v_1/2.
    std::vector<Vec3> half_velocity(v0);
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        half_velocity[a] += 0.5 * dt * total_acceleration(a);
    advance_from<Kernel>(x0, v0, rho0, half_velocity, dt, dt);
    rebuild_pairs_if_needed();
    evaluate_rates_with<Kernel>();
  }

  template <typename Kernel>
  void SphSolver::advance_from(const std::vector<Vec3> &x0, const std::vector<Vec3> &v0,
                               const std::vector<double> &rho0, const std::vector<Vec3> &u,
                               const double dx_dt, const double dv_dt)
  {
    std::vector<Vec3> correction;
    if (settings.xsph > 0. && exchange->active())
      {
        std::vector<Vec3> u_with_ghosts(u);
        exchange->extend(P, u_with_ghosts);
        xsph_corrections<Kernel>(P, pairs, box_, settings.xsph, u_with_ghosts, correction);
      }
    else if (settings.xsph > 0.)
      xsph_corrections<Kernel>(P, pairs, box_, settings.xsph, u, correction);
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        if (P.wall[a])
          continue;
        const Vec3 drift = correction.empty() ? u[a] : u[a] + correction[a];
        P.position[a]    = x0[a] + dx_dt * drift;
        P.velocity[a]    = v0[a] + dv_dt * total_acceleration(a);
        if (!settings.summation_density)
          P.density[a] = rho0[a] + dv_dt * P.density_rate[a];
      }
  }

  void SphSolver::set_fluid_fractions(const std::vector<double> &eps, const bool at_rest)
  {
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        {
          if (at_rest)
            {
              // The particle keeps its volume m / rho_hat and its pressure:
              // the fluid the solids displace is taken out with its mass.
              const double density = settings.forces.state.density(P.pressure[a], eps[a]);
              P.mass[a] *= density / P.density[a];
              P.density[a] = density;
            }
          P.porosity[a] = eps[a];
        }
    // The ghosts' porosity otherwise follows with the next drift's motion;
    // the masses change only here.
    if (at_rest)
      {
        exchange->refresh_fluid_fractions(P);
        evaluate_rates();
      }
  }

  void SphSolver::set_external_forces(std::vector<Vec3> forces)
  {
    external = std::move(forces);
  }

  void SphSolver::scale_velocities(const double factor)
  {
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        P.velocity[a] *= factor;
  }

  namespace
  {
    void write_particles(BinaryWriter &out, const SphParticles &Q)
    {
      out.write_vector(Q.id);
      for (const auto *v : {&Q.position, &Q.velocity, &Q.acceleration, &Q.wall_velocity})
        out.write_vector(*v);
      for (const auto *v : {&Q.mass, &Q.density, &Q.density_rate, &Q.smoothing, &Q.omega,
                            &Q.pressure, &Q.porosity})
        out.write_vector(*v);
      out.write_vector(Q.wall);
      out.write<std::uint64_t>(Q.n_local);
    }
  } // namespace

  void SphSolver::save(BinaryWriter &out) const
  {
    if (exchange->active())
      {
        // All ranks' particles by id, no pairs (an empty 'offset'): the
        // restored run builds them.
        std::vector<Vec3>  no_slip(walls.no_slip.begin(), walls.no_slip.begin() + P.n_local);
        const SphParticles all = exchange->gather_all(P, &no_slip);
        write_particles(out, all);
        out.write_vector(std::vector<unsigned int>());
        out.write_vector(std::vector<unsigned int>());
        out.write_vector(all.position);
        out.write(skin);
        out.write(h_at_build);
        out.write<std::uint64_t>(builds);
        // No external forces: a coupled scene deposits them again before its
        // next fluid step (and they are per owned particle, not by id).
        out.write_vector(std::vector<Vec3>());
        out.write_vector(no_slip);
        out.write_vector(exchange->cells());
        return;
      }
    write_particles(out, P);
    out.write_vector(pairs.offset);
    out.write_vector(pairs.partner);
    out.write_vector(position_at_build);
    out.write(skin);
    out.write(h_at_build);
    out.write<std::uint64_t>(builds);
    out.write_vector(external);
    out.write_vector(walls.no_slip);
    out.write_vector(std::vector<std::int64_t>());
  }

  void SphSolver::load(BinaryReader &in)
  {
    SphParticles Q;
    Q.id = in.read_vector<std::uint64_t>();
    for (auto *v : {&Q.position, &Q.velocity, &Q.acceleration, &Q.wall_velocity})
      *v = in.read_vector<Vec3>();
    for (auto *v : {&Q.mass, &Q.density, &Q.density_rate, &Q.smoothing, &Q.omega, &Q.pressure,
                    &Q.porosity})
      *v = in.read_vector<double>();
    Q.wall    = in.read_vector<unsigned char>();
    Q.n_local = in.read<std::uint64_t>();
    SphPairs restored;
    restored.offset  = in.read_vector<unsigned int>();
    restored.partner = in.read_vector<unsigned int>();
    std::vector<Vec3> at_build = in.read_vector<Vec3>();
    const double      s        = in.read<double>();
    const double      h        = in.read<double>();
    const auto        n_builds = in.read<std::uint64_t>();
    std::vector<Vec3> forces   = in.read_vector<Vec3>();
    std::vector<Vec3> no_slip  = in.read_vector<Vec3>();
    // The cells and their owners, written on several ranks.
    const auto        cells    = in.read_vector<std::int64_t>();
    const std::size_t n        = Q.id.size();
    // No pairs (an empty 'offset'): written on several ranks.
    const bool        with_pairs = !restored.offset.empty();
    bool              sizes_ok   = Q.n_local == n && at_build.size() == n &&
                    (!with_pairs || restored.offset.size() == n + 1) && Q.wall.size() == n;
    for (const auto *v : {&Q.position, &Q.velocity, &Q.acceleration, &Q.wall_velocity})
      sizes_ok = sizes_ok && v->size() == n;
    for (const auto *v : {&Q.mass, &Q.density, &Q.density_rate, &Q.smoothing, &Q.omega,
                          &Q.pressure, &Q.porosity})
      sizes_ok = sizes_ok && v->size() == n;
    sizes_ok = sizes_ok && (forces.empty() || forces.size() == n) && no_slip.size() == n;
    for (const unsigned int b : restored.partner)
      sizes_ok = sizes_ok && b < n;
    if (!sizes_ok || (!restored.offset.empty() && restored.offset.back() != restored.partner.size()))
      throw BinaryFormatError("the SPH particles' arrays do not fit together");
    P          = std::move(Q);
    skin       = s;
    h_at_build = h;
    builds     = n_builds;
    external   = std::move(forces);
    if (with_pairs && !exchange->active())
      {
        pairs.offset      = std::move(restored.offset);
        pairs.partner     = std::move(restored.partner);
        position_at_build = std::move(at_build);
        walls.no_slip     = std::move(no_slip);
        return;
      }
    // Each rank takes the cells the run had (if written on several ranks),
    // keeps its particles and builds their pairs. The no-slip velocities are
    // taken again before the next step's accelerations read them.
    exchange->restore_cells(cells, P);
    exchange->keep_own(P);
    double h_max = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      h_max = std::max(h_max, P.smoothing[a]);
    if (exchange->active())
      h_max = dealii::Utilities::MPI::max(h_max, communicator);
    const double needed_reach = (WendlandC2Kernel::support + settings.skin_fraction) * h_max;
    if (needed_reach > exchange->reach())
      exchange->fit(P, needed_reach);
    rebuild_pairs(h_max, {});
    --builds; // the uninterrupted run built its pairs as often
    walls.no_slip.assign(P.velocity.begin(), P.velocity.end());
  }

  template <typename F>
  void SphSolver::for_each_step_bound(const F &f) const
  {
    const SphForceParameters &forces = settings.forces;
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        if (P.wall[a])
          continue;
        const double h     = P.smoothing[a];
        const double speed = norm(P.velocity[a]);
        f(0.25 * h / (forces.state.sound_speed + speed), 0, a, speed);
        if (forces.viscosity > 0.)
          f(0.125 * h * h * P.density[a] / forces.viscosity, 1, a, P.density[a]);
        const double acceleration = norm(total_acceleration(a));
        if (acceleration > 0.)
          f(0.25 * std::sqrt(h / acceleration), 2, a, acceleration);
      }
  }

  double SphSolver::stable_time_step() const
  {
    double dt = std::numeric_limits<double>::max();
    for_each_step_bound([&](const double bound, int, unsigned int, double) {
      dt = std::min(dt, bound);
    });
    if (!settings.solid_walls.empty())
      dt = std::min(dt, settings.solid_walls.stable_time_step(P));
    if (exchange->active())
      MPI_Allreduce(MPI_IN_PLACE, &dt, 1, MPI_DOUBLE, MPI_MIN, communicator);
    return dt;
  }

  std::string SphSolver::stable_step_limit() const
  {
    // The smallest bound as one record (step, which, id, x, y, z, value),
    // which the rank that holds it sends to all.
    std::array<double, 7> least{{std::numeric_limits<double>::max(), -1., 0., 0., 0., 0., 0.}};
    for_each_step_bound([&](const double bound, const int which, const unsigned int a,
                            const double value) {
      if (bound < least[0])
        least = {{bound, static_cast<double>(which), static_cast<double>(P.id[a]),
                  P.position[a].x, P.position[a].y, P.position[a].z, value}};
    });
    if (!settings.solid_walls.empty())
      {
        const double walls = settings.solid_walls.stable_time_step(P);
        if (walls < least[0])
          least = {{walls, 3., 0., 0., 0., 0., 0.}};
      }
    if (exchange->active())
      share_from(rank_of_least(least[0], communicator).rank, least.data(), least.size(),
                 communicator);
    return step_bound_text(least);
  }
} // namespace sluice
