// The VANS solver behind the coupled scene's fluid interface (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/coupling/particle_fluid_exchange.h>
#include <sluice/coupling/vans_backend.h>
#include <sluice/fluid/fluid_coefficients.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    Vec3 to_vec(const Tensor<1, 3> &t) { return Vec3(t[0], t[1], t[2]); }
  } // namespace

  struct VansBackend::Implementation
  {
    Implementation(const FluidParameters &fp, const Vec3 &g, const std::string &file,
                   MPI_Comm comm)
      : p(fp), comm(comm)
      , fluid(fp, coefficients_from_prm(fp), Tensor<1, 3>({g.x, g.y, g.z}), file, comm)
    {}

    FluidParameters                        p;
    CouplingParameters                     c;
    double                                 max_solid_fraction = 1.;
    MPI_Comm                               comm;
    VansSolver                             fluid;
    std::unique_ptr<ParticleFluidExchange> exchange;
    TrilinosWrappers::MPI::Vector          solid_fraction, force_density, drag_density;
  };

  VansBackend::VansBackend(const FluidParameters &fp, const CouplingParameters &c,
                           const Vec3 &gravity, const double d_max, const std::string &file_name,
                           MPI_Comm comm)
    : impl(std::make_unique<Implementation>(fp, gravity, file_name, comm))
  {
    const auto fail = [&](const std::string &entry, const std::string &what) {
      throw InputError("error in '" + file_name + "': entry '" + entry + "' " + what);
    };
    impl->c                  = c;
    impl->max_solid_fraction = c.max_solid_fraction;
    VansSolver &fluid        = impl->fluid;
    fluid.initialize(0.);

    smallest_cell = std::numeric_limits<double>::max();
    for (const auto &cell : fluid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        smallest_cell = std::min(smallest_cell, cell->minimum_vertex_distance());
    smallest_cell = Utilities::MPI::min(smallest_cell, comm);
    radius        = c.kernel_radius > 0. ? c.kernel_radius : smallest_cell;
    if (c.two_way && c.projection == ProjectionScheme::kernel)
      {
        if (radius < 2. * d_max * (1. - 1e-12))
          fail("cfd-dem/kernel radius",
               "= " + to_text(radius) + " m" +
                 (c.kernel_radius > 0. ? "" : " (the smallest fluid cell)") +
                 " is below two particle diameters (" + to_text(2. * d_max) +
                 " m); allowed: 2 d <= R_s <= smallest fluid cell (" + to_text(smallest_cell) +
                 " m): use a coarser fluid mesh or the 'centroid' projection");
        if (radius > smallest_cell * (1. + 1e-10))
          fail("cfd-dem/kernel radius", "= " + to_text(radius) +
                                          " m exceeds the smallest fluid cell (" +
                                          to_text(smallest_cell) + " m)");
      }
    impl->exchange = std::make_unique<ParticleFluidExchange>(fluid.porosity_dofs(),
                                                             fluid.get_mapping(), c.projection,
                                                             radius);
    impl->exchange->set_smoothing_bandwidth(c.smoothing_bandwidth);
    for (const auto &bc : fp.boundaries)
      if (bc.type == BoundaryType::periodic)
        impl->exchange->add_periodic_pair(bc.ids[0], bc.ids[1], bc.direction);
  }

  VansBackend::~VansBackend() = default;

  void VansBackend::describe(std::ostream &out) const
  {
    out << "fluid cells: " << impl->fluid.n_active_cells()
        << ", fluid dofs: " << impl->fluid.n_dofs();
  }

  unsigned long long VansBackend::receive(const std::vector<ExchangeParticle> &particles)
  {
    return impl->exchange->gather(particles);
  }

  DepositReport VansBackend::deposit(const bool initial)
  {
    VansSolver            &fluid  = impl->fluid;
    const bool             semi_implicit = impl->c.semi_implicit_drag;
    const ProjectionReport report        = impl->exchange->project(
      impl->solid_fraction, impl->max_solid_fraction, nullptr, &fluid.momentum_source_dofs(),
      &impl->force_density, semi_implicit ? &impl->drag_density : nullptr);
    TrilinosWrappers::MPI::Vector porosity(impl->solid_fraction);
    porosity = 1.;
    porosity -= impl->solid_fraction;
    if (initial)
      fluid.set_initial_porosity(porosity);
    else
      fluid.set_porosity(porosity);
    fluid.set_momentum_source(impl->force_density);
    if (semi_implicit)
      fluid.set_exchange_drag(impl->drag_density);
    DepositReport r;
    r.particle_drag  = report.particle_drag;
    r.field_drag     = report.field_drag;
    r.particle_force = to_vec(report.particle_force);
    r.field_force    = to_vec(report.field_force);
    r.clipped_nodes  = report.clipped_nodes;
    return r;
  }

  void VansBackend::clear_momentum_source()
  {
    TrilinosWrappers::MPI::Vector no_source(impl->force_density);
    no_source = 0.;
    impl->fluid.set_momentum_source(no_source);
  }

  NewtonReport VansBackend::solve_steady()
  {
    return impl->fluid.solve_steady();
  }

  NewtonReport VansBackend::advance(const double dt)
  {
    const NewtonReport r = impl->fluid.advance(dt);
    if (impl->p.adaptive && impl->fluid.steps_done() % impl->p.refinement_interval == 0)
      impl->fluid.adapt_mesh();
    return r;
  }

  std::vector<ParticleFluidSample> VansBackend::sample() const
  {
    // Second derivatives cost a third to a half of the sampling: only for
    // the force that reads them.
    const std::vector<FluidSample> samples =
      impl->exchange->sample(impl->fluid, impl->c.viscous_force);
    std::vector<ParticleFluidSample> out(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k)
      {
        const FluidSample   &s = samples[k];
        ParticleFluidSample &o = out[k];
        o.found                = s.found;
        o.velocity             = to_vec(s.velocity);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            o.velocity_gradient[i][j] = s.velocity_gradient[i][j];
        o.pressure_gradient  = to_vec(s.pressure_gradient);
        o.viscous_divergence = to_vec(s.viscous_divergence);
        o.porosity           = s.porosity;
        o.porosity_gradient  = to_vec(s.porosity_gradient);
      }
    return out;
  }

  FluidIntegrals VansBackend::integrals() const
  {
    return impl->fluid.integrals();
  }

  std::string VansBackend::write_snapshot(const std::string &directory, const std::string &base,
                                          const unsigned int index) const
  {
    return impl->fluid.write_vtu(directory, base, index);
  }

  void VansBackend::save_checkpoint(const std::string &base)
  {
    impl->fluid.save_checkpoint(base, {});
    // What a restarted run cannot have: the preconditioner built steps ago.
    impl->fluid.rebuild_preconditioner();
  }

  void VansBackend::load_checkpoint(const std::string &base)
  {
    impl->fluid.load_checkpoint(base, "checkpoint/restart from");
  }

  std::unique_ptr<SelfInducedVelocity>
  VansBackend::self_induced_velocity(const Vec3 &direction, const unsigned int n_memory,
                                     const PeriodicBox &box, const double d_max,
                                     std::string &summary) const
  {
    const auto started = std::chrono::steady_clock::now();
    const FluidParameters &fp = impl->p;
    MPI_Comm               comm = impl->comm;
    Vec3                   lo(1e300, 1e300, 1e300), hi = -lo;
    for (const auto &cell : impl->fluid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 3; ++d)
            {
              lo[d] = std::min(lo[d], cell->vertex(v)[d]);
              hi[d] = std::max(hi[d], cell->vertex(v)[d]);
            }
    for (unsigned int d = 0; d < 3; ++d)
      {
        lo[d] = Utilities::MPI::min(lo[d], comm);
        hi[d] = Utilities::MPI::max(hi[d], comm);
      }
    // Small enough to stay linear (a disturbance far below nu / R_s).
    const double probe_force = 1e-5 * fp.viscosity * fp.viscosity / fp.density;
    const double reach       = 0.45 * std::min({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const CouplingParameters &c = impl->c;
    auto correction = std::make_unique<SelfInducedVelocity>(
      measure_self_response(fp, c.projection, radius, c.smoothing_bandwidth, 0.5 * (lo + hi),
                            direction, probe_force, n_memory,
                            std::min(smallest_cell, radius) / 8., reach, comm),
      box);
    // The velocity a steady force induces at its deposit by the end of the
    // memory, against the particle's own Stokes mobility 1 / (3 pi mu d).
    const double mobility = correction->table().steady_response_at_deposit();
    std::ostringstream text;
    text << std::setprecision(4) << "  self-induced velocity correction: response measured over "
         << n_memory << " fluid steps (" << n_memory * fp.time_step << " s) in "
         << std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()
         << " s; steady-force self mobility = " << mobility * 3. * M_PI * fp.viscosity * d_max
         << " of the Stokes mobility\n";
    summary = text.str();
    return correction;
  }
} // namespace sluice
