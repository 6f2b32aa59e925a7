#pragma once
// What a coupled scene asks of its fluid, whatever solves it: the finite-
// element VANS solver (vans_backend.h) or the SPH fluid (sph_backend.h).
// Everything crosses this interface as plain numbers per particle or per step,
// so the coupled scene, the particle-fluid forces and the validation probes do
// not depend on how the fluid is discretised. The calls are per coupling step,
// never per contact.

#include <sluice/core/vector3.h>
#include <sluice/coupling/self_induced_velocity.h>
#include <sluice/fluid/fluid_reports.h>

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace sluice
{
  /// One particle as the DEM hands it to the fluid.
  struct ExchangeParticle
  {
    Vec3   position, velocity;
    Vec3   reaction_force; // the force the fluid receives from this particle [N]
    double volume = 0.;
    // d(drag on the particle)/d(fluid velocity) [kg/s], for a fluid that takes
    // the drag semi-implicitly ('cfd-dem/semi-implicit drag')
    double drag_coefficient = 0.;
  };

  /// The fluid at one particle.
  struct ParticleFluidSample
  {
    bool   found = false; // the particle lies in the fluid (on this rank)
    Vec3   velocity;
    double velocity_gradient[3][3] = {}; // [i][j] = d u_i / d x_j
    Vec3   pressure_gradient;
    Vec3   viscous_divergence; // div tau
    double porosity = 1.;
    Vec3   porosity_gradient;
    // The share of the particle's surroundings the fluid fills: 1 inside it;
    // the SPH fluid with 'particles above sph fluid' gives its kernel's
    // coverage, below 1 across a free surface. Every fluid force is weighted
    // by it.
    double immersion = 1.;
  };

  /// The conservation record of one deposit (sums over all ranks).
  struct DepositReport
  {
    Vec3         particle_force;    // sum of the particles' reaction forces
    Vec3         field_force;       // integral of the fluid's momentum source
    double       particle_drag = 0., field_drag = 0.; // drag coefficients, semi-implicit
    unsigned int clipped_nodes = 0; // where the solid fraction hit its cap
  };

  /// What the fluid does to the DEM's walls, numbered as in the DEM's
  /// WallSet (planes, then meshes); empty where the fluid does not meet them
  /// (the SPH fluid with 'sph/solid walls').
  struct FluidWallLoads
  {
    std::vector<Vec3>   force, torque; // torque about each wall's motion origin [N], [N m]
    std::vector<double> power;         // what each wall gives the fluid [W]
    double              max_overlap = 0.; // the deepest a fluid particle came into one [m]
    Vec3                weight;           // the fluid's own [N]
  };

  class FluidBackend
  {
  public:
    virtual ~FluidBackend() = default;

    /// One line on the fluid's discretisation for the scene's header.
    virtual void describe(std::ostream &out) const = 0;

    /// Hands the particles over (the order is kept for sample()). Returns how
    /// many (all ranks) lie outside the fluid.
    virtual unsigned long long receive(const std::vector<ExchangeParticle> &particles) = 0;

    /// Two-way coupling: the porosity and the momentum source from the
    /// particles received last ('initial': the porosity the fluid starts in).
    virtual DepositReport deposit(bool initial) = 0;
    /// No momentum source (for the fluid's start at rest in its porosity).
    virtual void clear_momentum_source() = 0;

    /// The steady fluid in the current porosity and sources.
    virtual NewtonReport solve_steady() = 0;
    /// One fluid step of dt (a discretisation may adapt itself after it).
    virtual NewtonReport advance(double dt) = 0;

    /// The fluid at the particles received last, in their order.
    virtual std::vector<ParticleFluidSample> sample() const = 0;
    /// The rate [1/s] of the fastest pressure wave the explicit two-way
    /// exchange carries between a compressible fluid and its particles, of
    /// density 'particle_density', at fluid fraction 'eps'; 0 when the fluid
    /// is incompressible (the coupled scene keeps the fluid step below it).
    virtual double exchange_wave_rate(double /*eps*/, double /*particle_density*/) const
    {
      return 0.;
    }
    virtual FluidIntegrals                   integrals() const = 0;
    /// Collective. Lines on how the fluid is laid out over the ranks at the
    /// end, for the scene's summary (a layout fixed at the start says
    /// nothing).
    virtual void summarise_layout(std::ostream & /*out*/) const {}
    /// At the last step (sums over all ranks).
    virtual FluidWallLoads                   wall_loads() const { return {}; }

    /// Two-way coupling: this fluid's response to one particle's force,
    /// measured over n_memory fluid steps along 'direction', for the
    /// self-induced velocity correction (self_induced_velocity.h); says in
    /// 'summary' what was measured. Collective.
    virtual std::unique_ptr<SelfInducedVelocity>
    self_induced_velocity(const Vec3 &direction, unsigned int n_memory, const PeriodicBox &box,
                          double largest_diameter, std::string &summary) const = 0;

    /// Writes snapshot 'index'; returns the file name for the .pvd.
    virtual std::string write_snapshot(const std::string &directory, const std::string &base,
                                       unsigned int index) const = 0;

    /// Collective. The fluid's whole state (mesh, time levels, fields) as
    /// files whose names start with 'base', and back; loading throws
    /// InputError naming the file when it is missing or does not fit. Saving
    /// drops whatever the solver reuses between steps and a restarted run
    /// would not have (a preconditioner), so both go on identically.
    virtual void save_checkpoint(const std::string &base) = 0;
    virtual void load_checkpoint(const std::string &base)       = 0;
  };
} // namespace sluice
