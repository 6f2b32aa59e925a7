#pragma once
// Structure-of-arrays storage of the particles the DEM hot loop works on.
//
// Entries [0, n_local) are the particles this MPI rank owns; entries
// [n_local, size()) are ghost copies of particles owned by neighbouring ranks,
// refreshed every step. The order follows the cells of the background mesh, so
// neighbours in space are mostly neighbours in memory.

#include <sluice/core/vector3.h>

#include <cstdint>
#include <vector>

namespace sluice
{
  struct ParticleStorage
  {
    std::vector<std::uint64_t> id;
    std::vector<Vec3>          position, velocity, angular_velocity, force, torque;
    std::vector<double>        radius, mass, inverse_mass, inverse_inertia;
    std::vector<unsigned int>  type;
    std::vector<unsigned int>  coordination; // contacts per local particle, last step

    /// Per-particle data a coupled scene keeps for its owned particles (the
    /// fluid at the particle, frozen over a fluid step, and the impulse owed to
    /// the fluid): 'n_extra' doubles each, contiguous; empty in a pure-DEM
    /// scene. It travels with a particle that changes rank.
    unsigned int        n_extra = 0;
    std::vector<double> extra;
    double       *extra_of(const unsigned int i) { return extra.data() + n_extra * i; }
    const double *extra_of(const unsigned int i) const { return extra.data() + n_extra * i; }

    unsigned int n_local = 0;
    double       max_drift_speed_2 = 0.; // largest |v|^2 of the last drift()

    unsigned int size() const { return id.size(); }
    unsigned int n_ghost() const { return size() - n_local; }

    void clear();
    /// Appends one particle; mass and inertia follow from radius and density.
    void push_back(std::uint64_t id, const Vec3 &x, const Vec3 &v, const Vec3 &w, double r,
                   unsigned int type, double density);
  };
} // namespace sluice
