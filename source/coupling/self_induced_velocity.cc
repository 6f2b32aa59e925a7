// The convolution of each particle's force history with the measured response
// of the fluid (self_induced_velocity.h); the measurement itself is in
// self_response_measurement.cc.

#include <sluice/core/mpi_gather.h>
#include <sluice/core/binary_io.h>
#include <sluice/coupling/self_induced_velocity.h>

#include <algorithm>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace
{
  const std::string self_induced_tag = "sluice self-induced velocity 1";
}

namespace sluice
{
  Vec3 SelfResponseTable::response(const unsigned int m, const Vec3 &r, const Vec3 &force) const
  {
    const std::vector<double> &a = across[m], &b = along[m];
    const double distance = norm(r), position = distance / spacing;
    const auto   j = static_cast<std::size_t>(position);
    if (j + 1 >= a.size())
      return Vec3();
    const double w = position - j;
    const double A = (1. - w) * a[j] + w * a[j + 1];
    const double AB = (1. - w) * b[j] + w * b[j + 1];
    if (distance <= 1e-12 * spacing)
      return AB * force; // at the deposit itself along = across
    const Vec3 e = (1. / distance) * r;
    return A * force + ((AB - A) * dot(e, force)) * e;
  }

  double SelfResponseTable::steady_response_at_deposit() const
  {
    double sum = 0.;
    for (const auto &row : along)
      sum += row[0];
    return sum;
  }

  std::vector<Vec3> self_response_points(const Vec3 &centre, const Vec3 &direction,
                                         const double spacing, const double reach)
  {
    const Vec3 e      = (1. / norm(direction)) * direction;
    const Vec3 helper = std::abs(e.x) < 0.9 ? Vec3(1., 0., 0.) : Vec3(0., 1., 0.);
    const Vec3 a1     = (1. / norm(cross(e, helper))) * cross(e, helper);
    const Vec3 a2     = cross(e, a1);
    const unsigned int n_offsets = static_cast<unsigned int>(std::floor(reach / spacing)) + 1;
    std::vector<Vec3>  points{centre};
    for (unsigned int j = 1; j < n_offsets; ++j)
      for (const Vec3 &axis : {e, -e, a1, -a1, a2, -a2})
        points.push_back(centre + (j * spacing) * axis);
    return points;
  }

  void add_self_response_row(SelfResponseTable &table, const std::vector<double> &u)
  {
    const std::size_t   n_offsets = (u.size() - 1) / 6 + 1;
    std::vector<double> along(n_offsets), across(n_offsets);
    along[0] = across[0] = u[0];
    for (std::size_t j = 1; j < n_offsets; ++j)
      {
        const double *v = &u[1 + 6 * (j - 1)];
        along[j]        = 0.5 * (v[0] + v[1]);
        across[j]       = 0.25 * (v[2] + v[3] + v[4] + v[5]);
      }
    table.along.push_back(std::move(along));
    table.across.push_back(std::move(across));
  }

  SelfInducedVelocity::SelfInducedVelocity(SelfResponseTable table, const PeriodicBox &box)
    : response(std::move(table))
    , box(box)
  {
    if (response.steps() == 0 || response.spacing <= 0.)
      throw std::invalid_argument("SelfInducedVelocity: empty response table");
  }

