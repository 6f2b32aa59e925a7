#pragma once
// The particles as the fluid sees them: a dealii::Particles::ParticleHandler on
// the fluid's own distributed mesh. Each coupling step the DEM's particles
// (wherever the DEM keeps them) are inserted into it, which sends every particle
// to the rank that owns its fluid cell and gives its reference coordinates
// there. With the particles sorted into cells, the two directions of the
// exchange are one loop over cells each:
//  - project(): the particles' volume (-> solid fraction, porosity), momentum
//    (-> mean solid velocity) and reaction force (-> momentum source of the
//    fluid) deposited with one set of weights per particle, either the Gao & Sun
//    kernel (Eqs. 23-25, K = (1 - xi^2)^4 over a sphere of radius R_s) or the
//    finite-element shape functions of the particle's cell at its centre
//    ('centroid'). Both conserve every deposited quantity to round-off.
//  - sample(): the fluid (velocity, gradients, porosity) at every particle,
//    evaluated per cell with one FEValues, and sent back to the rank and index
//    the particle came from.

#include <sluice/core/coupling_parameters.h>
#include <sluice/core/vector3.h>
#include <sluice/coupling/fluid_backend.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace sluice
{
  class VansSolver;
  struct FluidSample;

  /// The conservation record of one projection (sums over all ranks).
  struct ProjectionReport
  {
    double               deposited_volume = 0.; // sum of the particles' volumes
    double               field_integral   = 0.; // integral of the projected solid fraction
    dealii::Tensor<1, 3> particle_momentum;     // sum of V_p v_p
    dealii::Tensor<1, 3> field_momentum;        // sum_i m_i s_i u_s,i
    dealii::Tensor<1, 3> particle_force;        // sum of the reaction forces
    dealii::Tensor<1, 3> field_force;           // integral of the momentum-source field
    double               particle_drag = 0.;    // sum of the drag coefficients [kg/s]
    double               field_drag    = 0.;    // integral of the drag-coefficient field
    unsigned int         clipped_nodes = 0;     // nodes whose solid fraction hit the cap
  };

  class ParticleFluidExchange
  {
  public:
    /// scalar_dofs: a scalar FE_Q DoFHandler on the fluid mesh (the solver's
    /// porosity dofs). A kernel radius above the smallest cell is refused in
    /// project() (the support must stay within the cell's vertex neighbours).
    ParticleFluidExchange(const dealii::DoFHandler<3> &scalar_dofs,
                          const dealii::Mapping<3> &mapping, ProjectionScheme scheme,
                          double kernel_radius);
    ~ParticleFluidExchange();

    /// A periodic pair of mesh boundaries (ids, direction 0..2): deposits on
    /// the two faces' nodes are added up and the field takes one value there,
    /// as the fluid's own periodic constraints do.
    void add_periodic_pair(unsigned int first_id, unsigned int second_id, unsigned int direction);

    /// Diffusion-based coarse graining on top of the projection (Sun & Xiao
    /// 2015): every deposited field is diffused to a width b [m] (pseudo time
    /// b^2/4), conserving its integral; 0 (the default) leaves it as deposited.
    void set_smoothing_bandwidth(double b);

    /// Moves the particles into the fluid mesh's ParticleHandler. Returns the
    /// number (all ranks) that lie outside the fluid mesh; those are neither
    /// projected nor sampled.
    unsigned long long gather(const std::vector<ExchangeParticle> &particles);

    /// Projects what gather() received. solid_fraction: a locally owned vector
    /// on the scalar dofs; its nodal values are capped at max_solid_fraction
    /// (report.clipped_nodes counts them; volume is then not conserved there).
    /// solid_velocity (optional): the mean solid velocity per component.
    /// force_dofs/force_density (optional): a FE_Q^3 DoFHandler of the same
    /// degree and a locally owned vector on it, the reaction force per volume.
    /// drag_density (optional): the particles' drag coefficients per volume,
    /// a locally owned vector on the scalar dofs (the semi-implicit exchange).
    ProjectionReport project(dealii::TrilinosWrappers::MPI::Vector &solid_fraction,
                             double max_solid_fraction = 1.,
                             std::array<dealii::TrilinosWrappers::MPI::Vector, 3> *solid_velocity =
                               nullptr,
                             const dealii::DoFHandler<3>           *force_dofs    = nullptr,
                             dealii::TrilinosWrappers::MPI::Vector *force_density = nullptr,
                             dealii::TrilinosWrappers::MPI::Vector *drag_density  = nullptr) const;

    /// The fluid at every particle given to the last gather(), in that order
    /// (found = false for a particle outside the fluid mesh). The divergence
    /// of the viscous stress, which needs second derivatives, only with
    /// 'viscous_divergence' (else it stays zero).
    std::vector<FluidSample> sample(const VansSolver &fluid, bool viscous_divergence) const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> impl;
  };
} // namespace sluice
