// One snapshot of an imported flow field (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/coupling/imported_field.h>

#include <deal.II/base/bounding_box.h>
#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <iterator>

namespace sluice
{
  namespace
  {
    using Leaf = std::pair<dealii::BoundingBox<3>, unsigned int>;

    [[noreturn]] void fail(const std::string &file, const std::string &what)
    {
      throw InputError("error: the flow field '" + file + "' " + what);
    }

    /// The point values of an array (cell values averaged onto the points).
    std::vector<double> point_values(const VtuGrid &g, const std::string &name,
                                     const unsigned int components, const std::string &file)
    {
      bool            on_points = true;
      const VtuArray *a         = g.find(name, on_points);
      if (!a)
        fail(file, "has no point or cell array '" + name + "'");
      if (a->components != components)
        fail(file, "has an array '" + name + "' of " + std::to_string(a->components) +
                     " components where " + std::to_string(components) + " belong");
      if (on_points)
        return a->values;
      std::vector<double> values(g.points.size() * components, 0.), n_cells(g.points.size(), 0.);
      for (std::size_t c = 0; c < g.n_cells(); ++c)
        for (std::uint64_t k = c == 0 ? 0 : g.offsets[c - 1]; k < g.offsets[c]; ++k)
          {
            const std::uint64_t v = g.connectivity[k];
            n_cells[v] += 1.;
            for (unsigned int d = 0; d < components; ++d)
              values[components * v + d] += a->values[components * c + d];
          }
      for (std::size_t v = 0; v < g.points.size(); ++v)
        for (unsigned int d = 0; d < components; ++d)
          values[components * v + d] /= std::max(n_cells[v], 1.);
      return values;
    }
  } // namespace

  struct FieldGeometry::Tree
  {
    decltype(dealii::pack_rtree(std::vector<Leaf>())) rtree;
  };

  FieldGeometry::FieldGeometry(std::vector<Vec3> points_, std::vector<std::uint64_t> connectivity_,
                               std::vector<std::uint64_t> offsets_,
                               std::vector<std::uint8_t> types_, const std::string &file)
    : points(std::move(points_)), connectivity(std::move(connectivity_))
    , offsets(std::move(offsets_)), types(std::move(types_))
  {
    if (types.empty())
      fail(file, "has no cells");
    std::vector<Leaf> leaves;
    leaves.reserve(types.size());
    lower = upper = points[connectivity[0]];
    for (std::size_t c = 0; c < types.size(); ++c)
      {
        const std::uint64_t first = c == 0 ? 0 : offsets[c - 1];
        const unsigned int  n     = vtk_cell::n_nodes(types[c]);
        if (n == 0)
          fail(file, "has cell " + std::to_string(c + 1) + " of VTK type " +
                       std::to_string(types[c]) +
                       "; Sluice reads tetrahedra (10), voxels (11), hexahedra (12), wedges "
                       "(13) and pyramids (14): decompose polyhedra first (ParaView: "
                       "Tetrahedralize, or foamToVTK's default decomposition)");
        if (offsets[c] - first != n)
          fail(file, "has cell " + std::to_string(c + 1) + " with " +
                       std::to_string(offsets[c] - first) + " points where its type has " +
                       std::to_string(n));
        dealii::Point<3> lo, hi;
        for (unsigned int d = 0; d < 3; ++d)
          lo[d] = hi[d] = points[connectivity[first]][d];
        for (std::uint64_t k = first; k < offsets[c]; ++k)
          for (unsigned int d = 0; d < 3; ++d)
            {
              lo[d]    = std::min(lo[d], points[connectivity[k]][d]);
              hi[d]    = std::max(hi[d], points[connectivity[k]][d]);
              lower[d] = std::min(lower[d], lo[d]);
              upper[d] = std::max(upper[d], hi[d]);
            }
        // Grown a little, so that a point on a face finds the cell.
        const double grow = 1e-9 * (hi - lo).norm();
        for (unsigned int d = 0; d < 3; ++d)
          lo[d] -= grow, hi[d] += grow;
        leaves.emplace_back(dealii::BoundingBox<3>(std::make_pair(lo, hi)), c);
      }
    tree        = std::make_unique<Tree>();
    tree->rtree = dealii::pack_rtree(leaves);
  }

  FieldGeometry::~FieldGeometry() = default;

