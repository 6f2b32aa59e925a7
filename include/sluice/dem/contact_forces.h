#pragma once
// Contact forces and torques of all listed pairs and wall contacts.
//
// The contact law is a template parameter: one instantiation per combination of
// normal law, tangential history (on/off), rolling model, wall motion and
// contact observer (on/off) is compiled, and the scene picks one function
// pointer at set-up. No virtual call, no branch on the law
// and no map lookup happens per contact.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/contact_observer.h>
#include <sluice/dem/contact_properties.h>
#include <sluice/dem/neighbour_list.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/dem/wall_set.h>

#include <vector>

namespace sluice
{
  struct ContactStatistics
  {
    double n_particle_contacts = 0.; // pairs with a ghost count 1/2 on each rank
    double n_wall_contacts     = 0.;
    double max_overlap_ratio   = 0.; // overlap / smaller radius
  };

  /// observer: null unless the kernel was selected with 'observed'.
  using ContactForceKernel = ContactStatistics (*)(ParticleStorage &, NeighbourList &,
                                                   const ContactProperties &,
                                                   const WallSet &,
                                                   const PeriodicBox &, double dt,
                                                   std::vector<Vec3> &wall_forces,
                                                   ContactObserver *observer);

  /// The kernel for a normal law, with or without tangential history, a
  /// rolling-resistance model, walls at rest or moving (a scene whose walls
  /// stay put does not pay for the wall velocity at each wall contact), and
  /// with or without a contact observer (contact_observer.h; a scene without
  /// one does not pay for the contact-start test). lane_width: how many
  /// Hertz–Mindlin contacts the sweep computes at a time (contact_lanes.h),
  /// 2 or 4, or 0 for widest_contact_lanes(); the results are the same.
  ContactForceKernel select_contact_kernel(NormalContactModel normal, bool tangential,
                                           RollingResistanceModel rolling, bool moving_walls,
                                           bool observed = false, unsigned int lane_width = 0);

  /// 4 where the processor has AVX2, else 2.
  unsigned int widest_contact_lanes();
} // namespace sluice
