#pragma once
// Verlet neighbour lists built from a cell grid (cell_grid.h) in O(N) (Allen &
// Tildesley; Bell, Yu & Mucha 2005 use cells of twice the largest radius). Each
// pair is listed once, from its local particle with the lower index; pairs with
// ghosts are listed from the local side. A list stays valid until some particle has moved more than half
// the skin. The tangential history of each contact lives in a flat array parallel
// to the list and is carried across rebuilds by particle ids.

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/cell_grid.h>
#include <sluice/dem/contact_history_map.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/periodic_box.h>
#include <sluice/dem/wall_set.h>

#include <cstdint>
#include <vector>

namespace sluice
{
  /// A triangle of a mesh wall: the mesh's index among the meshes, and the
  /// triangle's in the mesh.
  struct MeshTriangle
  {
    unsigned int mesh, triangle;
  };

  /// A contact with a mesh wall as the last contact pass left it: the triangle
  /// it was attributed to and its tangential history. In the history map its
  /// key is (particle id, n_planes + the triangle's number among all meshes'
  /// triangles, wall), so it travels with the particle like a plane's.
  struct MeshContactHistory
  {
    MeshTriangle triangle;
    Vec3         history;
  };

  class NeighbourList
  {
  public:
    /// Rebuilds the particle-particle and particle-wall lists, taking the
    /// tangential histories from the map (nothing is kept if keep_history is false).
    void build(const ParticleStorage &particles, const PeriodicBox &box,
               const WallSet &walls, double cutoff_radius, double skin,
               bool keep_history, const ContactHistoryMap &histories);

    /// The nonzero histories of the current lists, keyed by particle ids.
    void collect_histories(const ParticleStorage &particles, ContactHistoryMap &histories) const;

    /// Largest squared displacement of a local particle since the last build;
    /// infinity if a position is not finite (which max() alone would skip).
    double max_displacement_square(const ParticleStorage &particles) const;

    unsigned int n_pairs() const { return partner.size(); }

    // Compressed rows: the partners of local particle i are
    // partner[offset[i]] ... partner[offset[i+1]-1].
    std::vector<unsigned int> offset, partner;
    std::vector<Vec3>         history; // empty in frictionless scenes

    // Scratch of the contact pass (contact_forces.cc), rewritten every step:
    // the listed pairs that touch, touching[touching_offset[i] ...
    // touching_offset[i+1] - 1] for local particle i (indices into partner).
    std::vector<unsigned int> touching_offset, touching;
    // 1 where history[k] may be nonzero (pair k touched at the last pass),
    // so that the pass zeroes a history only when its contact ends. Derived
    // state, not saved: whatever rewrites history empties it, and the next
    // pass starts from all ones.
    std::vector<std::uint8_t> history_may_be_nonzero;

    std::vector<unsigned int> wall_offset, wall_partner;
    std::vector<Vec3>         wall_history;

    // Mesh walls: the triangles within the radius plus the skin of local
    // particle i at the build, mesh_candidate[mesh_offset[i] ...
    // mesh_offset[i+1] - 1], sorted by mesh; and the contacts of the last
    // contact pass with their histories, mesh_contact[mesh_contact_offset[i]
    // ...] (rewritten by every pass; mesh_contact_forces.h).
    std::vector<unsigned int>       mesh_offset;
    std::vector<MeshTriangle>       mesh_candidate;
    std::vector<unsigned int>       mesh_contact_offset;
    std::vector<MeshContactHistory> mesh_contact;

    std::vector<Vec3> position_at_build;
    unsigned int      n_builds = 0;

    // In a clump scene, the stride of the member ids (clump_system.h): two
    // members of one body (id / stride equal) are never listed. 0: spheres.
    unsigned int member_stride = 0;

  private:
    /// The mesh candidates, from the walls' triangle bins on the list's grid.
    void build_mesh_candidates(const ParticleStorage &particles, const PeriodicBox &box,
                               const WallSet &walls, const int n_cells[3],
                               double cutoff_radius, double skin);
    /// The mesh contacts' histories from the map (keys of mesh triangles).
    void restore_mesh_histories(const ParticleStorage &particles, const WallSet &walls,
                                const ContactHistoryMap &histories);

    CellGrid                  grid;
    // For collect_histories(): how the walls number the mesh triangles.
    unsigned int              n_planes = 0;
    std::vector<unsigned int> triangle_offset;
  };
} // namespace sluice
