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
