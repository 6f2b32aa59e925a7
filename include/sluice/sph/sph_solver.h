#pragma once
// One SPH fluid advanced in time (doc/sph.md): its particles (fluid and
// wall), their pairs with a skin, the walls' states and the step.
//
// The step is kick-drift-kick leap-frog (Price 2012, §3.9), with the rates
// that depend on velocity evaluated at a predicted velocity:
//   v_1/2 = v + dt/2 a,  rho_1/2 = rho + dt/2 drho/dt,  x += dt v_1/2,
//   then h, Omega, P, the walls, drho/dt (with delta-SPH's diffusion when
//   it is on) and a at x with
//   v* = v_1/2 + dt/2 a and rho* = rho_1/2 + dt/2 drho/dt,
//   v = v_1/2 + dt/2 a_new,  rho = rho_1/2 + dt/2 drho/dt_new.
// With XSPH the particles drift with v_1/2 plus its XSPH correction; with
// summation density the density comes from the kernel sum at x instead of
// being integrated. Wall particles do not move. The pairs are rebuilt when a
// particle has moved, or a smoothing length grown, by more than the skin
// allows.
//
// The alternative step (SphIntegrator::predictor_corrector) is Monaghan's
// (1989) predictor-corrector, the scheme Gao & Sun (§4) name beside the
// leap-frog: with the rates a, drho/dt at the start,
//   predictor: x* = x + dt/2 v, v* = v + dt/2 a, rho* = rho + dt/2 drho/dt,
//   the rates a*, drho/dt* at that half step,
//   corrector: v_1/2 = v + dt/2 a*, x += dt v_1/2, v += dt a*,
//   rho += dt drho/dt*,
// and the rates again at the new state for the next step: two evaluations a
// step (the leap-frog needs one), second order, not symplectic. With XSPH
// the drifts take v and v_1/2 with their corrections.
//
// The kernel is chosen at set-up; each stage is one templated loop.
//
// On several ranks (sph_exchange.h) each rank advances the particles it
// owns; the pairs reach its ghosts. The pairs' rebuild is decided over all
// ranks, shares the cells out again when the load has drifted or cuts wider
// ones when a smoothing length has grown past them (SphExchange::fit), and
// moves the particles to their cells' ranks, with the step's temporaries;
// between rebuilds the ghosts take their owners' position, velocity and
// density after each drift, and their Omega, pressure and
// no-slip velocity before the accelerations. Every sum over pairs is then
// the one-rank sum in another order.
//
// A coupled scene (coupling/sph_backend.h) gives the fluid particles their
// fluid fractions eps (which the state equation takes) and the DEM
// particles' reactions as forces F_a; each kick adds F_a / m_a to the
// fluid's own acceleration, so a new force acts from the next kick on; a
// rebuild that moves particles to other ranks carries their forces along.

#include <sluice/core/binary_io.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_boundary.h>
#include <sluice/sph/sph_density_diffusion.h>
#include <sluice/sph/sph_exchange.h>
#include <sluice/sph/sph_forces.h>
#include <sluice/sph/sph_pairs.h>
#include <sluice/sph/sph_particles.h>
#include <sluice/sph/sph_repulsive_walls.h>
#include <sluice/sph/sph_solid_walls.h>

#include <memory>
#include <string>

namespace sluice
{
  enum class SphKernel
  {
    wendland_c2,
    cubic_spline
  };

  enum class SphIntegrator
  {
    leap_frog,
    predictor_corrector
  };

  struct SphSettings
  {
    SphKernel          kernel = SphKernel::wendland_c2;
    double             smoothing_factor = 1.5; // sigma in h = sigma (m / rho)^(1/3)
    // Each particle keeps the h it starts with (no Omega: sph_density.h)
    // instead of taking h from its density at every step.
    bool               fixed_smoothing_length = false;
    SphForceParameters forces;
    DensityDiffusion   diffusion; // delta-SPH; off at delta = 0
    // The fluid's density from the kernel sum each step instead of the
    // continuity equation (for comparison: a free surface's deficient sums
    // pull its particles together).
    bool               summation_density = false;
    double             xsph = 0.; // XSPH's epsilon (sph_xsph.h); 0: off
    double             skin_fraction = 0.2; // the pairs' skin, in units of the largest h
    SphIntegrator      integrator = SphIntegrator::leap_frog;
    // Walls of repulsive boundary particles (Monaghan 1994), if any: their
    // force is added to the fluid's acceleration.
    RepulsiveWalls     repulsive_walls;
    // The DEM's walls held by a spring-dashpot contact, if any (moved by the
    // scene before each step): their force is added too.
    SphSolidWalls      solid_walls;
  };

  class SphSolver
  {
  public:
    /// Takes the particles with their masses, densities and positions; sets
    /// h from the densities and evaluates the first rates. On several ranks
    /// of 'communicator' every rank passes all particles and keeps those in
    /// its cells.
    SphSolver(SphParticles particles, const PeriodicBox &box, const SphSettings &settings,
              MPI_Comm communicator = MPI_COMM_SELF);

    /// One step of dt.
    void step(double dt);

