#pragma once
// Breakage statistics from the contacts' impact energies (Gao & Sun 2021 §2.3,
// Eq. 13): per particle its cumulative normal impact energy E_imp,i (a
// particle field, so it travels with the particle and is checkpointed), per
// material type the impact energy spectrum, and the breakage probability
// Br_i = C_br,i E_imp,i / m_i.
//
// The spectrum is the histogram of the energy per unit mass E / m_i of every
// impact (the normal energy 1/2 m_eff v_n^2 at a contact's start,
// contact_observer.h) in log-spaced bins, particle-particle and particle-wall
// apart; each impact counts once for each local particle it involves.

#include <sluice/core/wear_parameters.h>
#include <sluice/dem/contact_observer.h>
#include <sluice/dem/particle_storage.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace sluice
{
  class ImpactStatistics
  {
  public:
    /// 'energy_offset': where the cumulative impact energy lies in each
    /// particle's block of fields.
    ImpactStatistics(const WearParameters &parameters, unsigned int n_types,
                     unsigned int energy_offset);

    /// Adds this step's impacts (taken from the observer) to the particles'
    /// cumulative energies and to the spectra.
    /// In a clump scene 'particles' are the bodies, and member_body maps the
    /// observer's member indices onto them (clump_system.h).
    void take(ContactObserver &observer, ParticleStorage &particles,
              const std::vector<unsigned int> *member_body = nullptr);

    /// Per material type over all ranks (collective).
    struct TypeSummary
    {
      double particles = 0., impacts_particle = 0., impacts_wall = 0.;
      double energy_particle = 0., energy_wall = 0.; // [J], all impacts
      double mean_energy = 0.;                       // [J] per particle, cumulative
      double mean_breakage = 0., max_breakage = 0., fraction_broken = 0.; // Br >= 1
    };
    std::vector<TypeSummary> summarise(const ParticleStorage &particles, MPI_Comm comm) const;

    /// Writes the spectra (all ranks' counts; rank 0 writes 'path' whole).
    /// Columns: type, kind (particle or wall), bin edges [J/kg], count, and the
    /// count per unit of log10 of the energy. Collective. Throws OutputError.
    void write_spectrum(const std::string &path, MPI_Comm comm) const;

    /// This rank's counts and sums for a checkpoint, and back (a restart puts
    /// every rank's sum on rank 0). Returns false if the numbers do not fit.
    std::vector<double> state() const;
    bool                set_state(const std::vector<double> &numbers);

  private:
    unsigned int bin_of(double energy_per_mass) const;
    std::size_t  at(unsigned int type, bool wall) const { return 2 * type + wall; }

    WearParameters parameters;
    unsigned int   n_types, energy_offset;
    // Per (type, kind): impacts, their energy, and the histogram.
    std::vector<double> counts, energies, histogram;
  };
} // namespace sluice
