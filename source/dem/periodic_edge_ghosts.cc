#include <sluice/dem/periodic_edge_ghosts.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <map>

namespace sluice
{
  using namespace dealii;

  PeriodicEdgeGhosts::PeriodicEdgeGhosts(MPI_Comm communicator, const std::array<int, 3> &n_cells,
                                         const std::array<bool, 3> &periodic)
    : communicator(communicator), n_cells(n_cells), periodic(periodic)
  {
    this_rank = Utilities::MPI::this_mpi_process(communicator);
    active_   = Utilities::MPI::n_mpi_processes(communicator) > 1 &&
              (periodic[0] || periodic[1] || periodic[2]);
  }

  void PeriodicEdgeGhosts::set_owners(const std::vector<int> &owner)
  {
    if (!active_)
      return;
    partners.assign(owner.size(), {});
    const int nx = n_cells[0], ny = n_cells[1], nz = n_cells[2];
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          {
            const unsigned int lex = i + nx * (j + ny * k);
            if (owner[lex] != this_rank)
              continue;
            std::vector<int> &ranks = partners[lex];
            for (int dk = -1; dk <= 1; ++dk)
              for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di)
                  {
                    // The neighbour's index, wrapped where the box is periodic.
                    int  c[3]    = {i + di, j + dj, k + dk};
                    bool crossed = false, outside = false;
                    for (unsigned int d = 0; d < 3; ++d)
                      if (c[d] < 0 || c[d] >= n_cells[d])
                        {
                          crossed = true;
                          outside = outside || !periodic[d];
                          c[d]    = (c[d] + n_cells[d]) % n_cells[d];
                        }
                    if (!crossed || outside)
                      continue;
                    const int r = owner[c[0] + nx * (c[1] + ny * c[2])];
                    if (r != this_rank && std::find(ranks.begin(), ranks.end(), r) == ranks.end())
                      ranks.push_back(r);
                  }
            std::sort(ranks.begin(), ranks.end());
          }
  }

  std::vector<double>
  PeriodicEdgeGhosts::exchange(const std::vector<Send> &sends, const unsigned int record_size,
                               const std::function<void(unsigned int, double *)> &pack,
                               const std::function<bool(std::uint64_t)>          &already_here)
  {
    kept_sends.clear();
    kept_receives.clear();
    n_kept_ = 0;
    if (!active_)
      return {};

    // The records, and the handles in the order sent, by destination.
    std::map<unsigned int, std::vector<double>>       records;
    std::map<unsigned int, std::vector<unsigned int>> handles;
    for (const Send &s : sends)
      {
        std::vector<double> &buffer = records[s.rank];
        buffer.resize(buffer.size() + record_size);
        pack(s.handle, buffer.data() + buffer.size() - record_size);
        handles[s.rank].push_back(s.handle);
      }
    const std::map<unsigned int, std::vector<double>> arrived =
      Utilities::MPI::some_to_some(communicator, records);

    // Keep what the handler did not deliver; answer each sender with the
    // positions (in its message) of the records dropped here.
    std::vector<double>                         kept;
    std::map<unsigned int, std::vector<double>> dropped;
    for (const auto &[rank, buffer] : arrived)
      {
        std::vector<double> &dropped_here = dropped[rank];
        const unsigned int   n            = buffer.size() / record_size;
        unsigned int         n_from_rank  = 0;
        for (unsigned int m = 0; m < n; ++m)
          {
            const double *record = buffer.data() + m * record_size;
            if (already_here(static_cast<std::uint64_t>(record[0])))
              dropped_here.push_back(m);
            else
              {
                kept.insert(kept.end(), record, record + record_size);
                ++n_from_rank;
              }
          }
        if (n_from_rank > 0)
          kept_receives.emplace_back(rank, n_from_rank);
      }
    n_kept_ = kept.size() / record_size;

    const std::map<unsigned int, std::vector<double>> answers =
      Utilities::MPI::some_to_some(communicator, dropped);
    for (auto &[rank, sent] : handles)
      {
        std::vector<unsigned int> still;
        const auto                answer = answers.find(rank);
        for (unsigned int m = 0; m < sent.size(); ++m)
          if (answer == answers.end() ||
              !std::binary_search(answer->second.begin(), answer->second.end(),
                                  static_cast<double>(m)))
            still.push_back(sent[m]);
        if (!still.empty())
          kept_sends.emplace_back(rank, std::move(still));
      }
    return kept;
  }

  void PeriodicEdgeGhosts::refresh(const unsigned int                                       n_values,
                                   const std::function<void(unsigned int, double *)>       &pack,
                                   const std::function<void(unsigned int, const double *)> &unpack)
  {
    if (kept_sends.empty() && kept_receives.empty())
      return;
    // A tag of its own: the handler's messages on the same communicator
    // never match these.
    constexpr int tag = 0x51ce;
    std::vector<std::vector<double>> &out = send_buffers, &in = receive_buffers;
    out.resize(kept_sends.size());
    in.resize(kept_receives.size());
    requests.resize(out.size() + in.size());
    for (unsigned int s = 0; s < kept_receives.size(); ++s)
      {
        in[s].resize(kept_receives[s].second * n_values);
        MPI_Irecv(in[s].data(), in[s].size(), MPI_DOUBLE, kept_receives[s].first, tag, communicator,
                  &requests[s]);
      }
    for (unsigned int s = 0; s < kept_sends.size(); ++s)
      {
        const std::vector<unsigned int> &sent = kept_sends[s].second;
        out[s].resize(sent.size() * n_values);
        for (unsigned int m = 0; m < sent.size(); ++m)
          pack(sent[m], out[s].data() + m * n_values);
        MPI_Isend(out[s].data(), out[s].size(), MPI_DOUBLE, kept_sends[s].first, tag, communicator,
                  &requests[in.size() + s]);
      }
    MPI_Waitall(requests.size(), requests.data(), MPI_STATUSES_IGNORE);
    unsigned int k = 0;
    for (unsigned int s = 0; s < kept_receives.size(); ++s)
      for (unsigned int m = 0; m < kept_receives[s].second; ++m)
        unpack(k++, in[s].data() + m * n_values);
  }
} // namespace sluice
