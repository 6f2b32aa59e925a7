#pragma once
// The SPH fluid as a coupled scene's fluid (Robinson, Ramaioli & Luding
// 2014, §3.3-3.4; doc/sph.md, step 5). Per coupling step:
//   - receive: the DEM particles become solid points (centre, volume), and
//     their pairs with the SPH fluid particles within 2 h_c are listed
//     (sph_solid_exchange.h); a particle with none is 'outside' the fluid;
//   - deposit: each SPH particle's fluid fraction eps_a = 1 - sum_i V_i W,
//     held at or above 1 - (the largest solid fraction), goes into its state
//     equation, and the particles' reactions, spread with the Shepard weights,
//     become forces on the SPH particles (equal and opposite to round-off);
//     at the start the fluid takes the solids in at rest: rho_hat = eps rho(P);
//   - solve_steady (the start): the fluid relaxes to rest, damped, with the
//     time and the particles held, each passing on its pressure force's
//     reaction;
//   - advance: SPH steps of at most 'step fraction' times the SPH stable step
//     fill the fluid step, the deposit's forces held over them;
//   - sample: velocity, its gradient, grad P, div tau, eps and grad eps at
//     each particle by Shepard's interpolation of the SPH particles' values
//     (sph_fluid_fields.h), on pairs listed again after the fluid moved.
//     Shepard's normalisation gives a grain that one fluid particle barely
//     reaches the whole of that particle's grad P: a grain above a free
//     surface would get its full buoyancy, and its reaction would be heaped
//     on that one particle. With 'weight_by_immersion' the grain's forces are
//     weighted by the normalisation's own sum S_i = sum_a (m_a / rho_a) W_ia,
//     the kernel's coverage by the fluid (at most 1; 1 within it).
// With 'sph/solid walls' the fluid meets the DEM's walls (sph_solid_walls.h)
// in a WallSet of its own, built from the same entries and moved with the SPH
// steps: the DEM's has already reached the end of the fluid step when the
// fluid takes it. Its poses are in the fluid's checkpoint.
// On several ranks the SPH fluid is decomposed as in an SPH scene
// (sph_exchange.h), and every rank holds all the solids (each receive gathers
// them, in rank order): a rank pairs them with the SPH particles it owns, and
// the kernel sums S_i and the Shepard sums are added over the ranks before
// they are normalised. So each SPH particle gets its whole fluid fraction
// and its share of every reaction where it is owned, and each solid the sums
// of one rank. What that costs grows with the solids, not with a rank's share
// of them (doc/sph.md, "Several ranks").

#include <sluice/coupling/fluid_backend.h>
#include <sluice/dem/wall_set.h>
#include <sluice/sph/sph_setup.h>
#include <sluice/sph/sph_solid_exchange.h>
#include <sluice/sph/sph_solver.h>

#include <memory>
#include <string>

namespace sluice
{
  struct SphBackendSettings
  {
    double coupling_length    = 0.;   // h_c [m]
    double max_solid_fraction = 0.64; // eps is held at or above 1 - this [-]
    double step_fraction      = 0.5;  // of the SPH stable step [-]
    double fluid_step         = 0.;   // the coupling step the SPH steps fill [s]
    bool   start_at_rest      = true; // the start's relaxation must reach 1e-5 c_s
    // Each particle's forces weighted by its kernel's coverage by the fluid
    // (ParticleFluidSample::immersion): grains across a free surface.
    bool   weight_by_immersion = false;
  };

  class SphBackend : public FluidBackend
  {
  public:
    /// Builds the SPH fluid of 'setup' (sph_setup.h) at rest; with 'walls',
    /// the fluid meets them by the contact 'law'.
    /// The fluid is decomposed over the ranks of 'communicator'.
    SphBackend(SphSetup setup, const SphBackendSettings &settings,
               std::unique_ptr<WallSet> walls = nullptr, const SolidWallLaw &law = {},
               MPI_Comm communicator = MPI_COMM_SELF);

