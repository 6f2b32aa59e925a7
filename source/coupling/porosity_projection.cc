// The one-call projection of points with volumes (see the header): the
// particles go through a ParticleFluidExchange like the DEM's do.

#include <sluice/coupling/porosity_projection.h>

namespace sluice
{
  using namespace dealii;

  ProjectionReport project_solid_fraction(const DoFHandler<3>                  &dof_handler,
                                          const Mapping<3>                     &mapping,
                                          const std::vector<ProjectedParticle> &particles,
                                          const double                          support_radius,
                                          TrilinosWrappers::MPI::Vector        &solid_fraction,
                                          std::array<TrilinosWrappers::MPI::Vector, 3> *solid_velocity,
                                          const ProjectionScheme scheme)
  {
    ParticleFluidExchange         exchange(dof_handler, mapping, scheme, support_radius);
    std::vector<ExchangeParticle> given(particles.size());
    for (std::size_t i = 0; i < particles.size(); ++i)
      {
        const auto &p = particles[i];
        given[i].position = Vec3(p.position[0], p.position[1], p.position[2]);
        given[i].velocity = Vec3(p.velocity[0], p.velocity[1], p.velocity[2]);
        given[i].volume   = p.volume;
      }
    exchange.gather(given);
    return exchange.project(solid_fraction, 1e300, solid_velocity);
  }
} // namespace sluice
