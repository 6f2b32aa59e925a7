#pragma once
// Collective: which rank holds the least (or the greatest) of one number per
// rank, and that rank's record on every rank: the worst particle of a state
// check, the SPH step's tightest bound, the vertex nearest the pressure
// reference. Ties go to the lowest rank (MPI_MINLOC and MPI_MAXLOC).

#include <mpi.h>

namespace sluice
{
  /// The extreme value over the ranks, and the (lowest) rank holding it.
  struct RankedValue
  {
    double value;
    int    rank;
  };

  inline RankedValue ranked_extremum(const double mine, const MPI_Op op, const MPI_Comm comm)
  {
    RankedValue local{mine, 0}, global{};
    MPI_Comm_rank(comm, &local.rank);
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, op, comm);
    return global;
  }

  inline RankedValue rank_of_least(const double mine, const MPI_Comm comm)
  {
    return ranked_extremum(mine, MPI_MINLOC, comm);
  }

  inline RankedValue rank_of_greatest(const double mine, const MPI_Comm comm)
  {
    return ranked_extremum(mine, MPI_MAXLOC, comm);
  }

  /// The n numbers of `record` as rank `from` holds them, on every rank.
  inline void share_from(const int from, double *record, const int n, const MPI_Comm comm)
  {
    MPI_Bcast(record, n, MPI_DOUBLE, from, comm);
  }
} // namespace sluice
