#pragma once
// Output files that are never silently lost, mixed or half-written.
//
// The output directory is created and tested for writing before the first
// step; a directory that already holds an earlier run's series is handled as
// 'output/if exists' says (stop, overwrite, or a new directory). Series
// indices (.pvd) are replaced atomically, so a reader or a kill -9 never sees
// half of one, and every write checks its stream.

#include <mpi.h>

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace sluice
{
  /// A file that could not be written during the run (exit 6); names the path.
  class OutputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  enum class IfOutputExists
  {
    stop,         // refuse the run, touch nothing
    overwrite,    // remove the earlier series of these base names, then write
    new_directory // write into <directory>-2, -3, ... instead
  };

  /// Collective. Creates 'directory', checks that files can be created in it,
  /// and looks for an earlier run's files '<base>.pvd' or '<base>.csv' for each
  /// base name. Returns the directory to write into (another one for
  /// new_directory). 'continuing' (a restart) keeps the earlier series. Throws
  /// InputError (exit 2, nothing written) naming the path and the reason.
  std::string prepare_output_directory(const std::string &directory,
                                       const std::vector<std::string> &base_names,
                                       IfOutputExists policy, bool continuing,
                                       const std::string &file_name, MPI_Comm comm,
                                       const std::string &entry = "output/directory");

  /// Writes 'content' to a temporary file next to 'path' and renames it over
  /// 'path'. Throws OutputError.
  void write_file_atomically(const std::string &path, const std::string &content);

  /// Throws OutputError naming 'path' if the stream failed (disk full, ...).
  void check_stream(const std::ostream &stream, const std::string &path);
} // namespace sluice
