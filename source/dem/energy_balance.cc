// The energy bookkeeping (see the header).

#include <sluice/dem/energy_balance.h>

#include <sstream>

namespace sluice
{
  // The local numbers: kinetic energy, the springs' energies (particle and
  // wall), then the ledger's sums (normal damping, tangential work, rolling,
  // each particle and wall, then the walls' work).
  std::vector<double> EnergyBalance::local_energies(const ParticleStorage &P,
                                                    const ContactObserver &o) const
  {
    double kinetic = 0.;
    if (clumps)
      {
        for (unsigned int i = 0; i < P.n_local; ++i)
          kinetic += 0.5 * P.mass[i] * norm_square(P.velocity[i]);
        kinetic += clumps->rotational_energy();
      }
    else
      for (unsigned int i = 0; i < P.n_local; ++i)
        kinetic += 0.5 * P.mass[i] * norm_square(P.velocity[i]) +
                   0.5 / P.inverse_inertia[i] * norm_square(P.angular_velocity[i]);
    const EnergyLedger &l = o.ledger;
    return {kinetic,
            l.stored_normal[0] + l.stored_normal[1],
            l.stored_tangential[0] + l.stored_tangential[1],
            l.normal_damping[0],
            l.normal_damping[1],
            l.tangential_work[0],
            l.tangential_work[1],
            l.rolling[0],
            l.rolling[1],
            l.wall_work,
            l.stored_tangential[0],
            l.stored_tangential[1]};
  }

  void EnergyBalance::after_step(const ParticleStorage &P, const ContactObserver &o,
                                 const double dt)
  {
    if (baseline.empty())
      {
        baseline = local_energies(P, o);
        return;
      }
    double power = 0.;
    for (unsigned int i = 0; i < P.n_local; ++i)
      power += P.mass[i] * dot(gravity, P.velocity[i]);
    gravity_work += dt * power;
  }

  EnergyBalance::Totals EnergyBalance::totals(const ParticleStorage &P, const ContactObserver &o,
                                              MPI_Comm comm) const
  {
    std::vector<double> now = local_energies(P, o), base = baseline;
    base.resize(now.size(), 0.);
    std::vector<double> change(now.size() + 1);
    for (std::size_t k = 0; k < now.size(); ++k)
      change[k] = now[k] - base[k];
    change.back() = gravity_work;
    MPI_Allreduce(MPI_IN_PLACE, change.data(), change.size(), MPI_DOUBLE, MPI_SUM, comm);
    Totals t;
    t.kinetic_change           = change[0];
    t.normal_spring_change     = change[1];
    t.tangential_spring_change = change[2];
    for (const unsigned int k : {0u, 1u})
      {
        t.normal_damping[k] = change[3 + k];
        // Sliding friction: the tangential work less what the springs now hold.
        t.friction[k] = change[5 + k] - change[10 + k];
        t.rolling[k]  = change[7 + k];
      }
    t.wall_work    = change[9];
    t.gravity_work = change.back();
    t.dissipated   = t.normal_damping[0] + t.normal_damping[1] + t.friction[0] + t.friction[1] +
                   t.rolling[0] + t.rolling[1];
    t.residual = t.kinetic_change + t.normal_spring_change + t.tangential_spring_change -
                 t.gravity_work - t.wall_work + t.dissipated;
    return t;
  }

  std::string EnergyBalance::line(const Totals &t)
  {
    std::ostringstream out;
    out.precision(8);
    out << "energy: gravity_work=" << t.gravity_work << " wall_work=" << t.wall_work
        << " kinetic_change=" << t.kinetic_change << " spring_change="
        << t.normal_spring_change + t.tangential_spring_change
        << " normal_damping_pp=" << t.normal_damping[0] << " normal_damping_pw="
        << t.normal_damping[1] << " friction_pp=" << t.friction[0]
        << " friction_pw=" << t.friction[1] << " rolling_pp=" << t.rolling[0]
        << " rolling_pw=" << t.rolling[1] << " dissipated=" << t.dissipated
        << " residual=" << t.residual
        << " residual_over_dissipated=" << (t.dissipated != 0. ? t.residual / t.dissipated : 0.);
    return out.str();
  }

  std::vector<double> EnergyBalance::state() const
  {
    std::vector<double> s{gravity_work, static_cast<double>(baseline.size())};
    s.insert(s.end(), baseline.begin(), baseline.end());
    return s;
  }

  void EnergyBalance::set_state(const std::vector<double> &s)
  {
    if (s.size() < 2)
      return;
    gravity_work = s[0];
    baseline.assign(s.begin() + 2, s.begin() + 2 + static_cast<std::size_t>(s[1]));
  }
} // namespace sluice