  void SelfInducedVelocity::record(const std::vector<std::uint64_t> &ids,
                                   const std::vector<Vec3> &forces,
                                   const std::vector<Vec3> &deposits, MPI_Comm comm)
  {
    // Seven doubles per particle: the id's bits, F, x - D.
    std::vector<double> mine(7 * ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i)
      {
        std::memcpy(&mine[7 * i], &ids[i], sizeof(double));
        for (unsigned int d = 0; d < 3; ++d)
          {
            mine[7 * i + 1 + d] = forces[i][d];
            mine[7 * i + 4 + d] = deposits[i][d];
          }
      }
    const std::vector<double> all = gathered(mine, comm);

    ++step;
    const unsigned int n = response.steps();
    for (std::size_t k = 0; k < all.size(); k += 7)
      {
        std::uint64_t id;
        std::memcpy(&id, &all[k], sizeof(double));
        History &h = histories[id];
        if (h.force.empty())
          {
            h.force.resize(n);
            h.deposit.resize(n);
          }
        h.newest            = (h.newest + 1) % n;
        h.force[h.newest]   = Vec3(all[k + 1], all[k + 2], all[k + 3]);
        h.deposit[h.newest] = Vec3(all[k + 4], all[k + 5], all[k + 6]);
        h.size              = std::min(h.size + 1, n);
        h.last_step         = step;
      }
    // Particles that left the fluid (or the scene) start afresh if they return.
    for (auto it = histories.begin(); it != histories.end();)
      it = it->second.last_step != step ? histories.erase(it) : std::next(it);
  }

  Vec3 SelfInducedVelocity::velocity(const std::uint64_t id, const Vec3 &deposit_position) const
  {
    const auto it = histories.find(id);
    if (it == histories.end())
      return Vec3();
    const History     &h = it->second;
    const unsigned int n = response.steps();
    Vec3               u;
    for (unsigned int m = 0; m < h.size; ++m)
      {
        const unsigned int k = (h.newest + n - m) % n;
        u += response.response(m, box.minimum_image(deposit_position - h.deposit[k]), h.force[k]);
      }
    return u;
  }

  std::string SelfInducedVelocity::serialize() const
  {
    BinaryWriter out(self_induced_tag);
    out.write(response.spacing);
    out.write<std::uint64_t>(response.along.size());
    for (unsigned int m = 0; m < response.along.size(); ++m)
      {
        out.write_vector(response.along[m]);
        out.write_vector(response.across[m]);
      }
    out.write<std::uint64_t>(step);
    // By id, so that the same state gives the same bytes.
    std::vector<std::uint64_t> ids;
    for (const auto &entry : histories)
      ids.push_back(entry.first);
    std::sort(ids.begin(), ids.end());
    out.write_vector(ids);
    for (const std::uint64_t id : ids)
      {
        const History &h = histories.at(id);
        out.write_vector(h.force);
        out.write_vector(h.deposit);
        out.write<std::uint32_t>(h.newest);
        out.write<std::uint32_t>(h.size);
        out.write<std::uint64_t>(h.last_step);
      }
    return out.finish();
  }

  std::unique_ptr<SelfInducedVelocity> SelfInducedVelocity::deserialize(const std::string &bytes,
                                                                        const PeriodicBox &box)
  {
    BinaryReader      in(bytes, self_induced_tag);
    SelfResponseTable table;
    table.spacing             = in.read<double>();
    const std::uint64_t steps = in.read<std::uint64_t>();
    if (steps == 0 || steps > (1u << 24))
      throw BinaryFormatError("its response table is damaged");
    for (std::uint64_t m = 0; m < steps; ++m)
      {
        table.along.push_back(in.read_vector<double>());
        table.across.push_back(in.read_vector<double>());
      }
    auto correction  = std::make_unique<SelfInducedVelocity>(std::move(table), box);
    correction->step = in.read<std::uint64_t>();
    for (const std::uint64_t id : in.read_vector<std::uint64_t>())
      {
        History &h  = correction->histories[id];
        h.force     = in.read_vector<Vec3>();
        h.deposit   = in.read_vector<Vec3>();
        h.newest    = in.read<std::uint32_t>();
        h.size      = in.read<std::uint32_t>();
        h.last_step = in.read<std::uint64_t>();
        if (h.force.size() != steps || h.deposit.size() != steps || h.newest >= steps ||
            h.size > steps)
          throw BinaryFormatError("a force history does not fit the response table");
      }
    if (!in.at_end())
      throw BinaryFormatError("it holds more than a response table and its histories");
    return correction;
  }
} // namespace sluice
