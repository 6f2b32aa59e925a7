#pragma once
// The ghost particles of one MPI rank: copies of the particles that other
// ranks own in the cells next to this rank's cells, built at every
// neighbour-list rebuild and refreshed every step.
//
// The DEM's coarse mesh is a structured box of cells at least one interaction
// range wide (particle_exchange.h), so a cell's 26 neighbours, wrapped where
// the box is periodic, are known without the mesh. Every rank sends a record of
// each particle in a cell to each other rank that owns one of the cell's
// neighbours; between rebuilds it sends only what changes (position and
// velocities) to the same ranks, in the same order, by point-to-point messages.
//
// deal.II 9.4's ParticleHandler has a ghost exchange of its own, but it sends
// every property of every ghost (a particle's contact data among them) at each
// refresh, and across a periodic boundary it matches each vertex with one image
// only, so where two or three periodic directions meet (an edge or a corner of
// the box) a rank that is a neighbour only across that edge or corner gets no
// ghost (doc/dem.md §8). This layer replaces it.

#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace sluice
{
  class GhostLayer
  {
  public:
    GhostLayer(MPI_Comm communicator, const std::array<int, 3> &n_cells,
               const std::array<bool, 3> &periodic);

    /// Several ranks; on one rank every call below does nothing.
    bool active() const { return active_; }

    /// The owning rank of every cell, by lexicographic index
    /// i + n_x (j + n_y k). Call again whenever the cells are repartitioned.
    void set_owners(const std::vector<int> &owner);

    /// The other ranks that own a neighbour of cell `lex` (this rank's).
    const std::vector<int> &partners_of(const unsigned int lex) const { return partners[lex]; }

    /// A particle to send: its owner's handle for it (the index refresh()
    /// passes back) and the rank to send it to.
    struct Send
    {
      unsigned int handle;
      int          rank;
    };

    /// Collective. Sends a record of `record_size` doubles, written by
    /// pack(handle, record), for every entry of `sends`, and returns the
    /// records that arrived (concatenated), ordered by sending rank and then
    /// as sent.
    std::vector<double> exchange(const std::vector<Send> &sends, unsigned int record_size,
                                 const std::function<void(unsigned int, double *)> &pack);

    /// The number of records the last exchange() returned.
    unsigned int n_ghosts() const { return n_ghosts_; }

    /// Refreshes the ghosts: pack(handle, values) writes `n_values` doubles of
    /// an owned particle; unpack(k, values) reads them into the k-th record
    /// exchange() returned.
    void refresh(unsigned int                                             n_values,
                 const std::function<void(unsigned int, double *)>       &pack,
                 const std::function<void(unsigned int, const double *)> &unpack);

  private:
    MPI_Comm                      communicator;
    bool                          active_   = false;
    int                           this_rank = 0;
    std::array<int, 3>            n_cells;
    std::array<bool, 3>           periodic;
    std::vector<std::vector<int>> partners; // by cell
    // Since the last exchange(): the handles sent to each rank, and how many
    // records came from each rank (both in order).
    std::vector<std::pair<int, std::vector<unsigned int>>> sent;
    std::vector<std::pair<int, unsigned int>>              received;
    unsigned int                                           n_ghosts_ = 0;
    // refresh()'s messages, kept to spare an allocation per step.
    std::vector<std::vector<double>> send_buffers, receive_buffers;
    std::vector<MPI_Request>         requests;
  };
} // namespace sluice
