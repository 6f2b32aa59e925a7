#pragma once
// Collective: every rank's values, concatenated in rank order, on every rank:
// a stream's outlet list, an imported field check's initial states, the
// self-induced correction's per-particle records once per coupling step.

#include <mpi.h>

#include <vector>

namespace sluice
{
  inline std::vector<double> gathered(const std::vector<double> &mine, MPI_Comm comm)
  {
    int n_ranks;
    MPI_Comm_size(comm, &n_ranks);
    int              n = mine.size();
    std::vector<int> counts(n_ranks), offsets(n_ranks, 0);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    for (int r = 1; r < n_ranks; ++r)
      offsets[r] = offsets[r - 1] + counts[r - 1];
    std::vector<double> all(offsets.back() + counts.back());
    MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, comm);
    return all;
  }
} // namespace sluice