    void                             describe(std::ostream &out) const override;
    unsigned long long               receive(const std::vector<ExchangeParticle> &particles) override;
    DepositReport                    deposit(bool initial) override;
    void                             clear_momentum_source() override;
    /// The fluid at rest in its porosity: a damped relaxation with the time
    /// and the particles held (the SPH steps as 'iterations', the largest
    /// speed left as 'residual').
    NewtonReport                     solve_steady() override;
    /// The SPH steps taken are reported as 'iterations'.
    NewtonReport                     advance(double dt) override;
    std::vector<ParticleFluidSample> sample() const override;
    /// c_s / h_c sqrt(rho_f (1 - eps) / (rho_p eps)) (see the source).
    double exchange_wave_rate(double eps, double particle_density) const override;
    FluidIntegrals                   integrals() const override;
    /// On several ranks: the cells and their owners now, and how often they
    /// were shared out again (a smoothing length that outgrew them, or the
    /// fluid's flow).
    void                             summarise_layout(std::ostream &out) const override;
    FluidWallLoads                   wall_loads() const override;
    /// Measured on two copies of the fluid as it is now (after the start's
    /// relaxation), at the solids' centroid (sph_self_response.cc).
    std::unique_ptr<SelfInducedVelocity>
    self_induced_velocity(const Vec3 &direction, unsigned int n_memory, const PeriodicBox &box,
                          double largest_diameter, std::string &summary) const override;
    std::string write_snapshot(const std::string &directory, const std::string &base,
                               unsigned int index) const override;
    void save_checkpoint(const std::string &base) override;
    void load_checkpoint(const std::string &base) override;

    const SphSolver &solver() const { return *sph; }
    double           coupling_length() const { return settings.coupling_length; }
    unsigned long long n_sph_steps() const { return sph_steps; }
    /// The largest speed of a fluid particle [m/s] (all ranks).
    double largest_speed() const;

  private:
    /// Another backend in this one's state.
    std::unique_ptr<SphBackend> copy() const;
    /// The pairs of the solids received last with the SPH particles as they
    /// are now, and their S_i over all ranks.
    void list_pairs();
    /// <A>_i of 'field' (per SPH particle) at every solid, its sums over all
    /// ranks; 'fallback' where S_i = 0.
    template <typename Value>
    std::vector<Value> shepard(const std::vector<Value> &field, const Value &fallback) const;
    /// Throws SimulationFailure on every rank when 'check' throws on one.
    template <typename Check>
    void on_all_ranks(const Check &check) const;
    /// Throws SimulationFailure when the start's relaxation left the fluid
    /// faster than 1e-5 c_s.
    void check_at_rest(const NewtonReport &relaxation) const;
    /// Adds to 'forces' the reaction (-on_solids) of each solid that no SPH
    /// particle reaches now, on the fluid particle nearest to it.
    void pass_on_unreached(const std::vector<Vec3> &on_solids, std::vector<Vec3> &forces) const;
    /// Forces on the SPH particles: the reactions V_i <grad P>_i of the
    /// solids' pressure forces, for the start's relaxation.
    void hold_reactions();

    SphSetup                   setup;
    SphBackendSettings         settings;
    std::unique_ptr<WallSet>   walls; // the solid walls, or none
    SolidWallLaw               wall_law;
    std::unique_ptr<SphSolver> sph;
    MPI_Comm                   communicator;
    bool                       distributed = false; // more than one rank
    unsigned int               rank        = 0;
    std::string                decomposition; // the header's line on the ranks
    SolidPoints                solids;        // all ranks', in rank order
    std::vector<Vec3>          reactions; // what the fluid receives from each solid [N]
    unsigned int               first_local = 0, n_received = 0; // this rank's solids among them
    SphSolidPairs              pairs;
    double                     time      = 0.; // of the SPH fluid [s]
    unsigned long long         sph_steps = 0;
    unsigned int               builds_at_listing = 0; // the fluid's pair builds then
    bool                       deposited = false; // two-way: the solids are in the fluid
  };
} // namespace sluice
