// The note a stopped run prints (see the header).

#include <sluice/core/run_stopped.h>
#include <sluice/core/scene_parameters.h>

namespace sluice
{
  std::string stop_note(const double time, const std::vector<std::string> &written)
  {
    if (written.empty())
      return {};
    std::string files;
    for (std::size_t i = 0; i < written.size(); ++i)
      files += (i == 0 ? "" : i + 1 == written.size() ? " and " : ", ") + written[i];
    return "the state at the stop (t = " + to_text(time) + " s) is the last entry of " + files;
  }
} // namespace sluice