    /// The largest stable step: the smallest of 0.25 h / (c_s + |v|),
    /// 0.125 h^2 rho / mu and 0.25 sqrt(h / |a|) over the fluid particles,
    /// and with solid walls their contact's step. Collective.
    double stable_time_step() const;
    /// Which bound gives stable_time_step(), and where: a phrase for a stop's
    /// message ("the force bound 0.25 sqrt(h / |a|) at fluid particle 17 at
    /// (x, y, z), |a| = ..."). Collective.
    std::string stable_step_limit() const;

    /// Everything the next step depends on, for a checkpoint: the particles
    /// with their rates, the pairs and what decides their next rebuild, the
    /// external forces and the walls' no-slip velocities. A run restored
    /// from it repeats the uninterrupted run bit for bit. Collective; on
    /// several ranks the particles of all ranks by id, without the pairs
    /// (the restored run builds them again: the same flow, its sums in
    /// another order).
    void save(BinaryWriter &out) const;
    /// Throws BinaryFormatError for a damaged or foreign record.
    void load(BinaryReader &in);

    /// Several ranks.
    bool distributed() const { return exchange->active(); }
    /// Collective. How the particles are spread over the ranks.
    std::string decomposition() const { return exchange->describe(P); }
    /// Collective. All ranks' owned particles, by id (on one rank: them).
    SphParticles all_particles() const
    {
      return exchange->active() ? exchange->gather_all(P) : P;
    }

    /// The fluid fraction of every owned fluid particle. 'at_rest': the fluid
    /// takes the solids in where it is, at its current pressures (a coupled
    /// start): each particle keeps its volume m / rho_hat and takes
    /// rho_hat = eps rho(P), its mass scaled with it (the fluid the solids
    /// displace is taken out), and the rates are evaluated again.
    void set_fluid_fractions(const std::vector<double> &eps, bool at_rest);
    /// A force [N] per owned particle for the kicks from now on (empty: none);
    /// it stays with its particle across ranks. Not in a checkpoint written on
    /// several ranks (a coupled scene sets it again before its next step).
    void set_external_forces(std::vector<Vec3> forces);
    /// Multiplies the fluid particles' velocities by 'factor' (a damped
    /// relaxation to rest).
    void scale_velocities(double factor);

    /// The velocities the physical viscosity sees: the particles' own, at
    /// walls their no-slip extrapolation (sph_boundary.h).
    const std::vector<Vec3> &viscous_velocities() const { return walls.no_slip; }
    const std::vector<Vec3> &external_forces() const { return external; }
    const SphPairs          &fluid_pairs() const { return pairs; }

    const SphParticles  &particles() const { return P; }
    const SphSolidWalls &solid_walls() const { return settings.solid_walls; }
    /// The solid walls met from now on are those of 'walls' (a copy's).
    void rebind_solid_walls(const WallSet &walls) { settings.solid_walls.rebind(walls); }
    const PeriodicBox  &box() const { return box_; }
    unsigned int        n_pair_builds() const { return builds; }
    /// How often the cells were shared out again among the ranks.
    unsigned int        n_repartitions() const { return exchange->n_repartitions(); }

  private:
    /// h, Omega, P, the walls, drho/dt and a at the current positions.
    void evaluate_rates();
    template <typename Kernel>
    void evaluate_rates_with();
    template <typename Kernel>
    void step_with(double dt);
    template <typename Kernel>
    void predictor_corrector_step_with(double dt);
    /// For the fluid particles: x = x0 + dx_dt (u + its XSPH correction),
    /// v = v0 + dv_dt a, rho = rho0 + dv_dt drho/dt (unless by summation).
    template <typename Kernel>
    void advance_from(const std::vector<Vec3> &x0, const std::vector<Vec3> &v0,
                      const std::vector<double> &rho0, const std::vector<Vec3> &u,
                      double dx_dt, double dv_dt);
    /// 'moving': owned-sized temporaries of the step that a rebuild carries
    /// with their particles to other ranks.
    void rebuild_pairs_if_needed(const SphExchange::Attachments &moving = {});
    /// The pairs for the largest h over all ranks, now (after the particles
    /// moved to their ranks).
    void rebuild_pairs(double h_max, const SphExchange::Attachments &moving);
    /// f(step, bound, a, value) for each bound of stable_time_step() at each
    /// fluid particle a: 0 sound and flow speed (value |v|), 1 viscosity
    /// (rho_hat), 2 force (|a|).
    template <typename F>
    void for_each_step_bound(const F &f) const;
    /// a_a plus the external force's F_a / m_a.
    Vec3 total_acceleration(unsigned int a) const
    {
      return external.empty() ? P.acceleration[a] :
                               P.acceleration[a] + (1. / P.mass[a]) * external[a];
    }

    SphParticles      P;
    PeriodicBox       box_;
    SphSettings       settings;
    MPI_Comm          communicator;
    // Shared by copies (a coupled scene's trial copies, on one rank).
    std::shared_ptr<SphExchange> exchange;
    SphPairs          pairs;
    SphPairKernels    kernels; // r and dW/dr per pair, from the density pass to the forces
    WallStates        walls;
    std::vector<Vec3> position_at_build;
    std::vector<Vec3> external; // F_a [N]; empty: none
    double            skin = 0., h_at_build = 0.;
    unsigned int      builds = 0;
  };
} // namespace sluice
