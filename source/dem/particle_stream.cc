// A particle stream: inlet, outlet and recycling (see the header).

#include <sluice/core/mpi_gather.h>
#include <sluice/core/sphere.h>
#include <sluice/dem/clump_insertion.h>
#include <sluice/dem/particle_stream.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <random>

namespace sluice
{
  ParticleStream::ParticleStream(const SceneParameters &p, const DemSystem &dem)
    : parameters(p.stream), density(p.density), clumps(dem.clumps.get()),
      clump_parameters(p.clumps), next_time(p.stream.start_time), next_id(dem.n_inserted),
      removed(p.n_materials(), 0.), removed_mass(p.n_materials(), 0.)
  {
    // The mean mass of radii uniform in [a, b]: rho 4/3 pi E[r^3].
    const double a = parameters.radius, b = std::max(parameters.radius, parameters.radius_max);
    const double mean_r3 = b > a ? (std::pow(b, 4) - std::pow(a, 4)) / (4. * (b - a)) : a * a * a;
    mean_mass = clumps ? mean_clump_mass(p.clumps, clumps->templates, density[parameters.type]) :
                         density[parameters.type] * 4. / 3. * M_PI * mean_r3;
  }

  bool ParticleStream::at_outlet(const Vec3 &x) const
  {
    const StreamParameters &s = parameters;
    if (s.outlet == StreamRegion::box)
      return x.x >= s.outlet_lower.x && x.y >= s.outlet_lower.y && x.z >= s.outlet_lower.z &&
             x.x <= s.outlet_upper.x && x.y <= s.outlet_upper.y && x.z <= s.outlet_upper.z;
    if (s.outlet == StreamRegion::plane)
      return dot(x - s.outlet_point, s.outlet_normal) < 0.;
    return false;
  }

  bool ParticleStream::near_inlet(const Vec3 &x, const double reach) const
  {
    const StreamParameters &s = parameters;
    if (s.inlet == StreamRegion::box)
      return x.x > s.inlet_lower.x - reach && x.y > s.inlet_lower.y - reach &&
             x.z > s.inlet_lower.z - reach && x.x < s.inlet_upper.x + reach &&
             x.y < s.inlet_upper.y + reach && x.z < s.inlet_upper.z + reach;
    const Vec3   d     = x - s.inlet_centre;
    const double along = dot(d, s.inlet_axis);
    return std::abs(along) < 0.5 * s.inlet_thickness + reach &&
           norm(d - along * s.inlet_axis) < s.inlet_radius + reach;
  }

