#pragma once
// What the SPH fluid and the DEM's particles exchange (Robinson, Ramaioli &
// Luding 2014, §3.3-3.4; doc/sph.md, step 5), by kernel sums over the pairs
// of an SPH particle a and a solid particle i closer than the coupling
// length's support 2 h_c (one h_c for all, so that every sum below is over
// the same pairs):
//   - the fluid fraction at an SPH particle (their §3.3):
//       eps_a = 1 - sum_i V_i W(r_ai, h_c);
//   - a field A of the fluid at a solid particle, Shepard-corrected
//     (their §3.4), with the SPH particles' volumes V_a = m_a / rho_hat_a:
//       <A>_i = sum_a V_a A_a W(r_ia, h_c) / S_i,  S_i = sum_a V_a W(r_ia, h_c);
//   - the reaction of the force f_i the fluid exerts on solid particle i,
//     spread over the SPH particles with the same weights (their Eqs. 26-27):
//       F_a = -sum_i f_i V_a W(r_ai, h_c) / S_i,
//     so that sum_a F_a = -sum_i f_i to round-off: the S_i are the weights'
//     sums (unit.sph_solid_exchange: 3e-16 of the forces).
// Every periodic image of a pair within 2 h_c is a pair of its own: along a
// periodic direction narrower than 4 h_c one SPH particle can be in reach of
// a solid twice (unit.sph_solid_exchange checks a narrow box against a wide
// one).
// A solid particle with no SPH particle in reach (S_i = 0) samples nothing
// and spreads nothing; the caller is told how many.
// On several ranks every rank holds all solids and pairs them with the SPH
// particles it owns: its S_i and sums are its share, which the caller adds
// over the ranks (sph_backend.h) before normalising.

#include <sluice/core/vector3.h>
#include <sluice/dem/cell_grid.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/sph/sph_particles.h>

#include <vector>

namespace sluice
{
  /// The solid particles as the fluid sees them: centres and volumes.
  struct SolidPoints
  {
    std::vector<Vec3>   position;
    std::vector<double> volume; // [m^3]
  };

  class SphSolidPairs
  {
  public:
    /// Lists, per solid particle, the owned SPH fluid particles (walls left
    /// out) within 2 h_c, and their kernel weights V_a W(r, h_c) with S_i.
    template <typename Kernel>
    void build(const SphParticles &P, const SolidPoints &solids, const PeriodicBox &box,
               double coupling_length);

    /// eps_a of every owned SPH fluid particle (1 where no solid is in reach).
    template <typename Kernel>
    std::vector<double> fluid_fractions(const SphParticles &P, const SolidPoints &solids) const;

    /// <A>_i at every solid particle; 'fallback' where S_i = 0.
    template <typename Value>
    std::vector<Value> sample(const std::vector<Value> &field, const Value &fallback) const
    {
      return normalised(weighted_sums(field), fallback);
    }
    /// sum_a V_a A_a W(r_ia, h_c) at every solid particle.
    template <typename Value>
    std::vector<Value> weighted_sums(const std::vector<Value> &field) const;
    /// The sums divided by S_i; 'fallback' where S_i = 0.
    template <typename Value>
    std::vector<Value> normalised(std::vector<Value> sums, const Value &fallback) const;

    /// F_a on every SPH particle from the forces f_i on the solids.
    std::vector<Vec3> spread(const std::vector<Vec3> &solid_forces, unsigned int n_sph) const;

    /// Solid particles with no SPH particle in reach.
    unsigned int n_unreached() const;

    // Compressed rows per solid particle i: its SPH partners and their
    // weights V_a W(r_ia, h_c), from offset[i] to offset[i + 1] - 1.
    std::vector<unsigned int> offset, partner;
    std::vector<double>       weight, weight_sum; // per pair; S_i per solid
    std::vector<double>       kernel;             // W(r_ia, h_c) per pair

  private:
    CellGrid                  grid;
    std::vector<Vec3>         all;
    std::vector<unsigned int> stencil;
  };
} // namespace sluice
