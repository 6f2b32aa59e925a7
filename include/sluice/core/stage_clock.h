#pragma once
// The wall time a repeated step spends in each of its stages, for the cost
// breakdown a scene prints at its end (the 'cost:' line). Each rank measures
// its own; the stages that communicate wait for the slowest rank, so rank 0's
// figures are the run's.

#include <chrono>
#include <string>
#include <vector>

namespace sluice
{
  class StageClock
  {
  public:
    explicit StageClock(std::vector<std::string> stage_names);

    /// Starts the next step's first stage now.
    void start();
    /// Adds the time since the last start() or lap() to 'stage'.
    void lap(unsigned int stage);

    /// "name=<t> ... total=<t>", each stage's seconds times 'scale' divided
    /// by 'count' (ms per step: scale 1e3, count the steps); a count of 0
    /// prints zeros.
    std::string line(double count, double scale) const;

  private:
    std::vector<std::string>              names;
    std::vector<double>                   seconds;
    std::chrono::steady_clock::time_point last;
  };
} // namespace sluice
