// Output directory set-up and safe file writes (see the header).

#include <sluice/core/output_files.h>
#include <sluice/core/scene_parameters.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>

namespace sluice
{
  namespace fs = std::filesystem;

  namespace
  {
    /// The earlier run's series files of these base names in 'directory'.
    std::vector<std::string> earlier_series(const fs::path &directory,
                                            const std::vector<std::string> &base_names)
    {
      std::vector<std::string> found;
      std::error_code          ec;
      for (const auto &base : base_names)
        for (const char *ext : {".pvd", ".csv"})
          if (fs::exists(directory / (base + ext), ec))
            found.push_back(base + ext);
      return found;
    }

    /// Removes '<base>.pvd', '<base>.csv' and '<base>_*' (the snapshots).
    void remove_series(const fs::path &directory, const std::vector<std::string> &base_names)
    {
      for (const auto &entry : fs::directory_iterator(directory))
        {
          const std::string name = entry.path().filename().string();
          for (const auto &base : base_names)
            if (name == base + ".pvd" || name == base + ".csv" ||
                name.rfind(base + "_", 0) == 0)
              fs::remove_all(entry.path());
        }
    }

    /// Creates the directory and a probe file in it; "" on success, else why not.
    std::string make_writable(const fs::path &directory)
    {
      std::error_code ec;
      fs::create_directories(directory, ec);
      if (ec)
        return "it cannot be created (" + ec.message() + ")";
      if (!fs::is_directory(directory, ec))
        return "it exists and is not a directory";
      const fs::path probe = directory / ".sluice-write-test";
      {
        std::ofstream f(probe);
        f << "probe\n";
        f.flush();
        if (!f)
          return std::string("no file can be written in it (") + std::strerror(errno) + ")";
      }
      fs::remove(probe, ec);
      return "";
    }

    std::string prepare_on_root(const std::string &directory,
                                const std::vector<std::string> &base_names,
                                const IfOutputExists policy, const bool continuing,
                                const std::string &file_name, const std::string &entry,
                                std::string &chosen)
    {
      const std::string where =
        "error in '" + file_name + "': entry '" + entry + "' = '" + directory + "': ";
      chosen = directory;
      try
        {
          std::vector<std::string> earlier = earlier_series(directory, base_names);
          if (!earlier.empty() && !continuing)
            {
              if (policy == IfOutputExists::stop)
                {
                  std::string list;
                  for (const auto &f : earlier)
                    list += (list.empty() ? "" : ", ") + f;
                  return where + "it holds an earlier run's output (" + list +
                         "); remove it, or set 'output/if exists' to 'overwrite' or 'new'";
                }
              if (policy == IfOutputExists::new_directory)
                for (unsigned int k = 2;; ++k)
                  {
                    chosen = directory + "-" + std::to_string(k);
                    if (earlier_series(chosen, base_names).empty())
                      break;
                  }
            }
          const std::string why = make_writable(chosen);
          if (!why.empty())
            return "error in '" + file_name + "': entry '" + entry + "': '" + chosen + "': " + why;
          if (!earlier.empty() && !continuing && policy == IfOutputExists::overwrite)
            remove_series(chosen, base_names);
        }
      catch (const fs::filesystem_error &e)
        {
          return where + e.what();
        }
      return "";
    }

    void broadcast(std::string &text, MPI_Comm comm)
    {
      unsigned long n = text.size();
      MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, comm);
      text.resize(n);
      MPI_Bcast(text.data(), n, MPI_CHAR, 0, comm);
    }
  } // namespace

  std::string prepare_output_directory(const std::string &directory,
                                       const std::vector<std::string> &base_names,
                                       const IfOutputExists policy, const bool continuing,
                                       const std::string &file_name, MPI_Comm comm,
                                       const std::string &entry)
  {
    int rank;
    MPI_Comm_rank(comm, &rank);
    std::string error, chosen = directory;
    if (rank == 0)
      error =
        prepare_on_root(directory, base_names, policy, continuing, file_name, entry, chosen);
    broadcast(error, comm);
    broadcast(chosen, comm);
    if (!error.empty())
      throw InputError(error);
    return chosen;
  }

  void write_file_atomically(const std::string &path, const std::string &content)
  {
    const std::string tmp = path + ".tmp";
    {
      std::ofstream f(tmp);
      f << content;
      f.flush();
      check_stream(f, tmp);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw OutputError("cannot replace '" + path + "' (" + std::strerror(errno) + ")");
  }

  void check_stream(const std::ostream &stream, const std::string &path)
  {
    if (!stream)
      throw OutputError("cannot write '" + path + "' (" + std::strerror(errno) + ")");
  }
} // namespace sluice
