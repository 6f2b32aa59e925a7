// Triangle meshes from STL files (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/triangle_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

namespace sluice
{
  namespace
  {
    using Facets = std::vector<std::array<Vec3, 3>>;

    [[noreturn]] void fail(const std::string &where, const std::string &what)
    {
      throw InputError(where + ": " + what);
    }

    std::string facet_text(const std::size_t f) { return "facet " + std::to_string(f + 1); }

    /// Binary STL: an 80-byte header, a 32-bit count, then 50 bytes a facet
    /// (normal, three vertices as 32-bit floats, a 16-bit attribute). A file
    /// of exactly that size is binary, whatever its header says.
    bool read_binary_stl(const std::string &bytes, Facets &facets)
    {
      if (bytes.size() < 84)
        return false;
      std::uint32_t n = 0;
      std::memcpy(&n, bytes.data() + 80, 4);
      if (bytes.size() != 84 + 50ull * n)
        return false;
      facets.resize(n);
      for (std::uint32_t f = 0; f < n; ++f)
        for (unsigned int v = 0; v < 3; ++v)
          {
            float x[3];
            std::memcpy(x, bytes.data() + 84 + 50ull * f + 12 * (v + 1), 12);
            facets[f][v] = Vec3(x[0], x[1], x[2]);
          }
      return true;
    }

    /// ASCII STL: 'solid', then 'facet normal ...', 'outer loop', three
    /// 'vertex x y z', 'endloop', 'endfacet', ..., 'endsolid' (several solids
    /// may follow each other). The facet normals are not used: the vertex
    /// order gives the orientation.
    bool read_ascii_stl(const std::string &bytes, Facets &facets, const std::string &where)
    {
      std::istringstream in(bytes);
      std::string        word;
      if (!(in >> word) || word != "solid")
        return false;
      std::getline(in, word); // the solid's name
      std::vector<Vec3> loop;
      bool              in_facet = false;
      while (in >> word)
        {
          if (word == "facet")
            {
              in_facet = true;
              loop.clear();
              std::getline(in, word); // 'normal nx ny nz'
            }
          else if (word == "vertex")
            {
              std::string x, y, z;
              if (!in_facet || !(in >> x >> y >> z))
                fail(where, "a 'vertex' outside a facet, or with fewer than three numbers, in " +
                              facet_text(facets.size()));
              Vec3 p;
              try
                {
                  p = Vec3(std::stod(x), std::stod(y), std::stod(z));
                }
              catch (const std::exception &)
                {
                  fail(where, facet_text(facets.size()) + " has the vertex '" + x + " " + y +
                                " " + z + "', which is not three numbers");
                }
              loop.push_back(p);
            }
          else if (word == "endfacet")
            {
              if (loop.size() != 3)
                fail(where, facet_text(facets.size()) + " has " + std::to_string(loop.size()) +
                              " vertices; a triangle mesh has three per facet");
              facets.push_back({{loop[0], loop[1], loop[2]}});
              in_facet = false;
            }
          else if (word == "solid" || word == "endsolid")
            std::getline(in, word); // the solid's name
          else if (word != "outer" && word != "loop" && word != "endloop")
            fail(where, "unexpected '" + word.substr(0, 40) + "' after " +
                          (facets.empty() ? std::string("the header") :
                                            facet_text(facets.size() - 1)));
        }
      return true;
    }

    /// Skips to the line '$<section>'; false if there is none.
    bool find_section(std::istream &in, const std::string &section)
    {
      for (std::string line; std::getline(in, line);)
        if (line.compare(0, section.size() + 1, "$" + section) == 0)
          return true;
      return false;
    }

