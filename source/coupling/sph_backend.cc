// The SPH fluid as a coupled scene's fluid (see the header).

#include <sluice/core/binary_io.h>
#include <sluice/core/mpi_extremum.h>
#include <sluice/core/output_files.h>
#include <sluice/core/scene_parameters.h>
#include <sluice/coupling/sph_backend.h>
#include <sluice/sph/sph_fluid_fields.h>
#include <sluice/sph/sph_health.h>
#include <sluice/sph/sph_kernel.h>
#include <sluice/sph/sph_output.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// Calls f with the kernel the settings name (a type, for the templates).
    template <typename F>
    void with_kernel(const SphSettings &s, F &&f)
    {
      if (s.kernel == SphKernel::wendland_c2)
        f(WendlandC2Kernel());
      else
        f(CubicSplineKernel());
    }

    /// Each entry summed over the ranks, on every rank (in place).
    template <typename Value>
    void sum_over_ranks(std::vector<Value> &values, MPI_Comm communicator)
    {
      static_assert(sizeof(Value) % sizeof(double) == 0, "doubles only");
      const dealii::ArrayView<double> numbers(reinterpret_cast<double *>(values.data()),
                                              values.size() * sizeof(Value) / sizeof(double));
      dealii::Utilities::MPI::sum(dealii::ArrayView<const double>(numbers), communicator,
                                  numbers);
    }
  } // namespace

  template <typename Check>
  void SphBackend::on_all_ranks(const Check &check) const
  {
    if (distributed)
      check_on_all_ranks(communicator, check);
    else
      check();
  }

  template <typename Value>
  std::vector<Value> SphBackend::shepard(const std::vector<Value> &field,
                                         const Value             &fallback) const
  {
    std::vector<Value> sums = pairs.weighted_sums(field);
    if (distributed)
      sum_over_ranks(sums, communicator);
    return pairs.normalised(std::move(sums), fallback);
  }

  SphBackend::SphBackend(SphSetup setup_, const SphBackendSettings &settings_,
                         std::unique_ptr<WallSet> walls_, const SolidWallLaw &law,
                         MPI_Comm communicator_)
    : setup(std::move(setup_)), settings(settings_), walls(std::move(walls_)), wall_law(law)
    , communicator(communicator_)
  {
    // Without MPI (a unit test), one rank.
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (initialized)
      {
        rank        = dealii::Utilities::MPI::this_mpi_process(communicator);
        distributed = dealii::Utilities::MPI::n_mpi_processes(communicator) > 1;
      }
    if (!(settings.coupling_length > 0.))
      throw InputError("the SPH coupling length must be positive");
    setup.settings.solid_walls =
      walls ? SphSolidWalls(*walls, wall_law, setup.box.lower, setup.box.upper) :
              SphSolidWalls();
    sph = std::make_unique<SphSolver>(setup.particles, setup.box, setup.settings, communicator);
    if (distributed)
      decomposition = sph->decomposition();
  }

  void SphBackend::describe(std::ostream &out) const
  {
    // (The coupling length is the scene's to say, with the exchange.)
    out << "SPH particles: " << setup.n_fluid << " fluid, " << setup.n_walls << " wall";
    if (walls)
      out << "; the DEM's walls hold it (" << walls->n_planes() << " planes, "
          << walls->n_meshes() << " meshes; k = " << wall_law.stiffness << " N/m, zeta = "
          << wall_law.damping_ratio << ", R = dx/2; " << setup.n_cut_by_walls
          << " lattice points beyond them left out)";
    if (distributed)
      out << "\n  SPH on several ranks: " << decomposition << "; every rank holds all grains"
          << " as solids";
  }

  void SphBackend::list_pairs()
  {
    with_kernel(setup.settings, [&](auto kernel) {
      pairs.build<decltype(kernel)>(sph->particles(), solids, sph->box(),
                                    settings.coupling_length);
    });
    if (distributed)
      sum_over_ranks(pairs.weight_sum, communicator);
    builds_at_listing = sph->n_pair_builds();
  }

  void SphBackend::summarise_layout(std::ostream &out) const
  {
    if (distributed)
      out << "  SPH on several ranks at the end: " << sph->decomposition()
          << "; shared out again " << sph->n_repartitions() << " time(s)\n";
  }

  unsigned long long SphBackend::receive(const std::vector<ExchangeParticle> &particles)
  {
    // Each particle as 7 numbers: centre, volume, reaction.
    std::vector<double> mine(7 * particles.size());
    for (std::size_t i = 0; i < particles.size(); ++i)
      {
        double *r = mine.data() + 7 * i;
        for (unsigned int d = 0; d < 3; ++d)
          r[d] = particles[i].position[d], r[4 + d] = particles[i].reaction_force[d];
        r[3] = particles[i].volume;
      }
    std::vector<std::vector<double>> blocks{std::move(mine)};
    if (distributed)
      blocks = dealii::Utilities::MPI::all_gather(communicator, blocks[0]);
    first_local = 0;
    for (unsigned int r = 0; r < rank && distributed; ++r)
      first_local += blocks[r].size() / 7;
    n_received = particles.size();

    solids.position.clear(), solids.volume.clear(), reactions.clear();
    for (const std::vector<double> &block : blocks)
      for (std::size_t k = 0; k < block.size(); k += 7)
        {
          solids.position.emplace_back(block[k], block[k + 1], block[k + 2]);
          solids.volume.push_back(block[k + 3]);
          reactions.emplace_back(block[k + 4], block[k + 5], block[k + 6]);
        }
    list_pairs();
    return pairs.n_unreached();
  }

  DepositReport SphBackend::deposit(const bool initial)
  {
    DepositReport       report;
    std::vector<double> eps;
    with_kernel(setup.settings, [&](auto kernel) {
      eps = pairs.fluid_fractions<decltype(kernel)>(sph->particles(), solids);
    });
    const double floor = 1. - settings.max_solid_fraction;
    for (unsigned int a = 0; a < sph->particles().n_local; ++a)
      if (eps[a] < floor)
        {
          eps[a] = floor;
          ++report.clipped_nodes;
        }
    sph->set_fluid_fractions(eps, initial);
    deposited = true;

    // The fluid receives each solid's reaction: spread the force on the
    // solid, -reaction, and the spread comes back as +reaction in sum.
    std::vector<Vec3> on_solids(reactions.size());
    for (std::size_t i = 0; i < reactions.size(); ++i)
      {
        on_solids[i] = -reactions[i];
        report.particle_force += reactions[i];
      }
    std::vector<Vec3> forces = pairs.spread(on_solids, sph->particles().n_local);
    pass_on_unreached(on_solids, forces);
    for (const Vec3 &f : forces)
      report.field_force += f;
    sph->set_external_forces(std::move(forces));
    if (distributed)
      {
        std::vector<Vec3> field{report.field_force};
        sum_over_ranks(field, communicator);
        report.field_force   = field[0];
        report.clipped_nodes = dealii::Utilities::MPI::sum(report.clipped_nodes, communicator);
      }
    return report;
  }

  void SphBackend::pass_on_unreached(const std::vector<Vec3> &on_solids,
                                     std::vector<Vec3>       &forces) const
  {
    // A solid the fluid reached when it was sampled may have left its reach
    // since (a grain thrown out of a slurry): the reaction it owes goes to the
    // fluid particle nearest to it (on any rank), so that no momentum is lost.
    const SphParticles &P = sph->particles();
    for (std::size_t i = 0; i < on_solids.size(); ++i)
      {
        if (pairs.weight_sum[i] > 0. || norm_square(on_solids[i]) == 0.)
          continue;
        unsigned int nearest = P.n_local;
        double       closest = std::numeric_limits<double>::infinity();
        for (unsigned int a = 0; a < P.n_local; ++a)
          {
            if (P.wall[a])
              continue;
            const double r2 = norm_square(sph->box().minimum_image(solids.position[i] -
                                                                  P.position[a]));
            if (r2 < closest)
              closest = r2, nearest = a;
          }
        // The nearest over the ranks; the lowest rank's among equals.
        const int nearest_rank =
          distributed ? rank_of_least(closest, communicator).rank : static_cast<int>(rank);
        if (nearest < P.n_local && nearest_rank == static_cast<int>(rank))
          forces[nearest] -= on_solids[i];
      }
  }

  void SphBackend::clear_momentum_source()
  {
    sph->set_external_forces({});
  }

  NewtonReport SphBackend::solve_steady()
  {
    // The fluid starts at the hydrostatic density of its depth, but a
    // lattice's kernel sums miss that balance by about 1% (unit.sph_backend):
    // left alone it would slosh at ~1e-4 m/s for seconds, the speed of a slow
    // grain. So it relaxes to rest first, with the time held and the grains
    // held where they are, each passing on the reaction to its pressure force,
    // V_i <grad P>_i (without it the fluid among grains has no hydrostatic
    // rest: rho_hat g is not a gradient where eps varies; in set II, whose
    // fluid has -eps grad p, rho g is, and the grains pass on nothing).
    // Damping: critical for the slowest acoustic mode, omega = pi c_s / (2 L),
    // L the fluid's largest extent (faster modes are overdamped and settle
    // sooner); until the largest speed is below 1e-8 c_s, or has not halved
    // over the last 5 / omega (what is left then is the lattice's slow creep,
    // which the damping does not shorten: about 1e-7 m/s from 15 / omega on
    // in the sedimentation scenes), for at most 60 / omega. Without
    // 'start_at_rest' whatever is left then is accepted (a lattice cut to a
    // curved shell rearranges for far longer: 3e-4 m/s after 600 / omega in a
    // drum).
    const double c_s    = setup.settings.forces.state.sound_speed;
    const Vec3   extent = setup.domain_upper - setup.domain_lower;
    const double L      = std::max({extent.x, extent.y, extent.z, setup.column_height});
    const double omega  = M_PI * c_s / (2. * L);
    double       compared_speed = std::numeric_limits<double>::infinity(), compared_at = 0.;
    NewtonReport r;
    for (double t = 0.; t < 60. / omega; ++r.iterations)
      {
        if (deposited && !setup.settings.forces.stress_times_fluid_fraction)
          hold_reactions();
        const double h = settings.step_fraction * sph->stable_time_step();
        sph->step(h);
        sph->scale_velocities(std::max(0., 1. - 2. * omega * h));
        t += h;
        r.residual = largest_speed();
        if (r.residual < 1e-8 * c_s)
          break;
        if (t - compared_at >= 5. / omega)
          {
            if (r.residual > 0.5 * compared_speed)
              break;
            compared_speed = r.residual;
            compared_at    = t;
          }
      }
    if (settings.start_at_rest)
      check_at_rest(r);
    sph->set_external_forces({});
    on_all_ranks([&]() {
      check_sph_health(sph->particles(), setup, time);
      if (walls)
        check_solid_wall_overlap(sph->solid_walls(), setup.spacing, time);
    });
    list_pairs();
    return r;
  }

  void SphBackend::check_at_rest(const NewtonReport &relaxation) const
  {
    // A fluid not at rest now (the scenes reach 3e-8 c_s) would carry its
    // motion into the run: a block that does not fit its domain, say.
    const double c_s = setup.settings.forces.state.sound_speed;
    if (!(relaxation.residual > 1e-5 * c_s))
      return;
    std::ostringstream m;
    m << std::setprecision(4) << "the SPH fluid did not come to rest at the start: its "
      << "largest speed is " << relaxation.residual << " m/s after " << relaxation.iterations
      << " SPH steps of damped relaxation, above 1e-5 c_s = " << 1e-5 * c_s
      << " m/s; check that 'sph/fluid lower corner', 'sph/fluid upper corner' and "
         "'sph/particle spacing' give a block that fits its domain and walls";
    throw SimulationFailure(m.str());
  }

  void SphBackend::hold_reactions()
  {
    // On several ranks a rebuild of the fluid's pairs moves particles between
    // ranks and renumbers them: the solids' pairs are listed again (on one
    // rank those of the relaxation's start are kept, their partners' numbers
    // unchanged).
    if (distributed && sph->n_pair_builds() != builds_at_listing)
      list_pairs();
    std::vector<Vec3> grad_p;
    with_kernel(setup.settings, [&](auto kernel) {
      grad_p = pressure_gradients<decltype(kernel)>(sph->particles(), sph->fluid_pairs(),
                                                    sph->box());
    });
    std::vector<Vec3> on_solids = shepard(grad_p, Vec3());
    for (std::size_t i = 0; i < on_solids.size(); ++i)
      {
        const double phi =
          settings.weight_by_immersion ? std::min(1., pairs.weight_sum[i]) : 1.;
        on_solids[i] = (-phi * solids.volume[i]) * on_solids[i];
      }
    sph->set_external_forces(pairs.spread(on_solids, sph->particles().n_local));
  }

  double SphBackend::largest_speed() const
  {
    const SphParticles &P       = sph->particles();
    double              largest = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        largest = std::max(largest, norm(P.velocity[a]));
    return distributed ? dealii::Utilities::MPI::max(largest, communicator) : largest;
  }

  NewtonReport SphBackend::advance(const double dt)
  {
    // Equal SPH steps that fill the fluid step, each at most the fraction of
    // the stable step at its start.
    const double       limit = settings.step_fraction * sph->stable_time_step();
    const unsigned int n     = std::max(1., std::ceil(dt / limit - 1e-9));
    const double       h     = dt / n;
    for (unsigned int k = 0; k < n; ++k)
      {
        const double stable = sph->stable_time_step();
        if (h > stable)
          {
            std::ostringstream m;
            m << std::setprecision(6) << "the SPH step " << h << " s exceeds the stable step "
              << stable << " s after " << sph_steps << " SPH steps, set by "
              << sph->stable_step_limit()
              << " (lower 'sph/time step fraction' or 'cfd-dem/fluid time step')";
            throw SimulationFailure(m.str());
          }
        // The walls from t to t + h, then the fluid, as the SPH scene does.
        if (walls)
          walls->move(time + k * h, h);
        sph->step(h);
        ++sph_steps;
        if (walls)
          on_all_ranks([&]() {
            check_solid_wall_overlap(sph->solid_walls(), setup.spacing, time + (k + 1) * h);
          });
      }
    time += dt;
    on_all_ranks([&]() { check_sph_health(sph->particles(), setup, time); });
    list_pairs();
    NewtonReport r;
    r.iterations = n;
    return r;
  }

  std::vector<ParticleFluidSample> SphBackend::sample() const
  {
    const SphParticles &P = sph->particles();
    // The fluid particles' velocities as they are now; at walls the no-slip
    // extrapolation of the last rates.
    std::vector<Vec3> seen = P.velocity;
    for (unsigned int a = 0; a < P.size(); ++a)
      if (P.wall[a])
        seen[a] = sph->viscous_velocities()[a];
    SphFluidFields F;
    with_kernel(setup.settings, [&](auto kernel) {
      F = fluid_fields<decltype(kernel)>(P, sph->fluid_pairs(), sph->box(),
                                         setup.settings.forces, seen);
    });
    const std::vector<Vec3> velocity(P.velocity.begin(), P.velocity.begin() + P.n_local);
    const std::vector<double> porosity(P.porosity.begin(), P.porosity.begin() + P.n_local);
    const auto              u         = shepard(velocity, Vec3());
    const auto              grad_p    = shepard(F.pressure_gradient, Vec3());
    const auto              div_tau   = shepard(F.viscous_divergence, Vec3());
    const auto              eps       = shepard(porosity, 1.);
    const auto              grad_eps  = shepard(F.porosity_gradient, Vec3());
    std::array<std::vector<Vec3>, 3> grad_u;
    for (unsigned int i = 0; i < 3; ++i)
      grad_u[i] = shepard(F.velocity_gradient[i], Vec3());

    // This rank's particles, in the order received.
    std::vector<ParticleFluidSample> out(n_received);
    for (std::size_t j = 0; j < out.size(); ++j)
      {
        const std::size_t    k = first_local + j;
        ParticleFluidSample &o = out[j];
        o.found                = pairs.weight_sum[k] > 0.;
        o.velocity             = u[k];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            o.velocity_gradient[i][j] = grad_u[i][k][j];
        o.pressure_gradient  = grad_p[k];
        o.viscous_divergence = div_tau[k];
        o.porosity           = eps[k];
        o.porosity_gradient  = grad_eps[k];
        o.immersion = settings.weight_by_immersion ? std::min(1., pairs.weight_sum[k]) : 1.;
      }
    return out;
  }

  double SphBackend::exchange_wave_rate(const double eps, const double particle_density) const
  {
    // Particles displaced by xi change the fluid fraction in the SPH
    // particles' state equation: dP = rho_f c_s^2 d(1 - eps) / eps at a
    // held density, whose gradient pushes them back. In a suspension that is
    // a wave of speed c_s sqrt(rho_f (1 - eps) / (rho_p eps)) (rho_p xi'' =
    // rho_f c_s^2 (1 - eps) / eps xi_zz), its shortest wavelength the
    // coupling length's. Each side holds the other's state over a fluid
    // step, so the step must resolve it (a porous block at eps 0.6 in water:
    // the layers' velocities grew unboundedly at dt_f times this rate 0.62,
    // stayed within 5e-4 m/s at 0.31; doc/sph.md, step 5).
    const TaitEquation &state = setup.settings.forces.state;
    return state.sound_speed / settings.coupling_length *
           std::sqrt(state.reference_density * (1. - eps) / (particle_density * eps));
  }

  FluidIntegrals SphBackend::integrals() const
  {
    const SphParticles &P = sph->particles();
    FluidIntegrals      I;
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        I.kinetic_energy += 0.5 * P.mass[a] * norm_square(P.velocity[a]);
    if (distributed)
      I.kinetic_energy = dealii::Utilities::MPI::sum(I.kinetic_energy, communicator);
    return I;
  }

  FluidWallLoads SphBackend::wall_loads() const
  {
    FluidWallLoads L;
    if (!walls)
      return L;
    const SphSolidWalls &W = sph->solid_walls();
    L.force                = W.wall_forces();
    L.torque               = W.wall_torques();
    L.power                = W.wall_powers();
    L.max_overlap          = W.max_overlap();
    const SphParticles &P  = sph->particles();
    double              mass = 0.;
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        mass += P.mass[a];
    L.weight = mass * setup.settings.forces.gravity;
    // Before the first step: no contact seen yet.
    L.force.resize(walls->n_walls());
    L.torque.resize(walls->n_walls());
    L.power.resize(walls->n_walls());
    if (distributed)
      {
        sum_over_ranks(L.force, communicator);
        sum_over_ranks(L.torque, communicator);
        sum_over_ranks(L.power, communicator);
        L.max_overlap = dealii::Utilities::MPI::max(L.max_overlap, communicator);
        std::vector<Vec3> weight{L.weight};
        sum_over_ranks(weight, communicator);
        L.weight = weight[0];
      }
    return L;
  }

  std::string SphBackend::write_snapshot(const std::string &directory, const std::string &base,
                                         const unsigned int index) const
  {
    if (!distributed)
      return SphOutput(directory, base).write_files(sph->particles(), setup.spacing, index);
    // Rank 0 writes all particles by id; every rank returns the file's name.
    const SphParticles all = sph->all_particles();
    std::string        name;
    if (rank == 0)
      name = SphOutput(directory, base).write_files(all, setup.spacing, index);
    return dealii::Utilities::MPI::broadcast(communicator, name, 0);
  }

  void SphBackend::save_checkpoint(const std::string &base)
  {
    BinaryWriter out("sluice sph backend");
    sph->save(out);
    out.write(time);
    out.write<std::uint64_t>(sph_steps);
    out.write<std::uint8_t>(deposited);
    out.write_vector(walls ? walls->state() : std::vector<double>());
    if (rank == 0)
      write_file_atomically(base + "_sph.bin", out.finish());
  }

  void SphBackend::load_checkpoint(const std::string &base)
  {
    const std::string file = base + "_sph.bin";
    std::ifstream     in(file, std::ios::binary);
    if (!in)
      throw InputError("entry 'checkpoint/restart from': the SPH fluid's file '" + file +
                       "' is missing");
    try
      {
        BinaryReader reader(std::string((std::istreambuf_iterator<char>(in)), {}),
                            "sluice sph backend");
        sph->load(reader);
        time      = reader.read<double>();
        sph_steps = reader.read<std::uint64_t>();
        deposited = reader.read<std::uint8_t>();
        const std::vector<double> pose = reader.read_vector<double>();
        if (pose.size() != (walls ? walls->state().size() : 0))
          throw BinaryFormatError("it holds " + std::to_string(pose.size()) +
                                  " numbers of solid-wall poses, the scene's walls " +
                                  std::to_string(walls ? walls->state().size() : 0));
        if (walls)
          walls->set_state(pose);
      }
    catch (const BinaryFormatError &e)
      {
        throw InputError("entry 'checkpoint/restart from': the SPH fluid's file '" + file +
                         "' cannot be used: " + e.what());
      }
  }
} // namespace sluice