  std::vector<ParticleRecord> ParticleStream::place(const std::vector<ParticleRecord> &recycled,
                                                    const unsigned int n_new,
                                                    const std::vector<double> &obstacles)
  {
    const StreamParameters &s = parameters;
    std::mt19937_64 random(1000003ull * (s.seed + 1) + batch);
    std::uniform_real_distribution<double> unit(0., 1.);
    std::vector<ParticleRecord> wanted(recycled);
    for (unsigned int k = 0; k < n_new; ++k)
      {
        ParticleRecord r;
        if (clumps)
          draw_clump_body(clump_parameters, clumps->templates, random, r);
        else
          r.radius = s.radius_max > s.radius ? s.radius + (s.radius_max - s.radius) * unit(random) :
                                               s.radius;
        r.type   = s.type;
        wanted.push_back(r);
      }
    // A recycled clump keeps its template and scale and comes back turned anew.
    if (clumps)
      for (std::size_t k = 0; k < recycled.size(); ++k)
        {
          ParticleRecord turned;
          draw_clump_body(clump_parameters, clumps->templates, random, turned);
          wanted[k].orientation = turned.orientation;
        }
    std::vector<double>         spheres(obstacles);
    std::vector<ParticleRecord> placed;
    for (ParticleRecord r : wanted)
      for (unsigned int attempt = 0; attempt < 200; ++attempt)
        {
          Vec3 x;
          if (s.inlet == StreamRegion::box)
            for (unsigned int d = 0; d < 3; ++d)
              x[d] = s.inlet_lower[d] + r.radius +
                     (s.inlet_upper[d] - s.inlet_lower[d] - 2. * r.radius) * unit(random);
          else
            {
              // Uniform in the disc: an orthonormal pair across the axis.
              const Vec3 a = std::abs(s.inlet_axis.x) < 0.9 ? Vec3(1., 0., 0.) : Vec3(0., 1., 0.);
              const Vec3 e1 = (1. / norm(cross(s.inlet_axis, a))) * cross(s.inlet_axis, a);
              const Vec3 e2 = cross(s.inlet_axis, e1);
              const double rho = (s.inlet_radius - r.radius) * std::sqrt(unit(random));
              const double phi = 2. * M_PI * unit(random);
              const double h   = (0.5 * s.inlet_thickness - r.radius) * (2. * unit(random) - 1.);
              x = s.inlet_centre + rho * std::cos(phi) * e1 + rho * std::sin(phi) * e2 +
                  h * s.inlet_axis;
            }
          bool free = true;
          for (std::size_t k = 0; k + 4 <= spheres.size() && free; k += 4)
            {
              const double reach = r.radius + spheres[k + 3];
              free = norm_square(x - Vec3(spheres[k], spheres[k + 1], spheres[k + 2])) >=
                     reach * reach;
            }
          if (!free)
            continue;
          r.position         = x;
          r.velocity         = s.velocity;
          r.angular_velocity = Vec3();
          placed.push_back(r);
          spheres.insert(spheres.end(), {x.x, x.y, x.z, r.radius});
          break;
        }
    ++batch;
    return placed;
  }

  void ParticleStream::after_step(DemSystem &dem)
  {
    if (!active() || dem.time() < next_time - 0.5 * dem.dt)
      return;
    next_time += parameters.interval;
    // A clump scene's particles are its bodies (centroid, bounding radius).
    const ParticleStorage &P = dem.handler_particles();

    // The outlet: id, type, mass, radius (and a clump's template and scale)
    // of every particle there, all ranks.
    std::vector<double> mine;
    for (unsigned int i = 0; i < P.n_local; ++i)
      if (at_outlet(P.position[i]))
        mine.insert(mine.end(),
                    {static_cast<double>(P.id[i]), static_cast<double>(P.type[i]), P.mass[i],
                     P.radius[i],
                     clumps ? double(&clumps->template_of(i) - clumps->templates.data()) : 0.,
                     clumps ? clumps->scale_of(i) : 1.});
    const std::vector<double>   leaving = gathered(mine, dem.comm);
    // In the order of their ids (the same on every rank, whatever the ranks'
    // order): the particles to remove, and to put back when recycling.
    std::vector<std::pair<std::uint64_t, std::size_t>> by_id;
    for (std::size_t k = 0; k < leaving.size(); k += 6)
      by_id.emplace_back(static_cast<std::uint64_t>(leaving[k]), k);
    std::sort(by_id.begin(), by_id.end());
    std::vector<std::uint64_t>  remove_ids, ids;
    std::vector<ParticleRecord> back;
    for (const auto &[id, k] : by_id)
      {
        const unsigned int type = static_cast<unsigned int>(leaving[k + 1]);
        remove_ids.push_back(id);
        removed[type] += 1.;
        removed_mass[type] += leaving[k + 2];
        if (parameters.recycle)
          {
            ParticleRecord r;
            r.radius         = leaving[k + 3];
            r.type           = type;
            r.clump_template = static_cast<unsigned int>(leaving[k + 4]);
            r.clump_scale    = leaving[k + 5];
            back.push_back(r);
            ids.push_back(id);
          }
      }

    // The inlet: what the rate owes, while it runs.
    unsigned int n_new = 0;
    if (parameters.inlet != StreamRegion::none && dem.time() <= parameters.end_time)
      {
        const double per_second =
          parameters.mass_rate > 0. ? parameters.mass_rate / mean_mass : parameters.rate;
        owed += per_second * parameters.interval;
        n_new = static_cast<unsigned int>(std::floor(owed));
      }
    std::vector<ParticleRecord> batch_records;
    if (parameters.inlet != StreamRegion::none && (n_new > 0 || !back.empty()))
      {
        std::vector<double> near;
        const double        reach =
          2. * std::max({dem.r_max, parameters.radius_max, dem.body_radius_max});
        for (unsigned int i = 0; i < P.n_local; ++i)
          if (near_inlet(P.position[i], reach) &&
              !std::binary_search(remove_ids.begin(), remove_ids.end(), P.id[i]))
            near.insert(near.end(), {P.position[i].x, P.position[i].y, P.position[i].z,
                                     P.radius[i]});
        batch_records = place(back, n_new, gathered(near, dem.comm));
        // Recycled spheres keep their ids; new ones take the next.
        const std::size_t n_back = std::min(batch_records.size(), back.size());
        ids.resize(n_back);
        recycled += n_back;
        for (std::size_t k = n_back; k < batch_records.size(); ++k)
          ids.push_back(next_id++);
        const std::size_t n_placed_new = batch_records.size() - n_back;
        inserted += n_placed_new;
        owed -= n_placed_new;
        not_placed += back.size() - n_back;
        // (A recycled sphere that found no room is gone; it is counted.)
      }
    if (!remove_ids.empty() || !batch_records.empty())
      dem.schedule_replacement(remove_ids, batch_records, ids);
  }