    /// gmsh's ASCII .msh, format 2.2 or 4.1: the 3-node triangles (element
    /// type 2) of every entity, on the nodes they name; other elements (the
    /// lines and points gmsh also writes) are skipped.
    bool read_gmsh(const std::string &bytes, Facets &facets, const std::string &where)
    {
      if (bytes.compare(0, 11, "$MeshFormat") != 0)
        return false;
      std::istringstream in(bytes);
      std::string        line;
      double             version = 0.;
      int                binary  = 0;
      std::getline(in, line);
      if (!(in >> version >> binary))
        fail(where, "has a damaged $MeshFormat section");
      if (binary != 0)
        fail(where, "is a binary .msh file; save it as ASCII (gmsh's default, without "
                    "'-bin')");
      const bool v4 = version >= 4.;
      if (!v4 && std::abs(version - 2.2) > 1e-9)
        fail(where, "is .msh format " + to_text(version) + "; formats 2.2 and 4.1 are read");

      std::unordered_map<long long, Vec3> nodes;
      if (!find_section(in, "Nodes"))
        fail(where, "has no $Nodes section");
      const auto bad = [&](const std::string &section) {
        fail(where, "has a damaged " + section + " section");
      };
      if (v4)
        {
          long long blocks = 0, n = 0, lo = 0, hi = 0;
          if (!(in >> blocks >> n >> lo >> hi))
            bad("$Nodes");
          for (long long b = 0; b < blocks; ++b)
            {
              int       dim = 0, tag = 0, parametric = 0;
              long long count = 0;
              if (!(in >> dim >> tag >> parametric >> count))
                bad("$Nodes");
              std::vector<long long> tags(count);
              for (auto &t : tags)
                if (!(in >> t))
                  bad("$Nodes");
              for (const long long t : tags)
                {
                  Vec3 x;
                  if (!(in >> x.x >> x.y >> x.z))
                    bad("$Nodes");
                  for (int u = 0; parametric && u < dim; ++u)
                    in >> line; // parametric coordinates, not used
                  nodes[t] = x;
                }
            }
        }
      else
        {
          long long n = 0;
          if (!(in >> n))
            bad("$Nodes");
          for (long long k = 0; k < n; ++k)
            {
              long long t;
              Vec3      x;
              if (!(in >> t >> x.x >> x.y >> x.z))
                bad("$Nodes");
              nodes[t] = x;
            }
        }

      if (!find_section(in, "Elements"))
        fail(where, "has no $Elements section");
      const auto node = [&](const long long t) {
        const auto it = nodes.find(t);
        if (it == nodes.end())
          fail(where, "triangle " + std::to_string(facets.size() + 1) + " names node " +
                        std::to_string(t) + ", which is not in $Nodes");
        return it->second;
      };
      if (v4)
        {
          long long blocks = 0, n = 0, lo = 0, hi = 0;
          if (!(in >> blocks >> n >> lo >> hi))
            bad("$Elements");
          std::getline(in, line);
          for (long long b = 0; b < blocks; ++b)
            {
              int       dim = 0, tag = 0, type = 0;
              long long count = 0;
              if (!std::getline(in, line) ||
                  !(std::istringstream(line) >> dim >> tag >> type >> count))
                bad("$Elements");
              for (long long e = 0; e < count; ++e)
                {
                  if (!std::getline(in, line))
                    bad("$Elements");
                  if (type != 2)
                    continue;
                  std::istringstream el(line);
                  long long          id, a, b2, c;
                  if (!(el >> id >> a >> b2 >> c))
                    bad("$Elements");
                  facets.push_back({{node(a), node(b2), node(c)}});
                }
            }
        }
      else
        {
          long long n = 0;
          if (!(in >> n))
            bad("$Elements");
          std::getline(in, line);
          for (long long e = 0; e < n; ++e)
            {
              if (!std::getline(in, line))
                bad("$Elements");
              std::istringstream el(line);
              long long          id, type, n_tags, tag;
              if (!(el >> id >> type >> n_tags))
                bad("$Elements");
              for (long long k = 0; k < n_tags; ++k)
                el >> tag;
              if (type != 2)
                continue;
              long long a, b2, c;
              if (!(el >> a >> b2 >> c))
                bad("$Elements");
              facets.push_back({{node(a), node(b2), node(c)}});
            }
        }
      if (facets.empty())
        fail(where, "holds no triangles (element type 2); mesh the surface (gmsh -2)");
      return true;
    }

    Vec3 rotate(const Vec3 &x, const Vec3 &axis, const double angle)
    {
      // Rodrigues: x cos a + (k x x) sin a + k (k . x)(1 - cos a).
      const Vec3   k = (1. / norm(axis)) * axis;
      const double c = std::cos(angle), s = std::sin(angle);
      return c * x + s * cross(k, x) + ((1. - c) * dot(k, x)) * k;
    }

    /// Vertices closer than 'tolerance' become one: each point looks for an
    /// existing vertex in its grid cell of size 'tolerance' and the 26 around.
    std::vector<unsigned int> weld(const Facets &facets, const double tolerance,
                                   std::vector<Vec3> &vertices)
    {
      struct Key
      {
        long long i, j, k;
        bool      operator==(const Key &o) const { return i == o.i && j == o.j && k == o.k; }
      };
      struct Hash
      {
        std::size_t operator()(const Key &key) const
        {
          return std::hash<long long>()(key.i * 73856093ll ^ key.j * 19349663ll ^
                                        key.k * 83492791ll);
        }
      };
      std::unordered_map<Key, std::vector<unsigned int>, Hash> grid;
      std::vector<unsigned int>                                index;
      index.reserve(3 * facets.size());
      const auto cell = [&](const double x) { return static_cast<long long>(std::floor(x / tolerance)); };
      for (const auto &facet : facets)
        for (const Vec3 &p : facet)
          {
            const Key    c{cell(p.x), cell(p.y), cell(p.z)};
            unsigned int found = TriangleMesh::none;
            for (long long di = -1; di <= 1 && found == TriangleMesh::none; ++di)
              for (long long dj = -1; dj <= 1 && found == TriangleMesh::none; ++dj)
                for (long long dk = -1; dk <= 1 && found == TriangleMesh::none; ++dk)
                  {
                    const auto it = grid.find({c.i + di, c.j + dj, c.k + dk});
                    if (it != grid.end())
                      for (const unsigned int v : it->second)
                        if (norm_square(vertices[v] - p) <= tolerance * tolerance)
                          {
                            found = v;
                            break;
                          }
                  }
            if (found == TriangleMesh::none)
              {
                found = vertices.size();
                vertices.push_back(p);
                grid[c].push_back(found);
              }
            index.push_back(found);
          }
      return index;
    }

