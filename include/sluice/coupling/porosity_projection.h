#pragma once
// Solid volume fraction of a set of particles as a finite-element field, by
// kernel averaging (Gao & Sun Eqs. 23-25, K(xi) = (1 - xi^2)^4 for
// xi = r / R_s < 1): a one-call form of ParticleFluidExchange::project() for
// particles given as points with a volume and a velocity.
//
// Each particle spreads its volume over the quadrature points within R_s, with
// weights normalised by the kernel's integral over the part of the support that
// lies inside the domain: a particle next to a wall deposits its whole volume,
// not the fraction of the kernel that happens to be inside. The deposit goes
// into b_i = sum_p V_p sum_q phi_i(x_q) w_pq, and the nodal values are
// s_i = b_i / m_i with the lumped mass m_i = integral of phi_i: because the
// shape functions sum to one, the integral of the field equals sum_p V_p to
// round-off, the field is never negative, and ranks exchange only the entries
// of b that belong to dofs they do not own.

#include <sluice/coupling/particle_fluid_exchange.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>

#include <array>
#include <vector>

namespace sluice
{
  struct ProjectedParticle
  {
    dealii::Point<3>     position;
    double               volume = 0.;
    dealii::Tensor<1, 3> velocity;
  };

  /// particles: each on exactly one rank (any rank). support_radius R_s must not
  /// exceed the smallest cell size, so that the support stays within the
  /// cell's neighbours (one ghost layer); otherwise std::invalid_argument names
  /// the limit. solid_fraction: a locally owned vector on dof_handler (scalar
  /// FE_Q). solid_velocity (if not null): the mean solid velocity, one locally
  /// owned vector per component, projected with the same weights times v_p and
  /// divided by the solid deposit (0 where no particle reaches), so that the
  /// solid momentum sum_i m_i s_i u_s,i equals sum_p V_p v_p to round-off.
  ProjectionReport project_solid_fraction(
    const dealii::DoFHandler<3> &dof_handler, const dealii::Mapping<3> &mapping,
    const std::vector<ProjectedParticle> &particles, double support_radius,
    dealii::TrilinosWrappers::MPI::Vector                   &solid_fraction,
    std::array<dealii::TrilinosWrappers::MPI::Vector, 3>     *solid_velocity = nullptr,
    ProjectionScheme scheme = ProjectionScheme::kernel);
} // namespace sluice
