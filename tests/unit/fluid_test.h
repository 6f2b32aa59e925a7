#pragma once
// What the fluid solver's unit tests share: the scene file named on the
// command line, and one line per check printed by rank 0 ("ok" or "FAILED",
// the measured value), counted so that main() can return non-zero.

#include <sluice/core/scene_parameters.h>

#include <deal.II/base/mpi.h>

#include <cstdio>
#include <cstdlib>

namespace sluice::unit
{
  /// The scene file argv[1]; without one, prints the usage and exits with 1.
  inline SceneParameters scene_argument(const int argc, char **argv, const char *usage)
  {
    if (argc != 2)
      {
        std::printf("usage: %s\n", usage);
        std::exit(1);
      }
    return read_scene_parameters(argv[1]);
  }

  class RootReport
  {
  public:
    explicit RootReport(MPI_Comm comm)
      : root(dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    {}
    void operator()(const bool ok, const char *what, const double value)
    {
      if (root)
        std::printf("%s %s: %.3e\n", ok ? "ok    " : "FAILED", what, value);
      failures += ok ? 0 : 1;
    }
    int exit_code() const { return failures == 0 ? 0 : 1; }

  private:
    bool root;
    int  failures = 0;
  };
} // namespace sluice::unit
