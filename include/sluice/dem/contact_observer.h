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
    unsigned int  type;    // its material type
    unsigned int  partner; // the other particle's type, or the wall's index
    bool          wall;
    double        energy;  // 1/2 m_eff v_n^2 at the start [J]
  };

  class ContactObserver
  {
  public:
    explicit ContactObserver(unsigned int n_walls = 0)
      : wall_shear_work(n_walls, 0.), wall_impact_energy(n_walls, 0.)
    {}

    /// The impacts since the last call, handed over and forgotten.
    std::vector<ImpactRecord> take_impacts()
    {
      std::vector<ImpactRecord> out;
      out.swap(impacts);
      return out;
    }

    // ---- Called by the contact kernel ----
    void impact(const std::uint64_t id, const unsigned int type, const unsigned int partner,
                const bool wall, const double energy)
    {
      impacts.push_back({id, type, partner, wall, energy});
      if (wall)
        wall_impact_energy[partner] += energy;
    }
    void wall_shear(const unsigned int wall, const double work) { wall_shear_work[wall] += work; }

    /// Cumulative on this rank since the start [J]: the shear work -F_t . v_t dt
    /// done on the particles at each wall (positive: dissipated), and the
    /// normal impact energy each wall received.
    std::vector<double> wall_shear_work, wall_impact_energy;

    /// The sums as numbers for a checkpoint (the shear work, then the impact
    /// energy, per wall), and back. Impacts not yet taken are not state: a
    /// scene takes them every step.
    std::vector<double> state() const
    {
      std::vector<double> s(wall_shear_work);
      s.insert(s.end(), wall_impact_energy.begin(), wall_impact_energy.end());
      return s;
    }
    /// Returns false (and changes nothing) if the numbers do not fit the walls.
    bool set_state(const std::vector<double> &s)
    {
      const std::size_t n = wall_shear_work.size();
      if (s.size() != 2 * n)
        return false;
      wall_shear_work.assign(s.begin(), s.begin() + n);
      wall_impact_energy.assign(s.begin() + n, s.end());
      return true;
    }

  private:
    std::vector<ImpactRecord> impacts;
  };
} // namespace sluice
