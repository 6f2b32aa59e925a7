#pragma once
// The box that holds the particles, and what periodicity does to distances in it.

#include <sluice/core/vector3.h>

#include <array>

namespace sluice
{
  struct PeriodicBox
  {
    Vec3                lower, upper, length;
    std::array<bool, 3> periodic{{false, false, false}};
    bool                any_periodic = false;

    PeriodicBox() = default;
    PeriodicBox(const Vec3 &lo, const Vec3 &hi, const std::array<bool, 3> &per)
      : lower(lo), upper(hi), length(hi - lo), periodic(per)
      , any_periodic(per[0] || per[1] || per[2])
    {}

    /// The shortest periodic image of a separation vector. Positions are wrapped
    /// back into the box at every neighbour-list rebuild and move less than half the
    /// skin in between, so one correction per direction suffices.
    Vec3 minimum_image(Vec3 d) const
    {
      for (unsigned int k = 0; k < 3; ++k)
        if (periodic[k])
          {
            if (d[k] > 0.5 * length[k])
              d[k] -= length[k];
            else if (d[k] < -0.5 * length[k])
              d[k] += length[k];
          }
      return d;
    }

    /// Whether a (wrapped) position lies in the box.
    bool contains(const Vec3 &x) const
    {
      return x.x >= lower.x && x.x <= upper.x && x.y >= lower.y && x.y <= upper.y &&
             x.z >= lower.z && x.z <= upper.z;
    }

    /// Maps a position back into the box along the periodic directions.
    Vec3 wrap(Vec3 x) const
    {
      for (unsigned int k = 0; k < 3; ++k)
        if (periodic[k])
          {
            while (x[k] >= upper[k])
              x[k] -= length[k];
            while (x[k] < lower[k])
              x[k] += length[k];
          }
      return x;
    }
  };
} // namespace sluice