  bool FieldGeometry::in_cell(const std::size_t cell, const Vec3 &x, CellPoint &point) const
  {
    const std::uint64_t first = cell == 0 ? 0 : offsets[cell - 1];
    Vec3                X[vtk_cell::max_nodes];
    const unsigned int  n = vtk_cell::n_nodes(types[cell]);
    for (unsigned int a = 0; a < n; ++a)
      {
        point.nodes[a] = connectivity[first + a];
        X[a]           = points[point.nodes[a]];
      }
    if (!locate_in_cell(types[cell], X, x, point))
      return false;
    point.cell = static_cast<long>(cell);
    return true;
  }

  CellPoint FieldGeometry::locate(const Vec3 &x, const long hint) const
  {
    CellPoint point;
    if (hint >= 0 && static_cast<std::size_t>(hint) < types.size() && in_cell(hint, x, point))
      return point;
    if (x.x < lower.x || x.y < lower.y || x.z < lower.z || x.x > upper.x || x.y > upper.y ||
        x.z > upper.z)
      return CellPoint();
    std::vector<Leaf> hits;
    tree->rtree.query(boost::geometry::index::intersects(dealii::Point<3>(x.x, x.y, x.z)),
                      std::back_inserter(hits));
    for (const Leaf &leaf : hits)
      if (in_cell(leaf.second, x, point))
        return point;
    return CellPoint();
  }

  bool FieldGeometry::same_grid(const VtuGrid &g, const double length_scale) const
  {
    if (g.points.size() != points.size() || g.connectivity != connectivity || g.types != types)
      return false;
    for (std::size_t v = 0; v < points.size(); ++v)
      if (norm_square(length_scale * g.points[v] - points[v]) > 0.)
        return false;
    return true;
  }

  ImportedField::ImportedField(const std::vector<std::string> &files,
                               const ImportedFieldArrays &arrays,
                               std::shared_ptr<const FieldGeometry> earlier)
  {
    const std::string &file = files.front();
    VtuGrid            g    = read_unstructured_grid(file);
    for (std::size_t f = 1; f < files.size(); ++f)
      append_grid(g, read_unstructured_grid(files[f]), files[f]);
    // The values first: cell data need the cells, which the geometry then takes.
    const std::vector<double> u = point_values(g, arrays.velocity, 3, file);
    velocity.resize(g.points.size());
    for (std::size_t v = 0; v < velocity.size(); ++v)
      velocity[v] = Vec3(u[3 * v], u[3 * v + 1], u[3 * v + 2]);
    if (arrays.need_pressure)
      {
        pressure = point_values(g, arrays.pressure, 1, file);
        for (double &p : pressure)
          p *= arrays.pressure_scale;
      }
    if (!arrays.porosity.empty())
      {
        porosity = point_values(g, arrays.porosity, 1, file);
        for (std::size_t v = 0; v < porosity.size(); ++v)
          if (!(porosity[v] > 0. && porosity[v] <= 1.))
            fail(file, "has a porosity of " + std::to_string(porosity[v]) + " at point " +
                         std::to_string(v + 1) + "; it must lie in (0, 1]");
      }
    if (earlier && earlier->same_grid(g, arrays.length_scale))
      grid = std::move(earlier);
    else
      {
        std::vector<Vec3> points(g.points.size());
        for (std::size_t v = 0; v < points.size(); ++v)
          points[v] = arrays.length_scale * g.points[v];
        grid = std::make_shared<const FieldGeometry>(std::move(points), std::move(g.connectivity),
                                                     std::move(g.offsets), std::move(g.types),
                                                     file);
      }
  }

  void ImportedField::evaluate(const CellPoint &at, ParticleFluidSample &s) const
  {
    s.found    = true;
    s.velocity = Vec3();
    s.pressure_gradient = Vec3();
    s.porosity = porosity.empty() ? 1. : 0.;
    for (auto &row : s.velocity_gradient)
      std::fill(row, row + 3, 0.);
    for (unsigned int a = 0; a < at.n_nodes; ++a)
      {
        const std::uint64_t v = at.nodes[a];
        const Vec3         &g = at.gradient[a];
        s.velocity += at.N[a] * velocity[v];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            s.velocity_gradient[i][j] += velocity[v][i] * g[j];
        if (!pressure.empty())
          s.pressure_gradient += pressure[v] * g;
        if (!porosity.empty())
          s.porosity += at.N[a] * porosity[v];
      }
  }
} // namespace sluice
