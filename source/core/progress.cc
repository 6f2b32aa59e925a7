#include <sluice/core/progress.h>

#include <unistd.h>

#include <cstdio>

namespace sluice
{
  ProgressLine::ProgressLine(const bool enabled_, const double end_time_)
    : enabled(enabled_)
    , terminal(isatty(fileno(stderr)))
    , end_time(end_time_)
    , start(std::chrono::steady_clock::now())
    , last(start)
  {}

  bool ProgressLine::due()
  {
    if (!enabled || (++calls & 63) != 0)
      return false;
    return true;
  }

  void ProgressLine::update(const double time, const unsigned long long step,
                            const unsigned long long n_particles)
  {
    const auto   now      = std::chrono::steady_clock::now();
    const double fraction = end_time > 0. ? time / end_time : 1.;
    if (terminal)
      {
        if (std::chrono::duration<double>(now - last).count() < 0.5)
          return;
      }
    else if (fraction < next_fraction)
      return;
    else
      while (next_fraction <= fraction)
        next_fraction += 0.1;
    last                = now;
    const double wall_s = std::chrono::duration<double>(now - start).count();
    const double eta    = fraction > 0. ? wall_s * (1. - fraction) / fraction : 0.;
    std::fprintf(stderr,
                 "%st = %.4g s  %5.1f%%  %.4g steps/s  %llu particles  wall %.1f s  ETA %.1f s%s",
                 terminal ? "\r" : "", time, 100. * fraction, step / wall_s, n_particles, wall_s,
                 eta, terminal ? "   " : "\n");
    std::fflush(stderr);
    drawn = true;
  }

  void ProgressLine::finish()
  {
    if (enabled && terminal && drawn)
      std::fprintf(stderr, "\n");
  }
} // namespace sluice
