// What a clump scene writes (see the header).

#include <sluice/dem/clump_output.h>
#include <sluice/dem/particle_csv.h>
#include <sluice/dem/particle_exchange.h>

namespace sluice
{
  ParticleFieldRegistry member_output_fields(const ParticleFieldRegistry &body_fields)
  {
    ParticleFieldRegistry out;
    const ParticleFieldRegistry::Use shown{false, true, false};
    out.declare("body_id", 1, shown);
    out.declare("orientation", 4, shown);
    for (const ParticleField &f : body_fields.fields())
      if (f.output)
        out.declare(f.name, f.size, shown);
    return out;
  }

  ParticleStorage member_snapshot(const ParticleStorage &members, const ClumpSystem &clumps,
                                  const ParticleFieldRegistry &body_fields)
  {
    const ParticleFieldRegistry fields = member_output_fields(body_fields);
    ParticleStorage             S      = members;
    S.n_extra                          = fields.doubles_per_particle();
    S.extra.assign(S.n_extra * S.size(), 0.);
    const unsigned int q_at = body_fields.find(clump_fields::orientation)->offset;
    for (unsigned int i = 0; i < S.n_local; ++i)
      {
        const unsigned int b = clumps.member_body()[i];
        const double      *e = clumps.bodies.extra_of(b);
        double            *o = S.extra_of(i);
        o[0]                 = clumps.bodies.id[b];
        for (unsigned int k = 0; k < 4; ++k)
          o[1 + k] = e[q_at + k];
        for (const ParticleField &f : body_fields.fields())
          if (f.output)
            {
              const unsigned int at = fields.find(f.name)->offset;
              for (unsigned int c = 0; c < f.size; ++c)
                o[at + c] = e[f.offset + c];
            }
      }
    return S;
  }

  void write_member_csv(const ParticleStorage &M, const ClumpSystem &clumps, const double time,
                        const std::string &directory, const std::string &base_name,
                        const unsigned int index, MPI_Comm comm)
  {
    constexpr int       n_fields = 7;
    std::vector<double> mine;
    mine.reserve(n_fields * M.n_local);
    for (unsigned int i = 0; i < M.n_local; ++i)
      for (const double v : {static_cast<double>(M.id[i]),
                             static_cast<double>(clumps.bodies.id[clumps.member_body()[i]]),
                             double(M.type[i]), M.radius[i], M.position[i].x, M.position[i].y,
                             M.position[i].z})
        mine.push_back(v);
    write_rows_by_id(mine, n_fields, 3, "id,body_id,type,radius,x,y,z", time,
                     particle_csv_path(directory, base_name, index, "members"), comm);
  }

  void write_body_csv(const ClumpSystem &clumps, const double time, const std::string &directory,
                      const std::string &base_name, const unsigned int index, MPI_Comm comm)
  {
    constexpr int          n_fields = 23;
    const ParticleStorage &B        = clumps.bodies;
    std::vector<double>    mine;
    mine.reserve(n_fields * B.n_local);
    for (unsigned int b = 0; b < B.n_local; ++b)
      {
        const Eigen::Quaterniond q = clumps.rotation_of(b).orientation;
        const unsigned int template_index =
          &clumps.template_of(b) - clumps.templates.data();
        for (const double v : {static_cast<double>(B.id[b]), double(template_index),
                               double(B.type[b]), clumps.scale_of(b)})
          mine.push_back(v);
        for (unsigned int d = 0; d < 3; ++d)
          mine.push_back(B.position[b][d]);
        for (const double v : {q.w(), q.x(), q.y(), q.z()})
          mine.push_back(v);
        for (const Vec3 *v : {&B.velocity[b], &B.angular_velocity[b], &B.force[b], &B.torque[b]})
          for (unsigned int d = 0; d < 3; ++d)
            mine.push_back((*v)[d]);
      }
    write_rows_by_id(mine, n_fields, 3,
                     "id,template,type,scale,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,"
                     "tz",
                     time, particle_csv_path(directory, base_name, index), comm);
  }
} // namespace sluice
