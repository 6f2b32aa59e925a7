// Finding the particle behind bad input or a failed run (see the header).

#include <sluice/core/mpi_extremum.h>
#include <sluice/dem/mesh_contact.h>
#include <sluice/dem/state_check.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// What one rank found: a score (the worst wins), and a payload to report.
    struct Finding
    {
      double                score = -std::numeric_limits<double>::infinity();
      std::array<double, 8> data{};
    };

    /// The finding with the highest score over all ranks, on every rank.
    Finding worst_over_ranks(const Finding &local, MPI_Comm comm)
    {
      const RankedValue best   = rank_of_greatest(local.score, comm);
      Finding           global = local;
      global.score             = best.value;
      share_from(best.rank, global.data.data(), global.data.size(), comm);
      return global;
    }

    std::string point_text(const double *x)
    {
      return "(" + to_text(x[0]) + ", " + to_text(x[1]) + ", " + to_text(x[2]) + ")";
    }

    /// A particle's id; in a clump scene (member_stride > 0) the contact
    /// passes see members, named as their body's id and their number in it.
    std::string id_text(const double id, const unsigned int member_stride = 0)
    {
      const auto n = static_cast<unsigned long long>(id);
      if (member_stride == 0)
        return std::to_string(n);
      return std::to_string(n / member_stride) + " (member " + std::to_string(n % member_stride) +
             " of that clump)";
    }

    std::string where_text(const StepInfo &where)
    {
      return "at step " + std::to_string(where.step) + " (t = " + to_text(where.time) + " s)";
    }

    bool finite(const Vec3 &v)
    {
      return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    }

    /// The deepest overlap of a local particle with a listed partner or with any
    /// wall, relative to the smaller radius; coincident centres score infinity.
    /// data: id, partner id, wall index (-1 for a pair), overlap ratio, centre of
    /// the local particle (3), signed distance to the wall.
    Finding deepest_overlap(const ParticleStorage &P, const NeighbourList &L,
                            const WallSet &walls, const PeriodicBox &box,
                            const bool all_walls, double &n_above, const double bound)
    {
      Finding worst;
      n_above = 0.;
      auto consider = [&](const double score, const unsigned int i, const double partner,
                          const double wall, const double ratio, const double distance) {
        if (score > bound)
          n_above += 1.;
        if (score > worst.score)
          {
            worst.score = score;
            worst.data  = {{static_cast<double>(P.id[i]), partner, wall, ratio, P.position[i].x,
                            P.position[i].y, P.position[i].z, distance}};
          }
      };
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          for (unsigned int k = L.offset[i]; k < L.offset[i + 1]; ++k)
            {
              const unsigned int j       = L.partner[k];
              const Vec3         d       = box.minimum_image(P.position[i] - P.position[j]);
              const double       dist    = norm(d);
              const double       r_small = std::min(P.radius[i], P.radius[j]);
              const double       ratio   = (P.radius[i] + P.radius[j] - dist) / r_small;
              const bool coincident = dist <= 1e-12 * (P.radius[i] + P.radius[j]);
              consider(coincident ? std::numeric_limits<double>::infinity() : ratio, i,
                       P.id[j], -1., ratio, dist);
            }
          auto wall_overlap = [&](const unsigned int w) {
            const double distance = dot(P.position[i] - walls[w].point, walls[w].normal);
            const double ratio    = (P.radius[i] - distance) / P.radius[i];
            consider(ratio, i, -1., w, ratio, distance);
          };
          if (all_walls)
            for (unsigned int w = 0; w < walls.n_planes(); ++w)
              wall_overlap(w);
          else
            for (unsigned int k = L.wall_offset[i]; k < L.wall_offset[i + 1]; ++k)
              wall_overlap(L.wall_partner[k]);
          // Mesh walls: the contacts with the listed triangles (a centre
          // behind a mesh is not told from one in front of it).
          for (unsigned int k = L.mesh_offset[i]; k < L.mesh_offset[i + 1];)
            {
              const unsigned int        m = L.mesh_candidate[k].mesh;
              std::vector<unsigned int> triangles;
              for (; k < L.mesh_offset[i + 1] && L.mesh_candidate[k].mesh == m; ++k)
                triangles.push_back(L.mesh_candidate[k].triangle);
              std::vector<MeshContact> contacts;
              mesh_contacts(walls.meshes()[m].mesh(), P.position[i], P.radius[i], triangles,
                            contacts);
              for (const MeshContact &c : contacts)
                consider(c.overlap / P.radius[i], i, -1., walls.n_planes() + m,
                         c.overlap / P.radius[i], P.radius[i] - c.overlap);
            }
        }
      return worst;
    }

    /// "particles 3 and 7 overlap by ..." or "particle 3 and wall 'floor' ...".
    std::string overlap_text(const Finding &f, const WallSet &walls, const unsigned int stride)
    {
      const double *d = f.data.data();
      std::string   s;
      if (d[2] < 0.)
        {
          s = "particles " + id_text(d[0], stride) + " and " + id_text(d[1], stride);
          if (std::isinf(f.score))
            return s + " are at the same position " + point_text(d + 4);
          return s + " overlap by " + to_text(d[3]) + " of the smaller radius (particle " +
                 id_text(d[0], stride) + " at " + point_text(d + 4) + ")";
        }
      s = "particle " + id_text(d[0], stride) + " at " + point_text(d + 4) + " and wall '" +
          walls.name(static_cast<unsigned int>(d[2])) + "'";
      if (d[7] <= 0.)
        return s + ": its centre is " + (d[7] < 0. ? "behind" : "on") + " the wall (distance " +
               to_text(d[7]) + " m)";
      return s + " overlap by " + to_text(d[3]) + " of its radius";
    }
  } // namespace

  void check_initial_state(const ParticleStorage &particles, const NeighbourList &list,
                           const WallSet &walls, const PeriodicBox &box,
                           const double max_overlap, const std::string &file_name,
                           MPI_Comm comm, const unsigned int member_stride)
  {
    double        n_above = 0.;
    const Finding local   = deepest_overlap(particles, list, walls, box, true, n_above, max_overlap);
    MPI_Allreduce(MPI_IN_PLACE, &n_above, 1, MPI_DOUBLE, MPI_SUM, comm);
    const Finding worst = worst_over_ranks(local, comm);
    if (!(worst.score > max_overlap))
      return;
    std::ostringstream msg;
    msg << "error in '" << file_name << "': the initial state cannot be simulated: "
        << overlap_text(worst, walls, member_stride);
    if (n_above > 1.)
      msg << "; " << static_cast<unsigned long long>(n_above)
          << " contacts in all exceed the limit";
    msg << " (entry 'insertion/maximum initial overlap' = " << to_text(max_overlap)
        << " of the smaller radius; a centre must lie in front of every wall). Move the "
           "particles apart, or insert them by 'lattice' or 'random'";
    throw InputError(msg.str());
  }

  void fail_non_finite(const ParticleStorage &P, const StepInfo &where, MPI_Comm comm)
  {
    Finding local;
    for (unsigned int i = 0; i < P.n_local && local.score < 0.; ++i)
      if (!finite(P.position[i]) || !finite(P.velocity[i]) || !finite(P.angular_velocity[i]) ||
          !finite(P.force[i]))
        {
          local.score = 1.;
          local.data  = {{static_cast<double>(P.id[i]), norm(P.velocity[i]), norm(P.force[i])}};
        }
    const Finding worst = worst_over_ranks(local, comm);
    std::ostringstream msg;
    msg << "the simulation became non-finite " << where_text(where) << ": particle "
        << id_text(worst.data[0], where.member_stride) << " has speed " << to_text(worst.data[1]) << " m/s and force "
        << to_text(worst.data[2])
        << " N. Likely causes: a time step above the stability limit of the stiffest contact "
           "('simulation/time step', now "
        << to_text(where.dt)
        << " s), particles or walls that overlap deeply, or a body force far beyond the "
           "contact stiffness ('simulation/gravity')";
    throw SimulationFailure(msg.str());
  }

  void fail_fast_particle(const ParticleStorage &P, const StepInfo &where, MPI_Comm comm)
  {
    Finding local;
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        const double speed = norm(P.velocity[i]);
        if (speed > local.score)
          {
            local.score = speed;
            local.data  = {{static_cast<double>(P.id[i]), P.radius[i], P.position[i].x,
                            P.position[i].y, P.position[i].z}};
          }
      }
    const Finding worst = worst_over_ranks(local, comm);
    std::ostringstream msg;
    msg << "particle " << id_text(worst.data[0], where.member_stride) << " at "
        << point_text(worst.data.data() + 2)
        << " moves " << to_text(worst.score * where.dt) << " m in one step " << where_text(where)
        << " (speed " << to_text(worst.score) << " m/s, step " << to_text(where.dt)
        << " s), more than half the smallest radius (" << to_text(where.max_step_displacement)
        << " m): its contacts cannot be resolved and it may pass through a particle or a "
           "wall. Likely causes: a speed far above 'simulation/characteristic velocity' ("
        << to_text(where.characteristic_velocity)
        << " m/s), on which the time step is based, an explosive overlap, or an extreme "
           "'simulation/gravity'; raise the characteristic velocity or lower 'simulation/time "
           "step'";
    throw SimulationFailure(msg.str());
  }

  void fail_deep_overlap(const ParticleStorage &P, const NeighbourList &L,
                         const WallSet &walls, const PeriodicBox &box,
                         const double max_overlap, const StepInfo &where, MPI_Comm comm)
  {
    double        n_above = 0.;
    const Finding local   = deepest_overlap(P, L, walls, box, false, n_above, max_overlap);
    const Finding worst   = worst_over_ranks(local, comm);
    std::ostringstream msg;
    msg << "an overlap exceeded 'simulation/maximum overlap' = " << to_text(max_overlap)
        << " of the smaller radius " << where_text(where) << ": "
        << overlap_text(worst, walls, where.member_stride)
        << ". Likely causes: contacts too soft for the impact speeds (raise 'young modulus', "
           "or 'simulation/characteristic velocity' so that the step follows), a time step too "
           "large ('simulation/time step', now "
        << to_text(where.dt) << " s), or a body force that crushes the bed ('simulation/gravity')";
    throw SimulationFailure(msg.str());
  }
} // namespace sluice