  void ParticleStream::open_csv(const std::string &directory, const std::string &base_name,
                                const bool restart, const double time, MPI_Comm comm)
  {
    if (!active())
      return;
    int rank;
    MPI_Comm_rank(comm, &rank);
    std::string header = "time,inserted,recycled,not_placed";
    for (std::size_t t = 0; t < removed.size(); ++t)
      header += ",removed_" + std::to_string(t) + ",removed_mass_" + std::to_string(t);
    csv.open(directory + "/" + base_name + "_discharge.csv", header, rank == 0, restart, time);
  }

  void ParticleStream::write_row(const double time, const DemSystem &)
  {
    if (!active() || !csv.is_open())
      return;
    csv.row() << std::setprecision(10) << time << ',' << inserted << ',' << recycled << ','
              << not_placed;
    for (std::size_t t = 0; t < removed.size(); ++t)
      csv.row() << ',' << removed[t] << ',' << removed_mass[t];
    csv.end_row();
  }

  void ParticleStream::summary(std::ostream &out, const double time) const
  {
    if (!active())
      return;
    double n = 0., mass = 0.;
    for (std::size_t t = 0; t < removed.size(); ++t)
      {
        n += removed[t];
        mass += removed_mass[t];
      }
    out << "stream: inserted=" << inserted << " recycled=" << recycled
        << " not_placed=" << not_placed << " removed=" << n << " removed_mass=" << mass
        << " mean_discharge_rate=" << (time > 0. ? mass / time : 0.)
        << " owed=" << std::floor(owed) << "\n";
  }

  std::vector<double> ParticleStream::state() const
  {
    std::vector<double> s{next_time, owed, static_cast<double>(batch), static_cast<double>(next_id),
                          static_cast<double>(inserted), static_cast<double>(not_placed),
                          static_cast<double>(recycled)};
    s.insert(s.end(), removed.begin(), removed.end());
    s.insert(s.end(), removed_mass.begin(), removed_mass.end());
    return s;
  }

  void ParticleStream::set_state(const std::vector<double> &s)
  {
    if (s.size() != 7 + 2 * removed.size())
      return;
    next_time  = s[0];
    owed       = s[1];
    batch      = static_cast<unsigned long long>(s[2]);
    next_id    = static_cast<unsigned long long>(s[3]);
    inserted   = static_cast<unsigned long long>(s[4]);
    not_placed = static_cast<unsigned long long>(s[5]);
    recycled   = static_cast<unsigned long long>(s[6]);
    std::copy(s.begin() + 7, s.begin() + 7 + removed.size(), removed.begin());
    std::copy(s.begin() + 7 + removed.size(), s.end(), removed_mass.begin());
  }
} // namespace sluice
