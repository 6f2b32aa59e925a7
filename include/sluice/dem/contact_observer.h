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
    {}

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
    void wall_shear(const unsigned int wall, const double work) { wall_shear_work[wall] += work; }
    /// A mesh contact's start on triangle t (numbered over all meshes).
    void triangle_impact(const unsigned int t, const double energy)
    {
      triangle_impact_energy[t] += energy;
    }
    /// A mesh contact's shear work in one step, and its normal force times
    /// the slip distance (Archard's load-distance product), by particle type.
    void triangle_shear(const unsigned int t, const unsigned int type, const double work,
                        const double load_slip)
    {
      triangle_shear_work[static_cast<std::size_t>(type) * n_triangles + t] += work;
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
      return s;
    }
    /// Returns false (and changes nothing) if the numbers do not fit.
    bool set_state(const std::vector<double> &s)
    {
      std::size_t n = 0;
      for (const auto *a : arrays())
        n += a->size();
      if (s.size() != n)
        return false;
      auto from = s.begin();
      for (auto *a : arrays())
        {
          std::copy(from, from + a->size(), a->begin());
          from += a->size();
        }
      return true;
    }

  private:
    std::vector<const std::vector<double> *> arrays() const
    {
      return {&wall_shear_work, &wall_impact_energy, &triangle_impact_energy,
              &triangle_shear_work, &triangle_load_slip};
    }
    std::vector<std::vector<double> *> arrays()
    {
      return {&wall_shear_work, &wall_impact_energy, &triangle_impact_energy,
              &triangle_shear_work, &triangle_load_slip};
    }

    std::vector<ImpactRecord> impacts;
    unsigned int              n_triangles;
  };
} // namespace sluice
