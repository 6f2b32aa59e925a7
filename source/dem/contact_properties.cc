#include <sluice/core/sphere.h>
#include <sluice/dem/contact_properties.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sluice
{
  double damping_ratio_from_restitution(const double e)
  {
    // Linear oscillator: e = exp(-zeta pi / sqrt(1 - zeta^2)) (Gao & Sun Eq. 10).
    const double l = std::log(e);
    return -l / std::sqrt(M_PI * M_PI + l * l);
  }

  namespace
  {
    double pair_value(const std::vector<PairOverride> &overrides, const unsigned int a,
                      const unsigned int b, const double fallback)
    {
      double v = fallback;
      for (const auto &o : overrides)
        if ((o.type_a == a && o.type_b == b) || (o.type_a == b && o.type_b == a))
          v = o.value;
      return v;
    }

    /// The materials of the planes and the mesh walls, each once.
    std::vector<unsigned int> distinct_wall_materials(const SceneParameters &p)
    {
      std::vector<unsigned int> m;
      const auto add = [&](const unsigned int material) {
        if (std::find(m.begin(), m.end(), material) == m.end())
          m.push_back(material);
      };
      for (const PlaneWall &w : p.walls)
        add(w.material);
      for (const MeshWallParameters &w : p.meshes)
        add(w.material);
      return m;
    }
  } // namespace

  ContactProperties::ContactProperties(const SceneParameters &p)
    : normal_model(p.normal_model)
    , characteristic_velocity(p.characteristic_velocity)
    , fixed_linear_stiffness(p.linear_normal_stiffness)
    , tangential_stiffness_ratio(p.tangential_stiffness_ratio)
    , wall_materials(distinct_wall_materials(p))
    , n_types(p.n_materials())
    , densities(p.density)
    , young(p.young_modulus)
    , poisson(p.poisson_ratio)
    , table(n_types * n_types)
  {
    for (unsigned int a = 0; a < n_types; ++a)
      for (unsigned int b = 0; b < n_types; ++b)
        {
          PairProperties &pp = table[a * n_types + b];
          pp.E_star          = 1. / ((1. - poisson[a] * poisson[a]) / young[a] +
                            (1. - poisson[b] * poisson[b]) / young[b]);
          pp.G_star = 1. / (2. * (2. - poisson[a]) * (1. + poisson[a]) / young[a] +
                            2. * (2. - poisson[b]) * (1. + poisson[b]) / young[b]);
          pp.sqrt_tangential_to_normal_stiffness = std::sqrt(4. * pp.G_star / pp.E_star);
          pp.damping_ratio =
            damping_ratio_from_restitution(pair_value(p.restitution_pairs, a, b, p.restitution));
          pp.friction         = pair_value(p.friction_pairs, a, b, p.friction);
          pp.rolling_friction = pair_value(p.rolling_friction_pairs, a, b, p.rolling_friction);
        }
  }

  double ContactProperties::linear_stiffness(const PairProperties &pair, const double R_eff,
                                             const double m_eff) const
  {
    if (fixed_linear_stiffness > 0.)
      return fixed_linear_stiffness;
    const double sqrt_R = std::sqrt(R_eff);
    const double v      = characteristic_velocity;
    return 16. / 15. * sqrt_R * pair.E_star *
           std::pow(15. * m_eff * v * v / (16. * sqrt_R * pair.E_star), 0.2);
  }

  void ContactProperties::effective_mass_and_radius(const unsigned int a, const unsigned int b,
                                                    const double radius, const bool wall,
                                                    double &m_eff, double &R_eff) const
  {
    const double m_a = sphere_mass(densities[a], radius);
    const double m_b = sphere_mass(densities[b], radius);
    m_eff            = wall ? m_a : m_a * m_b / (m_a + m_b);
    R_eff            = wall ? radius : radius / 2.;
  }

  double ContactProperties::contact_time(const unsigned int a, const unsigned int b,
                                         const double radius, const bool wall) const
  {
    const PairProperties &pair = (*this)(a, b);
    double                m_eff, R_eff;
    effective_mass_and_radius(a, b, radius, wall, m_eff, R_eff);
    if (normal_model == NormalContactModel::linear)
      {
        const double k    = linear_stiffness(pair, R_eff, m_eff);
        const double zeta = pair.damping_ratio;
        return M_PI / (std::sqrt(k / m_eff) * std::sqrt(1. - zeta * zeta));
      }
    const double v = characteristic_velocity;
    return 2.868265699 *
           std::pow(m_eff * m_eff / (R_eff * pair.E_star * pair.E_star * v), 0.2);
  }

  double ContactProperties::damping_time_step(const unsigned int a, const unsigned int b,
                                              const double radius, const bool wall,
                                              const double accuracy) const
  {
    const PairProperties &pair = (*this)(a, b);
    const double          zeta = pair.damping_ratio;
    if (!(zeta > 0.))
      return std::numeric_limits<double>::max(); // e = 1: no dashpot
    double m_eff, R_eff;
    effective_mass_and_radius(a, b, radius, wall, m_eff, R_eff);
    // The dashpot coefficient where it is largest: for Hertz at the maximum
    // overlap of an impact at the characteristic velocity.
    double c_n;
    if (normal_model == NormalContactModel::linear)
      c_n = 2. * zeta * std::sqrt(linear_stiffness(pair, R_eff, m_eff) * m_eff);
    else
      {
        const double v         = characteristic_velocity;
        const double delta_max = std::pow(15. * m_eff * v * v / (16. * pair.E_star * std::sqrt(R_eff)),
                                          0.4);
        const double S_n       = 2. * pair.E_star * std::sqrt(R_eff * delta_max);
        c_n = 2. * sqrt_five_sixths * zeta * std::sqrt(S_n * m_eff);
      }
    const double tau_d     = m_eff / c_n;
    const double minus_ln_e = M_PI * zeta / std::sqrt(1. - zeta * zeta);
    return 4. * accuracy * tau_d * (1. - zeta * zeta) / minus_ln_e;
  }

  double ContactProperties::shortest_damping_time_step(const std::vector<unsigned int> &types,
                                                       const double smallest_radius,
                                                       const bool   with_walls,
                                                       const double accuracy) const
  {
    double h = std::numeric_limits<double>::max();
    for (const unsigned int a : types)
      {
        for (const unsigned int b : types)
          h = std::min(h, damping_time_step(a, b, smallest_radius, false, accuracy));
        if (with_walls)
          for (const unsigned int w : wall_materials)
            h = std::min(h, damping_time_step(a, w, smallest_radius, true, accuracy));
      }
    return h;
  }

  double ContactProperties::rayleigh_time(const unsigned int type, const double radius) const
  {
    const double G = young[type] / (2. * (1. + poisson[type]));
    return M_PI * radius * std::sqrt(densities[type] / G) / (0.1631 * poisson[type] + 0.8766);
  }

  double ContactProperties::shortest_contact_time(const std::vector<unsigned int> &types,
                                                  const double smallest_radius,
                                                  const bool   with_walls) const
  {
    double t = std::numeric_limits<double>::max();
    for (const unsigned int a : types)
      {
        for (const unsigned int b : types)
          t = std::min(t, contact_time(a, b, smallest_radius, false));
        if (with_walls)
          for (const unsigned int w : wall_materials)
            t = std::min(t, contact_time(a, w, smallest_radius, true));
      }
    return t;
  }
} // namespace sluice
