#pragma once
// The energy bookkeeping of a DEM scene (doc/geometry.md): from the first
// observed step on, the work of gravity and of the moving walls, the change of
// the kinetic energy and of the energy in the contacts' springs, and the
// energy dissipated by normal damping, sliding friction and rolling
// resistance, particle-particle and particle-wall apart (contact_observer.h).
// They balance up to the time integration's error:
//   residual = dKE + dU_n + dU_t - W_gravity - W_walls + D_n + D_t + D_r,
// which falls as dt^2 with Hertz's law (whose dashpot vanishes as a contact
// starts). Exact on one rank; on several, a pair across a rank boundary uses
// its ghost's velocity from the middle of the step.

#include <sluice/core/vector3.h>
#include <sluice/dem/contact_observer.h>
#include <sluice/dem/clump_system.h>
#include <sluice/dem/particle_storage.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace sluice
{
  class EnergyBalance
  {
  public:
    explicit EnergyBalance(const Vec3 &gravity) : gravity(gravity) {}

    /// In a clump scene the particles passed are the bodies, and their
    /// rotational energy is the clumps' (L_k^2 / 2 I_k).
    void count_bodies(const ClumpSystem *c) { clumps = c; }

    /// After each step with the observer attached: the gravity's work of the
    /// step (dt m g . v at the step's end, the velocity that makes it the
    /// kinetic energy gravity gave); the first call takes the baseline.
    void after_step(const ParticleStorage &particles, const ContactObserver &observer,
                    double dt);

    struct Totals
    {
      double kinetic_change = 0., normal_spring_change = 0., tangential_spring_change = 0.;
      double gravity_work = 0., wall_work = 0.;
      double normal_damping[2] = {0., 0.}, friction[2] = {0., 0.}, rolling[2] = {0., 0.};
      double dissipated = 0., residual = 0.;
    };
    /// Over all ranks since the baseline (collective).
    Totals totals(const ParticleStorage &particles, const ContactObserver &observer,
                  MPI_Comm comm) const;

    /// 'energy: ...' with every term [J] and the residual over the dissipation.
    static std::string line(const Totals &t);

    bool started() const { return !baseline.empty(); }
    /// For a checkpoint: this rank's baseline and gravity work, and back.
    std::vector<double> state() const;
    void                set_state(const std::vector<double> &numbers);

  private:
    std::vector<double> local_energies(const ParticleStorage &P, const ContactObserver &o) const;

    Vec3                gravity;
    const ClumpSystem  *clumps = nullptr;
    double              gravity_work = 0.;
    std::vector<double> baseline; // local_energies() at the first step
  };
} // namespace sluice