    /// The triangle across each edge, from the edges' vertex pairs.
    void find_neighbours(TriangleMesh &mesh)
    {
      std::map<std::pair<unsigned int, unsigned int>, std::vector<std::pair<unsigned, unsigned>>>
        edges; // (lower, higher vertex) -> (triangle, edge)
      for (unsigned int t = 0; t < mesh.size(); ++t)
        for (unsigned int k = 0; k < 3; ++k)
          {
            const unsigned int a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}].emplace_back(t, k);
          }
      mesh.neighbours.assign(mesh.size(), {{TriangleMesh::none, TriangleMesh::none,
                                            TriangleMesh::none}});
      for (const auto &[edge, sides] : edges)
        {
          if (sides.size() == 1)
            ++mesh.n_open_edges;
          else if (sides.size() > 2)
            ++mesh.n_nonmanifold_edges;
          else
            {
              mesh.neighbours[sides[0].first][sides[0].second] = sides[1].first;
              mesh.neighbours[sides[1].first][sides[1].second] = sides[0].first;
            }
        }
    }
  } // namespace

  double TriangleMesh::total_area() const
  {
    double a = 0.;
    for (const double x : areas)
      a += x;
    return a;
  }

  TriangleMesh make_triangle_mesh(const Facets &facets, const bool closed,
                                  const std::string &where)
  {
    if (facets.empty())
      fail(where, "holds no triangles");
    Vec3 lo(1e300, 1e300, 1e300), hi = -lo;
    for (std::size_t f = 0; f < facets.size(); ++f)
      for (const Vec3 &p : facets[f])
        {
          if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            fail(where, facet_text(f) + " has a vertex that is not a finite number");
          for (unsigned int d = 0; d < 3; ++d)
            {
              lo[d] = std::min(lo[d], p[d]);
              hi[d] = std::max(hi[d], p[d]);
            }
        }
    TriangleMesh mesh;
    const double tolerance = 1e-9 * std::max(norm(hi - lo), 1e-300);
    const std::vector<unsigned int> index = weld(facets, tolerance, mesh.vertices);
    for (std::size_t f = 0; f < facets.size(); ++f)
      {
        const Vec3  &a = facets[f][0], &b = facets[f][1], &c = facets[f][2];
        const Vec3   n = cross(b - a, c - a);
        const double longest =
          std::max({norm_square(b - a), norm_square(c - b), norm_square(a - c)});
        if (!(0.5 * norm(n) > 1e-12 * longest))
          fail(where, facet_text(f) + " is degenerate (its vertices are on one line or "
                                      "coincide)");
        mesh.triangles.push_back({{index[3 * f], index[3 * f + 1], index[3 * f + 2]}});
        mesh.normals.push_back((1. / norm(n)) * n);
        mesh.areas.push_back(0.5 * norm(n));
      }
    find_neighbours(mesh);
    mesh.vertex_offset.assign(mesh.vertices.size() + 1, 0);
    for (const auto &t : mesh.triangles)
      for (const unsigned int v : t)
        ++mesh.vertex_offset[v + 1];
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      mesh.vertex_offset[v + 1] += mesh.vertex_offset[v];
    mesh.vertex_triangles.resize(mesh.vertex_offset.back());
    std::vector<unsigned int> filled(mesh.vertex_offset.begin(), mesh.vertex_offset.end() - 1);
    for (unsigned int t = 0; t < mesh.size(); ++t)
      for (const unsigned int v : mesh.triangles[t])
        mesh.vertex_triangles[filled[v]++] = t;
    if (closed && mesh.n_open_edges > 0)
      for (unsigned int t = 0; t < mesh.size(); ++t)
        for (unsigned int k = 0; k < 3; ++k)
          if (mesh.neighbours[t][k] == TriangleMesh::none)
            fail(where, "is not a closed surface: " + facet_text(t) + " has an open edge (" +
                          std::to_string(mesh.n_open_edges) + " open edges in all)");
    return mesh;
  }

  TriangleMesh read_triangle_mesh(const std::string &file, const MeshPlacement &placement,
                                  const bool closed, const std::string &context)
  {
    const std::string where = context + " = '" + file + "'";
    std::ifstream     in(file, std::ios::binary);
    if (!in)
      fail(where, "cannot be read");
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    Facets            facets;
    if (!read_gmsh(bytes, facets, where) && !read_binary_stl(bytes, facets) &&
        !read_ascii_stl(bytes, facets, where))
      fail(where, "is not a triangle mesh (neither gmsh .msh starting with '$MeshFormat', "
                  "binary STL by its size, nor ASCII STL starting with 'solid')");
    if (!(placement.scale > 0.) || !(norm(placement.axis) > 0.))
      fail(where, "needs a scale > 0 and a rotation axis of non-zero length");
    for (auto &facet : facets)
      for (Vec3 &p : facet)
        p = rotate(placement.scale * p, placement.axis, placement.angle) + placement.offset;
    return make_triangle_mesh(facets, closed, where);
  }
} // namespace sluice
