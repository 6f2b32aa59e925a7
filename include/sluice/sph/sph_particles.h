#pragma once
// The SPH fluid's particles as structure-of-arrays (doc/sph.md): entries
// [0, n_local) are owned by this rank, the rest are ghost copies. Each
// particle carries its mass, position and velocity, the superficial density
// rho_hat = eps rho (eps the fluid fraction, 1 without DEM particles), its
// smoothing length h, Price's correction Omega, its pressure and the rates
// the integrator needs.

#include <sluice/core/vector3.h>

#include <cstdint>
#include <vector>

namespace sluice
{
  struct SphParticles
  {
    std::vector<std::uint64_t> id;
    std::vector<Vec3>          position, velocity, acceleration;
    std::vector<double>        mass;
    std::vector<double>        density;      // rho_hat [kg/m^3]
    std::vector<double>        density_rate; // d rho_hat / dt [kg/(m^3 s)]
    std::vector<double>        smoothing;    // h [m]
    std::vector<double>        omega;        // Price's Omega [-]
    std::vector<double>        pressure;     // [Pa]
    std::vector<double>        porosity;     // eps [-]
    // A wall particle (sph_boundary.h) is not moved by the fluid: its state
    // follows from the fluid around it each step; 'wall_velocity' is its own.
    std::vector<unsigned char> wall;
    std::vector<Vec3>          wall_velocity;
    unsigned int               n_local = 0;

    unsigned int size() const { return id.size(); }

    /// Appends a particle at rest with the fluid's density and eps = 1 (a
    /// wall particle if 'is_wall').
    void push_back(std::uint64_t id, const Vec3 &x, double mass, double density, double h,
                   bool is_wall = false)
    {
      this->id.push_back(id);
      position.push_back(x);
      velocity.emplace_back();
      acceleration.emplace_back();
      this->mass.push_back(mass);
      this->density.push_back(density);
      density_rate.push_back(0.);
      smoothing.push_back(h);
      omega.push_back(1.);
      pressure.push_back(0.);
      porosity.push_back(1.);
      wall.push_back(is_wall);
      wall_velocity.emplace_back();
    }
  };
} // namespace sluice
