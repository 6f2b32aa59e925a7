#include <sluice/dem/validation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace sluice
{
  ValidationProbe::ValidationProbe(const SceneParameters &p, const ContactProperties &props,
                                   const WallSet &w, MPI_Comm comm)
    : parameters(p), properties(props), walls(w), communicator(comm)
  {}

  std::vector<double> ValidationProbe::state() const
  {
    return {double(two_particles), double(started), double(ended), double(have_previous),
            previous_overlap, previous_time, previous_normal_speed, t_start, t_end, max_overlap,
            impact_speed, rebound_speed, initial_tangential_speed, last_velocity.x,
            last_velocity.y, last_velocity.z, last_angular_velocity.x, last_angular_velocity.y,
            last_angular_velocity.z, contact_normal.x, contact_normal.y, contact_normal.z,
            last_radius, last_overlap, double(last_wall)};
  }

  void ValidationProbe::set_state(const std::vector<double> &s)
  {
    if (s.size() != 25)
      return;
    two_particles = s[0] != 0., started = s[1] != 0., ended = s[2] != 0.;
    have_previous = s[3] != 0.;
    previous_overlap = s[4], previous_time = s[5], previous_normal_speed = s[6];
    t_start = s[7], t_end = s[8], max_overlap = s[9], impact_speed = s[10];
    rebound_speed = s[11], initial_tangential_speed = s[12];
    last_velocity         = Vec3(s[13], s[14], s[15]);
    last_angular_velocity = Vec3(s[16], s[17], s[18]);
    contact_normal        = Vec3(s[19], s[20], s[21]);
    last_radius = s[22], last_overlap = s[23];
    last_wall   = static_cast<unsigned int>(s[24]);
  }

  unsigned int ValidationProbe::partner_type(const TrackedState &s) const
  {
    return two_particles ? s.type[1] : walls[last_wall].material;
  }

  ValidationProbe::TrackedState ValidationProbe::gather_tracked(const ParticleStorage &P) const
  {
    // Particles 0 and 1 may live on any rank: every rank contributes what it owns.
    double local[2][14] = {};
    for (unsigned int i = 0; i < P.n_local; ++i)
      if (P.id[i] < 2)
        {
          double *s = local[P.id[i]];
          for (unsigned int d = 0; d < 3; ++d)
            {
              s[d]     = P.position[i][d];
              s[3 + d] = P.velocity[i][d];
              s[6 + d] = P.angular_velocity[i][d];
            }
          s[9]  = P.radius[i];
          s[10] = P.mass[i];
          s[11] = P.type[i];
          s[12] = 1.;
        }
    double global[2][14];
    MPI_Allreduce(local, global, 28, MPI_DOUBLE, MPI_SUM, communicator);
    TrackedState t;
    for (unsigned int k = 0; k < 2; ++k)
      {
        t.x[k]    = Vec3(global[k][0], global[k][1], global[k][2]);
        t.v[k]    = Vec3(global[k][3], global[k][4], global[k][5]);
        t.w[k]    = Vec3(global[k][6], global[k][7], global[k][8]);
        t.r[k]    = global[k][9];
        t.mass[k] = global[k][10];
        t.type[k] = static_cast<int>(global[k][11]);
      }
    return t;
  }

  double ValidationProbe::overlap(const TrackedState &s, Vec3 &normal, unsigned int &wall) const
  {
    if (two_particles)
      {
        const Vec3   d    = s.x[0] - s.x[1];
        const double dist = norm(d);
        normal            = (1. / dist) * d;
        return s.r[0] + s.r[1] - dist;
      }
    // The wall closest to particle 0.
    double best = -std::numeric_limits<double>::max();
    for (unsigned int k = 0; k < walls.n_planes(); ++k)
      {
        const double o = s.r[0] - dot(s.x[0] - walls[k].point, walls[k].normal);
        if (o > best)
          {
            best   = o;
            normal = walls[k].normal;
            wall   = k;
          }
      }
    return best;
  }

  void ValidationProbe::observe(const double time, const double, const ParticleStorage &P)
  {
    const ValidationCase c = parameters.validation;
    if (c != ValidationCase::hertz_impact && c != ValidationCase::restitution &&
        c != ValidationCase::sliding_to_rolling)
      return;
    const TrackedState s = gather_tracked(P);
    two_particles        = s.mass[1] > 0.;
    Vec3         n;
    const double delta = overlap(s, n, last_wall);
    // Against a wall, the velocity relative to the wall's surface where the
    // sphere touches it (or would).
    const Vec3 v_rel =
      two_particles ? s.v[0] - s.v[1] :
                      s.v[0] - walls[last_wall].velocity_at(s.x[0] - (s.r[0] - delta) * n);
    const double normal_speed = dot(v_rel, n); // < 0 approaching

    if (c == ValidationCase::sliding_to_rolling)
      {
        if (initial_tangential_speed < 0.)
          initial_tangential_speed = norm(v_rel - normal_speed * n);
        last_velocity         = v_rel;
        last_angular_velocity = s.w[0];
        last_radius           = s.r[0];
        last_overlap          = delta;
        contact_normal        = n;
        return;
      }

    if (!ended && have_previous)
      {
        if (!started && previous_overlap <= 0. && delta > 0.)
          {
            // Linear interpolation of the moment the spheres touch.
            started      = true;
            t_start      = previous_time + (time - previous_time) * (-previous_overlap) /
                                         (delta - previous_overlap);
            impact_speed = -previous_normal_speed;
          }
        else if (started && delta <= 0.)
          {
            ended         = true;
            t_end         = previous_time + (time - previous_time) * previous_overlap /
                                      (previous_overlap - delta);
            rebound_speed = normal_speed;
          }
      }
    if (started && !ended)
      max_overlap = std::max(max_overlap, delta);
    have_previous         = true;
    previous_overlap      = delta;
    previous_time         = time;
    previous_normal_speed = normal_speed;
  }

  ValidationResult ValidationProbe::finish(const ParticleStorage &P, const unsigned long long n_lost,
                                           const unsigned long long n_inserted)
  {
    ValidationResult   result;
    std::ostringstream check;
    check.precision(8);
    switch (parameters.validation)
      {
        case ValidationCase::hertz_impact:
          {
            result.name = "hertz_impact";
            const TrackedState s = gather_tracked(P);
            const PairProperties &pair = properties(s.type[0], partner_type(s));
            const double R_eff = two_particles ? s.r[0] * s.r[1] / (s.r[0] + s.r[1]) : s.r[0];
            const double m_eff = two_particles ? s.mass[0] * s.mass[1] / (s.mass[0] + s.mass[1]) : s.mass[0];
            const double v     = impact_speed;
            // Johnson (1985): delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5),
            // t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5).
            const double delta_ref =
              std::pow(15. * m_eff * v * v / (16. * pair.E_star * std::sqrt(R_eff)), 0.4);
            const double t_ref =
              2.868265699 * std::pow(m_eff * m_eff / (R_eff * pair.E_star * pair.E_star * v), 0.2);
            result.value     = ended ? t_end - t_start : 0.;
            result.reference = t_ref;
            result.error     = std::abs(result.value - t_ref) / t_ref;
            const double overlap_error = std::abs(max_overlap - delta_ref) / delta_ref;
            check << "check: maximum_overlap value=" << max_overlap << " reference=" << delta_ref
                  << " error=" << overlap_error;
            result.checks.push_back(check.str());
            result.error = std::max(result.error, overlap_error);
            break;
          }
        case ValidationCase::restitution:
          {
            result.name      = "restitution";
            const TrackedState s = gather_tracked(P);
            const double zeta = properties(s.type[0], partner_type(s)).damping_ratio;
            const double e    = std::exp(-M_PI * zeta / std::sqrt(1. - zeta * zeta));
            result.value     = ended && impact_speed > 0. ? rebound_speed / impact_speed : 0.;
            result.reference = e;
            result.error     = std::abs(result.value - e) / e;
            check << "check: impact_speed=" << impact_speed << " rebound_speed=" << rebound_speed;
            result.checks.push_back(check.str());
            break;
          }
        case ValidationCase::sliding_to_rolling:
          {
            result.name = "sliding_to_rolling";
            const Vec3   n   = contact_normal;
            const Vec3   v_t = last_velocity - dot(last_velocity, n) * n;
            // A solid sphere (I = 2/5 m R^2) ends rolling at 5/7 of its sliding speed.
            result.value     = norm(v_t);
            result.reference = 5. / 7. * initial_tangential_speed;
            result.error     = std::abs(result.value - result.reference) / result.reference;
            // Slip at the contact point, R - delta below the centre.
            const Vec3 slip =
              v_t - cross((last_radius - last_overlap) * last_angular_velocity, n);
            check << "check: final_slip_velocity_ratio=" << norm(slip) / result.reference;
            result.checks.push_back(check.str());
            break;
          }
        case ValidationCase::settle:
          {
            result.name = "settle";
            // Gather the bed on rank 0.
            int rank, n_ranks;
            MPI_Comm_rank(communicator, &rank);
            MPI_Comm_size(communicator, &n_ranks);
            std::vector<double> mine;
            for (unsigned int i = 0; i < P.n_local; ++i)
              {
                mine.insert(mine.end(), {P.position[i].x, P.position[i].y, P.position[i].z, P.radius[i]});
              }
            double energy = 0.;
            for (unsigned int i = 0; i < P.n_local; ++i)
              energy += 0.5 * P.mass[i] * norm_square(P.velocity[i]) +
                        0.5 / P.inverse_inertia[i] * norm_square(P.angular_velocity[i]);
            double total_energy = 0.;
            MPI_Allreduce(&energy, &total_energy, 1, MPI_DOUBLE, MPI_SUM, communicator);
            int              n_mine = mine.size();
            std::vector<int> counts(n_ranks), displs(n_ranks);
            MPI_Gather(&n_mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, communicator);
            std::vector<double> all;
            if (rank == 0)
              {
                int total = 0;
                for (int r = 0; r < n_ranks; ++r)
                  {
                    displs[r] = total;
                    total += counts[r];
                  }
                all.resize(total);
              }
            MPI_Gatherv(mine.data(), n_mine, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                        MPI_DOUBLE, 0, communicator);
            // bed_depth: in diameters, of the highest sphere top above the floor.
            double packing = 0., max_wall_overlap = 0., sampled_points = 0., bed_depth = 0.;
            if (rank == 0)
              {
                const unsigned int n = all.size() / 4;
                double r_max = 0., z_top = -std::numeric_limits<double>::max();
                for (unsigned int i = 0; i < n; ++i)
                  {
                    r_max = std::max(r_max, all[4 * i + 3]);
                    z_top = std::max(z_top, all[4 * i + 2] + all[4 * i + 3]);
                    for (const auto &w : parameters.walls)
                      max_wall_overlap = std::max(
                        max_wall_overlap,
                        (all[4 * i + 3] - dot(Vec3(all[4 * i], all[4 * i + 1], all[4 * i + 2]) - w.point, w.normal)) /
                          all[4 * i + 3]);
                  }
                // Solid fraction sampled on a point lattice in the core of the bed:
                // two diameters from the side walls and the floor, three below the top.
                const double d  = 2. * r_max;
                Vec3         lo = parameters.lower_corner + Vec3(2. * d, 2. * d, 2. * d);
                Vec3         hi(parameters.upper_corner.x - 2. * d, parameters.upper_corner.y - 2. * d,
                        z_top - 3. * d);
                for (unsigned int k = 0; k < 2; ++k)
                  if (parameters.periodic[k])
                    {
                      lo[k] = parameters.lower_corner[k];
                      hi[k] = parameters.upper_corner[k];
                    }
                const double h = d / 8.;
                int          m[3];
                for (unsigned int k = 0; k < 3; ++k)
                  m[k] = std::max(0, static_cast<int>((hi[k] - lo[k]) / h));
                // Bin spheres on a grid of cell size d for the point test.
                int nc[3];
                for (unsigned int k = 0; k < 3; ++k)
                  nc[k] = std::max(1, static_cast<int>((hi[k] - lo[k]) / d) + 3);
                std::vector<std::vector<unsigned int>> bins(nc[0] * nc[1] * nc[2]);
                auto bin_of = [&](const double x, const unsigned int k) {
                  return std::min(nc[k] - 1, std::max(0, static_cast<int>((x - lo[k]) / d) + 1));
                };
                for (unsigned int i = 0; i < n; ++i)
                  bins[bin_of(all[4 * i], 0) + nc[0] * (bin_of(all[4 * i + 1], 1) + nc[1] * bin_of(all[4 * i + 2], 2))]
                    .push_back(i);
                unsigned long long inside = 0, total = 0;
                for (int a = 0; a < m[0]; ++a)
                  for (int b = 0; b < m[1]; ++b)
                    for (int c = 0; c < m[2]; ++c)
                      {
                        const Vec3 x = lo + Vec3((a + 0.5) * h, (b + 0.5) * h, (c + 0.5) * h);
                        ++total;
                        const int bx = bin_of(x.x, 0), by = bin_of(x.y, 1), bz = bin_of(x.z, 2);
                        bool      hit = false;
                        for (int dz = -1; dz <= 1 && !hit; ++dz)
                          for (int dy = -1; dy <= 1 && !hit; ++dy)
                            for (int dx = -1; dx <= 1 && !hit; ++dx)
                              {
                                const int cx = bx + dx, cy = by + dy, cz = bz + dz;
                                if (cx < 0 || cy < 0 || cz < 0 || cx >= nc[0] || cy >= nc[1] || cz >= nc[2])
                                  continue;
                                for (const unsigned int i : bins[cx + nc[0] * (cy + nc[1] * cz)])
                                  if (norm_square(x - Vec3(all[4 * i], all[4 * i + 1], all[4 * i + 2])) <
                                      all[4 * i + 3] * all[4 * i + 3])
                                    {
                                      hit = true;
                                      break;
                                    }
                              }
                        inside += hit;
                      }
                packing        = total > 0 ? static_cast<double>(inside) / total : 0.;
                sampled_points = total;
                bed_depth      = (z_top - parameters.lower_corner.z) / d;
              }
            double shared[4] = {packing, max_wall_overlap, sampled_points, bed_depth};
            MPI_Bcast(shared, 4, MPI_DOUBLE, 0, communicator);
            packing          = shared[0];
            max_wall_overlap = shared[1];
            const bool measured = shared[2] > 0.;
            const double lo = parameters.packing_fraction_min, hi = parameters.packing_fraction_max;
            result.value     = packing;
            result.reference = 0.5 * (lo + hi);
            result.error     = packing < lo ? (lo - packing) / lo : packing > hi ? (packing - hi) / hi : 0.;
            // A bed too shallow for the sampling core is not a failed packing.
            if (!measured)
              result.error = 0.;
            // Lost particles, a particle inside a wall (overlap above 5% of its radius)
            // or a bed still moving make the run a failure outright.
            if (n_lost > 0 || max_wall_overlap > 0.05 ||
                total_energy > parameters.kinetic_energy_threshold)
              result.error = std::max(result.error, 1.);
            check << "check: particles_lost=" << n_lost << " of " << n_inserted
                  << " max_wall_overlap_ratio_below_0.05="
                  << (max_wall_overlap <= 0.05 ? "yes" : "no")
                  << " kinetic_energy_below_threshold="
                  << (total_energy <= parameters.kinetic_energy_threshold ? "yes" : "no")
                  << " packing_fraction_in_range="
                  << (!measured ? "not_measured" : result.error == 0. ? "yes" : "no");
            result.checks.push_back(check.str());
            if (!measured)
              result.checks.push_back(
                "check: the bed is " + to_text(shared[3]) +
                " diameters deep, too shallow to measure its packing fraction: the sampling "
                "core runs from 2 diameters above the floor to 3 below the top (and 2 from the "
                "side walls), so it needs a bed deeper than 5 diameters");
            break;
          }
        default:
          break;
      }
    return result;
  }
} // namespace sluice
