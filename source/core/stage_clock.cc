#include <sluice/core/stage_clock.h>

#include <iomanip>
#include <numeric>
#include <sstream>

namespace sluice
{
  StageClock::StageClock(std::vector<std::string> stage_names)
    : names(std::move(stage_names)), seconds(names.size(), 0.),
      last(std::chrono::steady_clock::now())
  {}

  void StageClock::start() { last = std::chrono::steady_clock::now(); }

  void StageClock::lap(const unsigned int stage)
  {
    const auto now = std::chrono::steady_clock::now();
    seconds.at(stage) += std::chrono::duration<double>(now - last).count();
    last = now;
  }

  std::string StageClock::per_step_ms(const unsigned long long n_steps) const
  {
    const double       to_ms = n_steps > 0 ? 1e3 / n_steps : 0.;
    std::ostringstream out;
    out << std::setprecision(4);
    for (std::size_t s = 0; s < names.size(); ++s)
      out << names[s] << '=' << seconds[s] * to_ms << ' ';
    out << "total=" << std::accumulate(seconds.begin(), seconds.end(), 0.) * to_ms;
    return out.str();
  }
} // namespace sluice
