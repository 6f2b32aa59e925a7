#pragma once
// A run that cannot go on: the particles (SimulationFailure, exit 5) or the
// fluid solver (SolverFailure, exit 4). Every rank throws it at the same step,
// since the checks that raise it reduce over the ranks first; so a scene may
// catch it, write its state at the stop (collectively), name those files in
// the exception, and pass it on. A user then opens the state that failed
// instead of running the scene again to see it.

#include <stdexcept>
#include <string>
#include <vector>

namespace sluice
{
  class RunStopped : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;

    /// What the scene wrote at the stop (stop_note()), printed after the
    /// message; empty when it writes nothing.
    std::string written_at_stop;
  };

  /// "the state at the stop (t = <time> s) is the last entry of A, B and C",
  /// or "" when 'written' is empty.
  std::string stop_note(double time, const std::vector<std::string> &written);

  /// A run whose particles cannot go on (exit 5): a non-finite state, an
  /// overlap beyond the stated bound, a particle too fast for its step. The
  /// message names the particle, the step and the likely cause; the output
  /// already written stays.
  class SimulationFailure : public RunStopped
  {
  public:
    using RunStopped::RunStopped;
  };
} // namespace sluice
