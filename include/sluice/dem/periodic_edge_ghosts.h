#pragma once
// Ghost particles across the edges and corners of a periodic box, on several
// MPI ranks.
//
// deal.II 9.4's ParticleHandler sends a ghost to the ranks whose ghost cells
// share a vertex with the particle's cell. Across a periodic boundary it
// matches each vertex with one image only, so where two or three periodic
// directions meet (an edge or a corner of the box) a rank that is a neighbour
// only across that edge or corner gets no ghost, and contacts across it are
// lost. (With one periodic direction it was seen to miss some neighbours across
// the periodic face too, so this runs whenever a direction is periodic: see
// doc/dem.md §8.) The DEM's coarse mesh is a structured box of cells at least one
// interaction range wide, so a cell's neighbours are known without the mesh:
// this class sends a copy of every particle in a cell to each other rank that
// owns one of the cell's 26 neighbours across a periodic boundary, keeps only
// those the handler did not deliver (the receiver tells the sender which), and
// refreshes the kept ones every step with plain point-to-point messages.

#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace sluice
{
  class PeriodicEdgeGhosts
  {
  public:
    PeriodicEdgeGhosts(MPI_Comm communicator, const std::array<int, 3> &n_cells,
                       const std::array<bool, 3> &periodic);

    /// Several ranks and at least one periodic direction; otherwise every
    /// call below does nothing.
    bool active() const { return active_; }

    /// The owning rank of every cell, by lexicographic index
    /// i + n_x (j + n_y k). Call again whenever the cells are repartitioned.
    void set_owners(const std::vector<int> &owner);

    /// The other ranks that own a neighbour of cell `lex` across a periodic
    /// boundary (empty for most cells).
    const std::vector<int> &partners_of(const unsigned int lex) const { return partners[lex]; }

    /// A particle to send: its owner's handle for it (the index refresh()
    /// passes back) and the rank to send it to.
    struct Send
    {
      unsigned int handle;
      int          rank;
    };

    /// Collective. Sends a record of `record_size` doubles, written by
    /// pack(handle, record) and starting with the particle's id, for every
    /// entry of `sends`; drops the records whose id is already_here(), tells
    /// their senders, and returns the others (concatenated), ordered by
    /// sending rank and then as sent.
    std::vector<double> exchange(const std::vector<Send> &sends, unsigned int record_size,
                                 const std::function<void(unsigned int, double *)> &pack,
                                 const std::function<bool(std::uint64_t)> &already_here);

    /// The number of records the last exchange() returned.
    unsigned int n_kept() const { return n_kept_; }

    /// Refreshes the kept ghosts: pack(handle, values) writes `n_values`
    /// doubles of an owned particle; unpack(k, values) reads them into the
    /// k-th record exchange() returned.
    void refresh(unsigned int                                         n_values,
                 const std::function<void(unsigned int, double *)>       &pack,
                 const std::function<void(unsigned int, const double *)> &unpack);

  private:
    MPI_Comm                      communicator;
    bool                          active_ = false;
    int                           this_rank = 0;
    std::array<int, 3>            n_cells;
    std::array<bool, 3>           periodic;
    std::vector<std::vector<int>> partners; // by cell
    // Since the last exchange(): the handles sent to each rank and kept
    // there, and how many kept records came from each rank (both in order).
    std::vector<std::pair<int, std::vector<unsigned int>>> kept_sends;
    std::vector<std::pair<int, unsigned int>>              kept_receives;
    unsigned int                                           n_kept_ = 0;
    // refresh()'s messages, kept to spare an allocation per step.
    std::vector<std::vector<double>> send_buffers, receive_buffers;
    std::vector<MPI_Request>         requests;
  };
} // namespace sluice
