#pragma once
// The contact forces between the particles and the triangle-mesh walls: a
// second pass after the particle and plane contacts (contact_forces.h), run
// only in a scene that has meshes.
//
// Each local particle's contacts come from its candidate triangles
// (NeighbourList::mesh_candidate) by the one-contact-per-patch rule
// (mesh_contact.h), and feel the same contact law as a plane
// (contact_law.h) with the mesh's velocity at the contact point. The
// tangential history follows a contact from triangle to triangle: a new
// contact takes the history of the last pass's contact on the same triangle,
// else that of the last pass's contact (same mesh, not taken yet) whose
// triangle now holds the point nearest to it, if nearer than the radius.
// The pass adds the particles' forces and torques, and each mesh's force, its
// torque about the motion origin and the power it puts into the particles,
// P = sum F . v_wall(contact point) (a mill's net power draw).

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/contact_forces.h>
#include <sluice/dem/contact_observer.h>
#include <sluice/dem/contact_properties.h>
#include <sluice/dem/neighbour_list.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/wall_set.h>

#include <vector>

namespace sluice
{
  /// Per mesh wall: the torque about its motion origin and the power, summed
  /// over this rank's contacts in the last pass (the force is in the wall
  /// forces, at index n_planes + m).
  struct MeshWallLoads
  {
    std::vector<Vec3>   torque;
    std::vector<double> power;
  };

  /// Adds the mesh contacts' forces to P.force/torque and wall_forces, sets
  /// 'loads' and adds to 'stats'. observer: null unless selected with 'observed'.
  using MeshContactKernel = void (*)(ParticleStorage &, NeighbourList &,
                                     const ContactProperties &, const WallSet &, double dt,
                                     std::vector<Vec3> &wall_forces, MeshWallLoads &loads,
                                     ContactObserver *observer, ContactStatistics &stats);

  MeshContactKernel select_mesh_contact_kernel(NormalContactModel normal, bool tangential,
                                               RollingResistanceModel rolling, bool observed);
} // namespace sluice
