#pragma once
// The one-line progress report: simulated time, percent done, steps/s,
// particles, wall time and ETA. On a terminal the line is redrawn in place twice a
// second; into a file or pipe a new line is written every 10% of the run.

#include <chrono>

namespace sluice
{
  class ProgressLine
  {
  public:
    ProgressLine(bool enabled, double end_time);

    /// Cheap test whether a new line is due (checks the clock every 64 calls).
    bool due();
    void update(double time, unsigned long long step, unsigned long long n_particles);
    void finish();

  private:
    bool                                  enabled, terminal;
    double                                end_time;
    std::chrono::steady_clock::time_point start, last;
    unsigned long long                    calls = 0;
    int                                   last_decile = 0;
    double                                next_fraction = 0.1;
    bool                                  drawn = false;
  };
} // namespace sluice
