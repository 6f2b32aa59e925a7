#pragma once
// What the contact pass can report to wear and breakage statistics (Gao & Sun
// Eqs. 12-13): the normal impact energy of each contact as it starts, and the
// shear (friction) work done at each wall contact in each step.
//
// A scene that wants them attaches a ContactObserver to the DEM
// (DemSystem::observe); the contact kernel is then the instantiation that
// records (contact_forces.h), and a scene that does not pays nothing: the
// recording code is compiled out of the kernel it runs.
//
// Contact start needs no stored flag: with velocity Verlet the centres moved
// by dt v^{n+1/2} in the drift just before the contact pass, and the contact
// pass sees exactly those velocities, so the pair's separation one step ago is
// |d - dt (v_i - v_j)| (a wall: the gap one step ago is the gap now plus dt
// times the normal approach speed relative to the wall's surface). A contact
// starts in this step when it overlaps now and did not then. This holds
// across list rebuilds and rank changes, where a flag would have to travel.

#include <sluice/core/vector3.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace sluice
{
  /// One particle's impact: recorded for every local particle of a starting
  /// contact (both of a pair on one rank; a pair across ranks on each rank
  /// for its own particle).
  struct ImpactRecord
  {
    std::uint64_t id;      // the particle's
    unsigned int  index;   // its place in the local arrays
    unsigned int  type;    // its material type
    unsigned int  partner; // the other particle's type, or the wall's index
    bool          wall;
    double        energy;  // 1/2 m_eff v_n^2 at the start [J]
  };

  /// One contact of the last pass as the energy bookkeeping needs it: the
  /// forces it exerted on particle i (and -F, with its own lever arm, on j or
  /// the wall), to be dotted with the velocities at the end of the step.
  struct ContactEnergyRecord
  {
    static constexpr unsigned int none = ~0u;
    unsigned int i, j;                // j: none for a wall
    unsigned int wall, triangle;      // wall index; triangle over all meshes, or none
    Vec3         n;                   // from j (or the wall) to i
    double       arm_i, arm_j;
    Vec3         force;               // total contact force on i
    double       damping_force;       // the normal dashpot's part, along n
    Vec3         tangential_force;
    Vec3         rolling_torque;      // on i
    Vec3         wall_velocity, wall_spin; // at the contact point; the spin the law used
    double       share;               // 1, or 1/2 for a pair with a ghost (each rank counts half)
  };

  /// Energies of the contacts, cumulative since the observer was attached
  /// [J]: index 0 particle-particle, 1 particle-wall. 'tangential_work' is
  /// the work the tangential forces took from the relative motion; the
  /// friction dissipation is that minus the energy now in the tangential
  /// springs ('stored_tangential').
  struct EnergyLedger
  {
    double normal_damping[2] = {0., 0.}, tangential_work[2] = {0., 0.},
           rolling[2] = {0., 0.};
    double wall_work = 0.; // done by moving walls on the particles
    // In the springs at the last pass (a state, not a sum).
    double stored_normal[2] = {0., 0.}, stored_tangential[2] = {0., 0.};
    // Per particle type, particle-wall tangential work (for the per-type check).
    std::vector<double> wall_tangential_work_by_type;
  };

  class ContactObserver
  {
  public:
    /// n_triangles: of all mesh walls, numbered as WallSet::triangle_offset()
    /// does; n_types: particle material types (the per-triangle shear sums
    /// are kept per type, for wear coefficients that depend on it).
    explicit ContactObserver(unsigned int n_walls = 0, unsigned int n_triangles = 0,
                             unsigned int n_types = 1)
      : wall_shear_work(n_walls, 0.), wall_impact_energy(n_walls, 0.),
        triangle_impact_energy(n_triangles, 0.),
        triangle_shear_work(static_cast<std::size_t>(n_types) * n_triangles, 0.),
        triangle_load_slip(static_cast<std::size_t>(n_types) * n_triangles, 0.),
        n_triangles(n_triangles)
    {
      ledger.wall_tangential_work_by_type.assign(n_types, 0.);
    }

    // ---- The energy bookkeeping ----
    /// Called by the contact pass for every contact, and with the energy in
    /// its springs; settle() completes the step once the velocities are at
    /// its end (DemSystem::advance, after the second half kick).
    void contact(const ContactEnergyRecord &r) { pending.push_back(r); }
    void stored(const bool wall, const double share, const double normal,
                const double tangential)
    {
      pass_stored_normal[wall] += share * normal;
      pass_stored_tangential[wall] += share * tangential;
    }
    /// Each pending contact's work over the step with the velocities at its
    /// end, v^{n+1} = (v^{n+1/2} + v^{n+3/2}) / 2 by velocity Verlet, which
    /// is the velocity that makes the work equal the kinetic energy each
    /// contact's forces give (doc/geometry.md): the normal damping, the
    /// tangential and rolling work, the moving walls' work, and each wall
    /// contact's shear work on its wall and triangle (wear). 'types' and
    /// 'v', 'w' are the particles'.
    void settle(const Vec3 *v, const Vec3 *w, const unsigned int *types, const double dt)
    {
      for (const ContactEnergyRecord &r : pending)
        {
          const bool wall = r.j == ContactEnergyRecord::none;
          Vec3       v_c  = v[r.i] - cross(r.arm_i * w[r.i], r.n);
          Vec3       spin = w[r.i];
          if (wall)
            {
              v_c -= r.wall_velocity;
              spin -= r.wall_spin;
            }
          else
            {
              v_c -= v[r.j] + cross(r.arm_j * w[r.j], r.n);
              spin -= w[r.j];
            }
          const double h = r.share * dt;
          ledger.normal_damping[wall] -= h * r.damping_force * dot(r.n, v_c);
          const double tangential = -h * dot(r.tangential_force, v_c);
          ledger.tangential_work[wall] += tangential;
          ledger.rolling[wall] -= h * dot(r.rolling_torque, spin);
          if (wall)
            {
              ledger.wall_work += dt * (dot(r.force, r.wall_velocity) + dot(r.rolling_torque, r.wall_spin));
              ledger.wall_tangential_work_by_type[types[r.i]] += tangential;
              wall_shear_work[r.wall] += tangential;
              if (r.triangle != ContactEnergyRecord::none)
                triangle_shear_work[static_cast<std::size_t>(types[r.i]) * n_triangles +
                                    r.triangle] += tangential;
            }
        }
      pending.clear();
      for (const unsigned int k : {0u, 1u})
        {
          ledger.stored_normal[k]     = pass_stored_normal[k];
          ledger.stored_tangential[k] = pass_stored_tangential[k];
          pass_stored_normal[k] = pass_stored_tangential[k] = 0.;
        }
    }
    EnergyLedger ledger;

    /// The impacts since the last call, handed over and forgotten.
    std::vector<ImpactRecord> take_impacts()
    {
      std::vector<ImpactRecord> out;
      out.swap(impacts);
      return out;
    }

    // ---- Called by the contact kernel ----
    void impact(const std::uint64_t id, const unsigned int index, const unsigned int type,
                const unsigned int partner, const bool wall, const double energy)
    {
      impacts.push_back({id, index, type, partner, wall, energy});
      if (wall)
        wall_impact_energy[partner] += energy;
    }
    /// A mesh contact's start on triangle t (numbered over all meshes).
    void triangle_impact(const unsigned int t, const double energy)
    {
      triangle_impact_energy[t] += energy;
    }
    /// A mesh contact's normal force times its slip distance in one step
    /// (Archard's load-distance product), by particle type.
    void triangle_load(const unsigned int t, const unsigned int type, const double load_slip)
    {
      triangle_load_slip[static_cast<std::size_t>(type) * n_triangles + t] += load_slip;
    }

    /// Cumulative on this rank since the start [J]: the shear work -F_t . v_t dt
    /// done on the particles at each wall (positive: dissipated), and the
    /// normal impact energy each wall received.
    std::vector<double> wall_shear_work, wall_impact_energy;
    /// The same per mesh triangle [J], the shear work per particle type
    /// (type-major: [type * n_triangles + t]), and Archard's sum of normal
    /// force times slip distance [N m], per type.
    std::vector<double> triangle_impact_energy, triangle_shear_work, triangle_load_slip;

    /// The sums as numbers for a checkpoint (per wall the shear work and the
    /// impact energy, then the triangles' arrays), and back. Impacts not yet
    /// taken are not state: a scene takes them every step.
    std::vector<double> state() const
    {
      std::vector<double> s;
      for (const auto *a : arrays())
        s.insert(s.end(), a->begin(), a->end());
      for (const double *x : ledger_numbers())
        s.push_back(*x);
      return s;
    }
    /// Returns false (and changes nothing) if the numbers do not fit.
    bool set_state(const std::vector<double> &s)
    {
      std::size_t n = 0;
      for (const auto *a : arrays())
        n += a->size();
      if (s.size() != n + ledger_numbers().size())
        return false;
      auto from = s.begin();
      for (auto *a : arrays())
        {
          std::copy(from, from + a->size(), a->begin());
          from += a->size();
        }
      for (double *x : ledger_numbers())
        *x = *from++;
      return true;
    }

  private:
    std::vector<const std::vector<double> *> arrays() const
    {
      return {&wall_shear_work, &wall_impact_energy, &triangle_impact_energy,
              &triangle_shear_work, &triangle_load_slip, &ledger.wall_tangential_work_by_type};
    }
    std::vector<std::vector<double> *> arrays()
    {
      return {&wall_shear_work, &wall_impact_energy, &triangle_impact_energy,
              &triangle_shear_work, &triangle_load_slip, &ledger.wall_tangential_work_by_type};
    }
    std::vector<double *> ledger_numbers()
    {
      EnergyLedger &l = ledger;
      return {&l.normal_damping[0],    &l.normal_damping[1],  &l.tangential_work[0],
              &l.tangential_work[1],   &l.rolling[0],         &l.rolling[1],
              &l.wall_work,            &l.stored_normal[0],   &l.stored_normal[1],
              &l.stored_tangential[0], &l.stored_tangential[1]};
    }
    std::vector<const double *> ledger_numbers() const
    {
      const EnergyLedger &l = ledger;
      return {&l.normal_damping[0],    &l.normal_damping[1],  &l.tangential_work[0],
              &l.tangential_work[1],   &l.rolling[0],         &l.rolling[1],
              &l.wall_work,            &l.stored_normal[0],   &l.stored_normal[1],
              &l.stored_tangential[0], &l.stored_tangential[1]};
    }
    std::vector<ContactEnergyRecord> pending;
    double                           pass_stored_normal[2] = {0., 0.},
                                     pass_stored_tangential[2] = {0., 0.};

    std::vector<ImpactRecord> impacts;
    unsigned int              n_triangles;
  };
} // namespace sluice
