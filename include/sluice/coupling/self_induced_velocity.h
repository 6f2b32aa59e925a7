#pragma once
// The self-induced velocity of a two-way coupled point particle, and its
// removal from the fluid velocity the drag law sees.
//
// A drag law such as Dallavalle / Di Felice wants the fluid velocity the
// particle would see without its own disturbance: the disturbance it causes is
// already inside the law. A point particle in a two-way coupled fluid deposits
// its reaction force on the mesh, the fluid there starts to move with it, and
// the velocity sampled at the particle contains that motion: it grows over
// R^2 / nu (R: the width the force is spread over) towards about F / (mu R)
// and makes the particle fall faster, the more the finer the mesh (Balachandar,
// Liu & Lakhote 2019, J. Comput. Phys. 376, 160; Horwitz & Mani 2016,
// J. Comput. Phys. 318, 85).
//
// The fluid is linear in a small disturbance, so the velocity a particle has
// induced at itself is a convolution of its force history with the response
// of the discretised fluid to one deposited impulse:
//
//   u_self(t_n) = sum_k R_{n-k}(x_n - y_k) F_k,
//   R_m(r) F = A_m(|r|) F + B_m(|r|) (r_hat . F) r_hat,
//
// F_k the reaction given to the fluid in step k, y_k where it was deposited,
// carried since with the corrected (undisturbed) fluid velocity (the Oseen
// picture: a particle moving through the fluid leaves its disturbance behind).
// A_m and B_m are measured once per scene: an unsteady solve on the scene's own
// mesh, with its kernel, time step and boundaries, of one impulse deposited at
// the domain's centre, sampled along the force (A + B) and across it (A).
// Everything the discretisation does to the disturbance (the kernel width, the
// finite elements, the stabilisation, BDF, periodic images, walls) is in the
// table; what it assumes is that the response is the same everywhere in the
// mesh (uniform cells, away from walls) and isotropic.

#include <sluice/core/vector3.h>
#include <sluice/dem/periodic_box.h>

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace sluice
{
  struct FluidParameters;
  enum class ProjectionScheme;

  /// The discretised fluid's response to a unit force held over one fluid step,
  /// m steps later, at distance s = j * spacing from where it was deposited:
  /// along[m][j] in the direction of the force, across[m][j] perpendicular to it
  /// (both the velocity component along the force, per newton) [m/(s N)].
  struct SelfResponseTable
  {
    double                           spacing = 0.;
    std::vector<std::vector<double>> along, across;

    unsigned int steps() const { return along.size(); }
    /// R_m(r) F by linear interpolation in |r|; zero beyond the last offset.
    Vec3 response(unsigned int m, const Vec3 &r, const Vec3 &force) const;
    /// The velocity per newton a force held over the whole table induces at
    /// its deposit: sum over m of along[m][0] [m/(s N)].
    double steady_response_at_deposit() const;
  };

  /// Where a response is sampled: the centre, then +-s along 'direction' and
  /// +-s along two directions across it, for s = j * spacing up to 'reach'
  /// (six points per offset j >= 1).
  std::vector<Vec3> self_response_points(const Vec3 &centre, const Vec3 &direction,
                                         double spacing, double reach);
  /// Appends one step's row to the table from the responses u (velocity along
  /// the force, per newton) at self_response_points(): along, the mean of the
  /// two points on the axis; across, of the four beside it.
  void add_self_response_row(SelfResponseTable &table, const std::vector<double> &u);

  /// Measures the table: the fluid of 'fluid' (its mesh, boundaries with every
  /// prescribed velocity set to zero, time step and BDF, no gravity and porosity
  /// 1) at rest; one step without force, one step with 'force' along 'direction'
  /// deposited at 'centre' by the scene's projection, then n_steps - 1 steps
  /// without. The velocity is sampled after each step at offsets of 'spacing' up
  /// to 'reach' along and across the direction (both signs, averaged).
  SelfResponseTable measure_self_response(const FluidParameters &fluid,
                                          ProjectionScheme scheme, double kernel_radius,
                                          double smoothing_bandwidth,
                                          const Vec3 &centre, const Vec3 &direction,
                                          double force, unsigned int n_steps, double spacing,
                                          double reach, MPI_Comm comm);

  /// Every particle's force history (replicated on all ranks, so that a particle
  /// may change rank) and the convolution with the table.
  class SelfInducedVelocity
  {
  public:
    /// box: distances between a particle and its deposits are taken as the
    /// nearest periodic image.
    SelfInducedVelocity(SelfResponseTable table, const PeriodicBox &box);

    /// One fluid step: each rank hands its particles' id, reaction force F_k and
    /// deposit position x_k - D_k (D: the particle's distance carried with the
    /// undisturbed fluid so far); all ranks receive all. Histories longer than
    /// the table forget their oldest entry; a particle absent from a step is
    /// dropped.
    void record(const std::vector<std::uint64_t> &ids, const std::vector<Vec3> &forces,
                const std::vector<Vec3> &deposits, MPI_Comm comm);

    /// The velocity particle 'id' has induced at its current deposit position
    /// x_n - D_n (after the record() of this step).
    Vec3 velocity(std::uint64_t id, const Vec3 &deposit_position) const;

    const SelfResponseTable &table() const { return response; }

    /// The table and every history as bytes for a checkpoint, and the
    /// correction back from them (throws BinaryFormatError if damaged).
    std::string                                 serialize() const;
    static std::unique_ptr<SelfInducedVelocity> deserialize(const std::string &bytes,
                                                            const PeriodicBox &box);

  private:
    struct History
    {
      std::vector<Vec3> force, deposit; // ring buffers of table.steps() entries
      unsigned int      newest = 0, size = 0;
      unsigned long     last_step = 0;
    };
    SelfResponseTable                           response;
    PeriodicBox                                 box;
    std::unordered_map<std::uint64_t, History>  histories;
    unsigned long                               step = 0;
  };
} // namespace sluice
