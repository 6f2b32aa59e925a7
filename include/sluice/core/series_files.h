#pragma once
// The two kinds of time series every scene writes, one implementation each:
//   - a ParaView collection (.pvd) that lists snapshot files with their times,
//     replaced whole at every snapshot (a reader or a kill -9 never sees half
//     of it);
//   - a .csv of one row per output time, each row flushed whole.
// Both continue after a restart: the .pvd from the records a checkpoint kept,
// the .csv from its rows up to the checkpoint's time (rows a killed run wrote
// after it are dropped: they are computed again).

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace sluice
{
  class PvdSeries
  {
  public:
    /// 'path' is the .pvd file; 'write' is false on the ranks that do not write.
    PvdSeries(std::string path, bool write) : path(std::move(path)), writes(write) {}

    /// Adds a snapshot (its file name relative to the .pvd) and rewrites the index.
    void add(double time, const std::string &file);

    unsigned int size() const { return records.size(); }

    /// The records as text (one 'time file' each) for a checkpoint, and back.
    std::vector<std::string> to_text() const;
    void                     restore(const std::vector<std::string> &lines);

  private:
    std::string                                 path;
    bool                                        writes;
    std::vector<std::pair<double, std::string>> records;
  };

  class CsvSeries
  {
  public:
    /// Opens 'path' (on the writing rank only) with its header line, or, when
    /// continuing a restarted run, keeps the header and the rows up to
    /// 'restart_time' of the existing file. Throws OutputError.
    void open(const std::string &path, const std::string &header, bool write,
              bool continuing = false, double restart_time = 0.);

    bool is_open() const { return writes; }

    /// The stream for one row; end it with end_row().
    std::ofstream &row() { return out; }
    /// Ends the row and flushes it whole. Throws OutputError.
    void end_row();

  private:
    std::string   path;
    bool          writes = false;
    std::ofstream out;
  };
} // namespace sluice
