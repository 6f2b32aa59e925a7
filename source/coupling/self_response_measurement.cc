// The response of the discretised fluid to one particle's force
// (self_induced_velocity.h): a second, particle-free VansSolver on the scene's
// mesh receives one impulse through the scene's own projection and is sampled
// around it while the disturbance spreads.

#include <sluice/coupling/particle_fluid_exchange.h>
#include <sluice/coupling/self_induced_velocity.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>

#include <cmath>

namespace sluice
{
  using namespace dealii;

  SelfResponseTable measure_self_response(const FluidParameters &fluid,
                                          const ProjectionScheme scheme,
                                          const double kernel_radius,
                                          const double smoothing_bandwidth, const Vec3 &centre,
                                          const Vec3 &direction, const double force,
                                          const unsigned int n_steps, const double spacing,
                                          const double reach, MPI_Comm comm)
  {
    // The disturbance alone: the fluid at rest, no gravity, porosity 1, every
    // prescribed velocity zero, nothing written.
    FluidParameters fp          = fluid;
    fp.porosity                 = "1";
    fp.porosity_as_field        = false;
    fp.momentum_source          = "0; 0; 0";
    fp.momentum_source_as_field = true;
    fp.mass_source              = "0";
    fp.initial_velocity         = "0; 0; 0";
    fp.use_gravity              = false;
    fp.driving_pressure_gradient = Vec3();
    fp.adaptive                 = false;
    fp.vtu_interval             = 0.;
    fp.csv_interval             = 0.;
    fp.checkpoint_interval      = 0;
    fp.progress                 = false;
    fp.restart_from.clear();
    // Linear in the impulse: converge each step relative to its own start.
    fp.newton_tolerance          = 0.;
    fp.newton_relative_tolerance = 1e-8;

    FluidCoefficients coefficients;
    for (const auto &bc : fp.boundaries)
      coefficients.boundary_velocity.push_back(
        bc.type == BoundaryType::velocity ? std::make_shared<Functions::ZeroFunction<3>>(4) :
                                            nullptr);
    VansSolver probe(fp, coefficients, Tensor<1, 3>(), "(self-response probe)", comm);
    probe.initialize(0.);

    ParticleFluidExchange exchange(probe.porosity_dofs(), probe.get_mapping(), scheme,
                                   kernel_radius);
    exchange.set_smoothing_bandwidth(smoothing_bandwidth);
    for (const auto &bc : fp.boundaries)
      if (bc.type == BoundaryType::periodic)
        exchange.add_periodic_pair(bc.ids[0], bc.ids[1], bc.direction);
    const Vec3 e = (1. / norm(direction)) * direction;
    std::vector<ExchangeParticle> impulse;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        ExchangeParticle p;
        p.position       = centre;
        p.reaction_force = force * e;
        impulse.push_back(p);
      }
    exchange.gather(impulse);
    TrilinosWrappers::MPI::Vector solid_fraction, source;
    exchange.project(solid_fraction, 1., nullptr, &probe.momentum_source_dofs(), &source);
    TrilinosWrappers::MPI::Vector no_source(source);
    no_source = 0.;

    std::vector<Point<3>> points;
    for (const Vec3 &x : self_response_points(centre, e, spacing, reach))
      points.emplace_back(x.x, x.y, x.z);

    SelfResponseTable table;
    table.spacing = spacing;
    const double dt = fp.time_step;
    probe.set_momentum_source(no_source); // a first step at rest: the impulse gets BDF2
    probe.advance(dt);
    for (unsigned int m = 0; m < n_steps; ++m)
      {
        probe.set_momentum_source(m == 0 ? source : no_source);
        probe.advance(dt);
        const std::vector<FluidSample> samples = probe.sample(points);
        std::vector<double>            u(points.size(), 0.);
        for (unsigned int q = 0; q < points.size(); ++q)
          if (samples[q].found)
            u[q] = (samples[q].velocity[0] * e.x + samples[q].velocity[1] * e.y +
                    samples[q].velocity[2] * e.z) / force;
        Utilities::MPI::sum(u, comm, u);
        // A point on a face between two ranks' cells is found by both.
        std::vector<double> found(points.size(), 0.);
        for (unsigned int q = 0; q < points.size(); ++q)
          found[q] = samples[q].found ? 1. : 0.;
        Utilities::MPI::sum(found, comm, found);
        for (unsigned int q = 0; q < points.size(); ++q)
          u[q] = found[q] > 0. ? u[q] / found[q] : 0.;

        add_self_response_row(table, u);
      }
    return table;
  }
} // namespace sluice
