#pragma once
// Effective properties of every pair of material types, computed once per scene
// so that the contact loop only indexes a flat table (no map lookup per contact).

#include <sluice/core/scene_parameters.h>

#include <vector>

namespace sluice
{
  /// sqrt(5/6): the Hertz dashpot factor (Tsuji et al. 1992, as in LIGGGHTS)
  /// whose realised restitution equals the set one.
  inline constexpr double sqrt_five_sixths = 0.91287092917527685576;

  /// The damping ratio zeta of a linear spring-dashpot whose restitution is
  /// e in (0, 1]: zeta = -ln e / sqrt(pi^2 + ln^2 e).
  double damping_ratio_from_restitution(double e);

  struct PairProperties
  {
    double E_star = 0.;      // 1/E* = (1-nu_a^2)/E_a + (1-nu_b^2)/E_b (Johnson 1985)
    double G_star = 0.;      // 1/G* = 2(2-nu_a)(1+nu_a)/E_a + 2(2-nu_b)(1+nu_b)/E_b
    double damping_ratio = 0.; // zeta = -ln e / sqrt(pi^2 + ln^2 e)
    double sqrt_tangential_to_normal_stiffness = 0.; // sqrt(4 G*/E*), Hertz-Mindlin
    double friction = 0.;
    double rolling_friction = 0.;
  };

  class ContactProperties
  {
  public:
    explicit ContactProperties(const SceneParameters &parameters);

    const PairProperties &operator()(const unsigned int a, const unsigned int b) const
    {
      return table[a * n_types + b];
    }

    double density(const unsigned int type) const { return densities[type]; }

    /// Linear law: normal stiffness for a pair with effective radius and mass.
    /// Either the fixed value from the .prm or the stiffness whose maximum overlap at
    /// the characteristic velocity equals Hertz's (Lethe's choice):
    /// k_n = 16/15 sqrt(R*) E* (15 m* v^2 / (16 sqrt(R*) E*))^(1/5).
    double linear_stiffness(const PairProperties &pair, double R_eff, double m_eff) const;

    /// Contact duration of a pair of spheres (or a sphere and a wall when
    /// wall = true) of the given radius and material types: pi/omega_d for the
    /// linear law, Hertz's 2.868 (m*^2 / (R* E*^2 v))^(1/5) at the characteristic
    /// velocity otherwise.
    double contact_time(unsigned int type_a, unsigned int type_b, double radius,
                        bool wall) const;

    /// The longest step at which velocity Verlet keeps the restitution realised
    /// by this pair within the relative 'accuracy' of the set value. The
    /// dashpot sees the half-kicked velocity v(t - dt/2); expanding,
    /// m a = -k d - c (v - dt/2 a), so the effective mass is m - c dt/2 and
    /// zeta grows by dt/(4 tau_d), tau_d = m* / c_n. Through
    /// ln e = -pi zeta / sqrt(1 - zeta^2) the restitution is off by
    /// |ln e| / (1 - zeta^2) dt / (4 tau_d), hence
    /// dt <= 4 accuracy tau_d (1 - zeta^2) / |ln e| (doc/dem.md, section 6).
    /// For Hertz, c_n is taken at the maximum overlap at the characteristic
    /// velocity, where it is largest. No limit for e = 1.
    double damping_time_step(unsigned int type_a, unsigned int type_b, double radius, bool wall,
                             double accuracy) const;

    /// The shortest damping_time_step among the pairs the scene can create.
    double shortest_damping_time_step(const std::vector<unsigned int> &types_present,
                                      double smallest_radius, bool with_walls,
                                      double accuracy) const;

    /// Rayleigh time pi R sqrt(rho/G) / (0.1631 nu + 0.8766) of a material.
    double rayleigh_time(unsigned int type, double radius) const;

    /// The shortest contact time among the pairs the scene can create.
    double shortest_contact_time(const std::vector<unsigned int> &types_present,
                                 double smallest_radius, bool with_walls) const;

    NormalContactModel normal_model;
    double             characteristic_velocity;
    double             fixed_linear_stiffness;
    double             tangential_stiffness_ratio;
    std::vector<unsigned int> wall_materials; // of the scene's walls, each once

  private:
    /// m* and R* of two spheres of one radius (or a sphere and a wall).
    void effective_mass_and_radius(unsigned int type_a, unsigned int type_b, double radius,
                                   bool wall, double &m_eff, double &R_eff) const;

    unsigned int                n_types;
    std::vector<double>         densities, young, poisson;
    std::vector<PairProperties> table;
  };
} // namespace sluice
