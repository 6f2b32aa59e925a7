#pragma once
// The finite-element VANS solver as a coupled scene's fluid: the particles go
// to the fluid mesh's ParticleHandler, deposit their volume and reaction with
// the kernel (or centroid) weights (particle_fluid_exchange.h), and the fluid
// is sampled at their centres.

#include <sluice/core/coupling_parameters.h>
#include <sluice/core/fluid_parameters.h>
#include <sluice/coupling/fluid_backend.h>
#include <sluice/coupling/self_induced_velocity.h>
#include <sluice/dem/periodic_box.h>

#include <mpi.h>

#include <memory>
#include <string>

namespace sluice
{
  class VansBackend : public FluidBackend
  {
  public:
    /// fluid: the fluid entries as the coupling formulation needs them;
    /// largest_diameter: of the particles (the kernel must cover two). Builds
    /// and initialises the mesh; throws InputError for a kernel radius
    /// outside [2 d, smallest cell].
    VansBackend(const FluidParameters &fluid, const CouplingParameters &coupling,
                const Vec3 &gravity, double largest_diameter, const std::string &file_name,
                MPI_Comm comm);
    ~VansBackend() override;

    void                             describe(std::ostream &out) const override;
    unsigned long long               receive(const std::vector<ExchangeParticle> &particles) override;
    DepositReport                    deposit(bool initial) override;
    void                             clear_momentum_source() override;
    NewtonReport                     solve_steady() override;
    NewtonReport                     advance(double dt) override;
    std::vector<ParticleFluidSample> sample() const override;
    FluidIntegrals                   integrals() const override;
    std::string write_snapshot(const std::string &directory, const std::string &base,
                               unsigned int index) const override;
    void save_checkpoint(const std::string &base) override;
    void load_checkpoint(const std::string &base) override;

    double kernel_radius() const { return radius; }

    /// The fluid's response to one particle's force, measured on this mesh
    /// over n_memory fluid steps (self_induced_velocity.h); returns the
    /// correction and says in 'summary' what was measured.
    std::unique_ptr<SelfInducedVelocity> self_induced_velocity(const Vec3 &direction,
                                                               unsigned int n_memory,
                                                               const PeriodicBox &box,
                                                               double largest_diameter,
                                                               std::string &summary) const override;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> impl;
    double                          radius = 0., smallest_cell = 0.;
  };
} // namespace sluice
