#include <sluice/dem/ghost_layer.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <map>

namespace sluice
{
  using namespace dealii;

  GhostLayer::GhostLayer(MPI_Comm communicator, const std::array<int, 3> &n_cells,
                                         const std::array<bool, 3> &periodic)
    : communicator(communicator), n_cells(n_cells), periodic(periodic)
  {
    this_rank = Utilities::MPI::this_mpi_process(communicator);
    active_   = Utilities::MPI::n_mpi_processes(communicator) > 1;
  }

  void GhostLayer::set_owners(const std::vector<int> &owner)
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
                    bool outside = false;
                    for (unsigned int d = 0; d < 3; ++d)
                      if (c[d] < 0 || c[d] >= n_cells[d])
                        {
                          outside = outside || !periodic[d];
                          c[d]    = (c[d] + n_cells[d]) % n_cells[d];
                        }
                    if (outside)
                      continue;
                    const int r = owner[c[0] + nx * (c[1] + ny * c[2])];
                    if (r != this_rank && std::find(ranks.begin(), ranks.end(), r) == ranks.end())
                      ranks.push_back(r);
                  }
            std::sort(ranks.begin(), ranks.end());
          }
  }

  std::vector<double>
  GhostLayer::exchange(const std::vector<Send> &sends, const unsigned int record_size,
                       const std::function<void(unsigned int, double *)> &pack)
  {
    sent.clear();
    received.clear();
    n_ghosts_ = 0;
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

    std::vector<double> ghosts;
    for (const auto &[rank, buffer] : arrived)
      if (!buffer.empty())
        {
          ghosts.insert(ghosts.end(), buffer.begin(), buffer.end());
          received.emplace_back(rank, buffer.size() / record_size);
        }
    n_ghosts_ = ghosts.size() / record_size;
    for (auto &[rank, h] : handles)
      sent.emplace_back(rank, std::move(h));
    return ghosts;
  }

  void GhostLayer::refresh(const unsigned int                                       n_values,
                                   const std::function<void(unsigned int, double *)>       &pack,
                                   const std::function<void(unsigned int, const double *)> &unpack)
  {
    if (sent.empty() && received.empty())
      return;
    // A tag of its own: the handler's messages on the same communicator
    // never match these.
    constexpr int tag = 0x51ce;
    std::vector<std::vector<double>> &out = send_buffers, &in = receive_buffers;
    out.resize(sent.size());
    in.resize(received.size());
    requests.resize(out.size() + in.size());
    for (unsigned int s = 0; s < received.size(); ++s)
      {
        in[s].resize(received[s].second * n_values);
        MPI_Irecv(in[s].data(), in[s].size(), MPI_DOUBLE, received[s].first, tag, communicator,
                  &requests[s]);
      }
    for (unsigned int s = 0; s < sent.size(); ++s)
      {
        const std::vector<unsigned int> &handles = sent[s].second;
        out[s].resize(handles.size() * n_values);
        for (unsigned int m = 0; m < handles.size(); ++m)
          pack(handles[m], out[s].data() + m * n_values);
        MPI_Isend(out[s].data(), out[s].size(), MPI_DOUBLE, sent[s].first, tag, communicator,
                  &requests[in.size() + s]);
      }
    MPI_Waitall(requests.size(), requests.data(), MPI_STATUSES_IGNORE);
    unsigned int k = 0;
    for (unsigned int s = 0; s < received.size(); ++s)
      for (unsigned int m = 0; m < received[s].second; ++m)
        unpack(k++, in[s].data() + m * n_values);
  }
} // namespace sluice
