#pragma once
// What a clump scene writes (clump_system.h): its members in the particle
// .vtu series, each with its body's id and orientation (and the body's other
// output fields), so that ParaView draws the true shapes; and, instead of the
// sphere dump, one CSV row per body: id, template, type, scale, centroid,
// orientation quaternion, velocity, angular velocity, force and torque (SI).

#include <sluice/dem/clump_system.h>
#include <sluice/dem/particle_fields.h>

#include <mpi.h>

#include <string>

namespace sluice
{
  /// The fields of a member snapshot: 'body_id', 'orientation' (w, x, y, z)
  /// and every body field marked for output.
  ParticleFieldRegistry member_output_fields(const ParticleFieldRegistry &body_fields);

  /// The owned members with the fields of member_output_fields() filled.
  ParticleStorage member_snapshot(const ParticleStorage &members, const ClumpSystem &clumps,
                                  const ParticleFieldRegistry &body_fields);

  /// Collective: <directory>/<base_name>_members_<index>.csv with a row per
  /// member sphere: id, body_id, type, radius, x, y, z.
  void write_member_csv(const ParticleStorage &members, const ClumpSystem &clumps, double time,
                        const std::string &directory, const std::string &base_name,
                        unsigned int index, MPI_Comm comm);

  /// Collective: <directory>/<base_name>_state_<index>.csv with a row per body.
  void write_body_csv(const ClumpSystem &clumps, double time, const std::string &directory,
                      const std::string &base_name, unsigned int index, MPI_Comm comm);
} // namespace sluice
