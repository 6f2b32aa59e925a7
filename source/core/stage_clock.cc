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

  std::string StageClock::line(const double count, const double scale) const
  {
    const double       factor = count > 0. ? scale / count : 0.;
    std::ostringstream out;
    out << std::setprecision(4);
    for (std::size_t s = 0; s < names.size(); ++s)
      out << names[s] << '=' << seconds[s] * factor << ' ';
    out << "total=" << std::accumulate(seconds.begin(), seconds.end(), 0.) * factor;
    return out.str();
  }
} // namespace sluice
