// The .pvd and .csv series (see the header).

#include <sluice/core/output_files.h>
#include <sluice/core/series_files.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace sluice
{
  void PvdSeries::add(const double time, const std::string &file)
  {
    records.emplace_back(time, file);
    if (!writes)
      return;
    std::ostringstream pvd;
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
        << "  <Collection>\n";
    for (const auto &[t, name] : records)
      pvd << "    <DataSet timestep=\"" << std::setprecision(10) << t
          << "\" group=\"\" part=\"0\" file=\"" << name << "\"/>\n";
    pvd << "  </Collection>\n</VTKFile>\n";
    write_file_atomically(path, pvd.str());
  }

  std::vector<std::string> PvdSeries::to_text() const
  {
    std::vector<std::string> lines;
    for (const auto &[t, name] : records)
      {
        std::ostringstream line;
        line << std::setprecision(17) << t << ' ' << name;
        lines.push_back(line.str());
      }
    return lines;
  }

  void PvdSeries::restore(const std::vector<std::string> &lines)
  {
    records.clear();
    for (const auto &line : lines)
      {
        std::istringstream in(line);
        double             t;
        std::string        name;
        if (in >> t >> name)
          records.emplace_back(t, name);
      }
  }

  void CsvSeries::open(const std::string &file, const std::string &header, const bool write,
                       const bool continuing, const double restart_time)
  {
    path   = file;
    writes = write;
    if (!writes)
      return;
    std::string kept;
    if (continuing && std::filesystem::exists(path))
      {
        std::ifstream earlier(path);
        std::string   line;
        while (std::getline(earlier, line))
          {
            // The header, then whole rows up to the checkpoint's time (a row
            // cut by a kill has fewer fields and is dropped). Rows hold 10
            // digits: the checkpoint's own row may read up to 5e-10 above it.
            char        *end  = nullptr;
            const double time = std::strtod(line.c_str(), &end);
            if (kept.empty())
              kept = line + '\n';
            else if (end != line.c_str() && time <= restart_time * (1. + 1e-9) &&
                     std::count(line.begin(), line.end(), ',') ==
                       std::count(header.begin(), header.end(), ','))
              kept += line + '\n';
          }
      }
    if (kept.empty())
      kept = header + '\n';
    write_file_atomically(path, kept);
    out.open(path, std::ios::app);
    check_stream(out, path);
    out << std::setprecision(10);
  }

  void CsvSeries::end_row()
  {
    if (!writes)
      return;
    // Each row whole on disk: a killed run leaves a readable series.
    out << '\n' << std::flush;
    check_stream(out, path);
  }
} // namespace sluice
