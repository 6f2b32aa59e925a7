// VTK unstructured grids (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/core/vtk_xml.h>
#include <sluice/core/vtu_reader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace sluice
{
  namespace
  {
    [[noreturn]] void fail(const std::string &file, const std::string &what)
    {
      throw InputError("error: the VTK file '" + file + "' " + what);
    }

    /// A path given in a file, relative to that file's directory.
    std::string beside(const std::string &file, const std::string &path)
    {
      const std::filesystem::path p(path);
      if (p.is_absolute())
        return path;
      return (std::filesystem::path(file).parent_path() / p).lexically_normal().string();
    }

    std::size_t count(const XmlTag &tag, const std::string &key, const std::string &file)
    {
      const std::string text = tag.attribute(key);
      if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
        fail(file, "has a <Piece> without a valid " + key);
      return std::stoull(text);
    }

    /// The DataArray tags between 'begin' and the end of the tag at 'parent'.
    std::vector<const XmlTag *> arrays_in(const VtkXmlFile &file, const std::size_t parent)
    {
      std::vector<const XmlTag *> arrays;
      const auto                 &tags = file.tags();
      for (std::size_t t = parent + 1; t < tags.size() &&
                                       tags[t].content_begin <= tags[parent].content_end;
           ++t)
        if (tags[t].name == "DataArray")
          arrays.push_back(&tags[t]);
      return arrays;
    }

    std::vector<VtuArray> read_arrays(const VtkXmlFile &file, const std::size_t parent,
                                      const std::size_t n)
    {
      std::vector<VtuArray> out;
      for (const XmlTag *tag : arrays_in(file, parent))
        {
          VtuArray a;
          a.name       = tag->attribute("Name");
          a.components = std::stoul(tag->attribute("NumberOfComponents", "1"));
          a.values     = file.data_array(*tag, n * a.components);
          for (std::size_t i = 0; i < a.values.size(); ++i)
            if (!std::isfinite(a.values[i]))
              fail(file.file_name(), "has a value that is not finite in array '" + a.name +
                                       "' at entry " + std::to_string(i / a.components + 1));
          out.push_back(std::move(a));
        }
      return out;
    }

    /// One <Piece> of a .vtu, starting at tag index 'piece'.
    VtuGrid read_piece(const VtkXmlFile &file, const std::size_t piece)
    {
      const auto        &tags = file.tags();
      const std::string &name = file.file_name();
      const std::size_t  n_points = count(tags[piece], "NumberOfPoints", name);
      const std::size_t  n_cells  = count(tags[piece], "NumberOfCells", name);
      VtuGrid            grid;
      for (std::size_t t = piece + 1;
           t < tags.size() && tags[t].content_begin <= tags[piece].content_end; ++t)
        {
          const std::string &section = tags[t].name;
          if (section == "PointData")
            grid.point_data = read_arrays(file, t, n_points);
          else if (section == "CellData")
            grid.cell_data = read_arrays(file, t, n_cells);
          else if (section == "Points")
            {
              const auto a = read_arrays(file, t, n_points);
              if (a.size() != 1 || a[0].components != 3)
                fail(name, "has no <Points> array of three components");
              for (std::size_t i = 0; i < n_points; ++i)
                grid.points.emplace_back(a[0].values[3 * i], a[0].values[3 * i + 1],
                                         a[0].values[3 * i + 2]);
            }
          else if (section == "Cells")
            {
              for (const XmlTag *tag : arrays_in(file, t))
                {
                  const std::string array = tag->attribute("Name");
                  // The connectivity's length follows from the offsets, which VTK
                  // writes after it: checked below.
                  const std::size_t n = array == "connectivity" ? any_size : n_cells;
                  const std::vector<double> v = file.data_array(*tag, n);
                  if (array == "offsets")
                    grid.offsets.assign(v.begin(), v.end());
                  else if (array == "types")
                    grid.types.assign(v.begin(), v.end());
                  else if (array == "connectivity")
                    grid.connectivity.assign(v.begin(), v.end());
                }
            }
        }
      if (grid.points.size() != n_points || grid.types.size() != n_cells ||
          grid.offsets.size() != n_cells || (n_cells > 0 && grid.connectivity.empty()))
        fail(name, "has a <Piece> without its points, or cells (connectivity, offsets, types)");
      if (n_cells > 0 && grid.connectivity.size() != grid.offsets.back())
        fail(name, "has " + std::to_string(grid.connectivity.size()) +
                     " connectivity entries where its offsets need " +
                     std::to_string(grid.offsets.back()));
      for (std::size_t c = 0; c < n_cells; ++c)
        if ((c > 0 && grid.offsets[c] < grid.offsets[c - 1]) ||
            grid.offsets[c] > grid.connectivity.size())
          fail(name, "has bad offsets at cell " + std::to_string(c + 1));
      for (const std::uint64_t v : grid.connectivity)
        if (v >= n_points)
          fail(name, "has a cell with a point index beyond its " + std::to_string(n_points) +
                       " points");
      return grid;
    }

    /// 'piece' as the grid's first piece, or merged into it.
    void add_piece(VtuGrid &grid, bool &first, const VtuGrid &piece, const std::string &name)
    {
      if (first)
        grid = piece;
      else
        append_grid(grid, piece, name);
      first = false;
    }

    VtuGrid read_vtu(const std::string &file_name)
    {
      const VtkXmlFile file(file_name);
      if (file.root().attribute("type") != "UnstructuredGrid")
        fail(file_name, "is a VTK '" + file.root().attribute("type") +
                          "' file, not an UnstructuredGrid (.vtu)");
      VtuGrid grid;
      bool    first = true;
      for (std::size_t t = 0; t < file.tags().size(); ++t)
        if (file.tags()[t].name == "Piece")
          add_piece(grid, first, read_piece(file, t), file_name);
      if (first)
        fail(file_name, "has no <Piece>");
      return grid;
    }
  } // namespace

  const VtuArray *VtuGrid::find(const std::string &name, bool &on_points) const
  {
    for (const auto *list : {&point_data, &cell_data})
      for (const VtuArray &a : *list)
        if (a.name == name)
          {
            on_points = list == &point_data;
            return &a;
          }
    return nullptr;
  }

  void append_grid(VtuGrid &grid, const VtuGrid &piece, const std::string &piece_name)
  {
    const std::uint64_t point_shift = grid.points.size(), cell_shift = grid.connectivity.size();
    for (auto [mine, theirs] : {std::pair{&grid.point_data, &piece.point_data},
                                std::pair{&grid.cell_data, &piece.cell_data}})
      {
        if (mine->size() != theirs->size())
          fail(piece_name, "has other data arrays than the pieces before it");
        for (std::size_t a = 0; a < mine->size(); ++a)
          {
            if ((*mine)[a].name != (*theirs)[a].name ||
                (*mine)[a].components != (*theirs)[a].components)
              fail(piece_name, "has array '" + (*theirs)[a].name +
                                 "' where the pieces before it have '" + (*mine)[a].name + "'");
            (*mine)[a].values.insert((*mine)[a].values.end(), (*theirs)[a].values.begin(),
                                     (*theirs)[a].values.end());
          }
      }
    grid.points.insert(grid.points.end(), piece.points.begin(), piece.points.end());
    for (const std::uint64_t v : piece.connectivity)
      grid.connectivity.push_back(v + point_shift);
    for (const std::uint64_t o : piece.offsets)
      grid.offsets.push_back(o + cell_shift);
    grid.types.insert(grid.types.end(), piece.types.begin(), piece.types.end());
  }

  VtuGrid read_unstructured_grid(const std::string &file_name)
  {
    const std::string extension = std::filesystem::path(file_name).extension().string();
    if (extension == ".vtu")
      return read_vtu(file_name);
    if (extension != ".pvtu")
      fail(file_name, "is neither a .vtu nor a .pvtu file");
    const VtkXmlFile file(file_name);
    VtuGrid          grid;
    bool             first = true;
    for (const XmlTag &tag : file.tags())
      if (tag.name == "Piece")
        {
          const std::string source = beside(file_name, tag.attribute("Source"));
          add_piece(grid, first, read_vtu(source), source);
        }
    if (first)
      fail(file_name, "lists no <Piece Source=...>");
    return grid;
  }

  std::vector<PvdSnapshot> read_pvd(const std::string &file_name)
  {
    const VtkXmlFile         file(file_name);
    std::vector<PvdSnapshot> snapshots;
    for (const XmlTag &tag : file.tags())
      if (tag.name == "DataSet")
        {
          const double      time   = std::stod(tag.attribute("timestep", "0"));
          const std::string source = beside(file_name, tag.attribute("file"));
          if (!snapshots.empty() && snapshots.back().time == time)
            snapshots.back().files.push_back(source); // another part of the same time
          else
            snapshots.push_back({time, {source}});
        }
    if (snapshots.empty())
      fail(file_name, "lists no <DataSet>");
    std::stable_sort(snapshots.begin(), snapshots.end(),
                     [](const auto &a, const auto &b) { return a.time < b.time; });
    for (std::size_t s = 1; s < snapshots.size(); ++s)
      if (snapshots[s].time == snapshots[s - 1].time)
        fail(file_name, "lists the time " + std::to_string(snapshots[s].time) +
                          " in two places; a time series needs increasing times");
    return snapshots;
  }
} // namespace sluice
