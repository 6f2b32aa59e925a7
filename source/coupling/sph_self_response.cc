// The SPH fluid's response to one particle's force, for the self-induced
// velocity correction (self_induced_velocity.h): measured on two copies of the
// fluid as it is after the start's relaxation, one given the impulse and one
// not, so that whatever else moves the fluid cancels in their difference.

#include <sluice/coupling/sph_backend.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace sluice
{
  std::unique_ptr<SphBackend> SphBackend::copy() const
  {
    auto twin = std::make_unique<SphBackend>(
      setup, settings, walls ? std::make_unique<WallSet>(*walls) : nullptr, wall_law,
      communicator);
    if (distributed)
      {
        // The twin keeps its own exchange (its ghosts follow its particles):
        // the fluid's state passes through a checkpoint's record, and the
        // twin builds its pairs again.
        BinaryWriter out("sluice sph copy");
        sph->save(out);
        BinaryReader in(out.finish(), "sluice sph copy");
        twin->sph->load(in);
      }
    else
      *twin->sph = *sph;
    // The twin's fluid meets the twin's walls, which its own steps move.
    if (walls)
      twin->sph->rebind_solid_walls(*twin->walls);
    twin->solids       = solids;
    twin->reactions    = reactions;
    twin->pairs        = pairs;
    twin->time         = time;
    twin->sph_steps    = sph_steps;
    twin->deposited    = deposited;
    return twin;
  }

  std::unique_ptr<SelfInducedVelocity>
  SphBackend::self_induced_velocity(const Vec3 &direction, const unsigned int n_memory,
                                    const PeriodicBox &box, const double largest_diameter,
                                    std::string &summary) const
  {
    const auto   started = std::chrono::steady_clock::now();
    const double h_c     = settings.coupling_length;
    const double rho_f   = setup.settings.forces.state.reference_density;
    const double mu      = setup.settings.forces.viscosity;

    // Deposited where the solids are (their centroid; one grain: the grain
    // itself), since the SPH fluid is not homogeneous: it has a floor, a free
    // surface and a lattice the Shepard weights see.
    Vec3   centre  = 0.5 * (setup.domain_lower + setup.domain_upper);
    double largest = M_PI / 6. * std::pow(largest_diameter, 3); // the largest volume
    if (!solids.position.empty())
      {
        centre = Vec3();
        for (std::size_t i = 0; i < solids.position.size(); ++i)
          {
            centre += solids.position[i];
            largest = std::max(largest, solids.volume[i]);
          }
        centre = (1. / solids.position.size()) * centre;
      }
    // The size of a grain's own reaction (its buoyancy) keeps the probe in
    // the regime the correction is used in; the response is linear in it.
    const double probe_force =
      rho_f * largest * std::max(norm(setup.settings.forces.gravity), 1.);

    // The probe points (self_response_points, up to 0.45 of the domain's
    // smallest extent) after the solids, which keep the fluid fraction as it
    // is; a probe point has no volume. On several ranks rank 0 hands them all
    // over (every rank holds what it receives) and takes their samples.
    const Vec3   e      = (1. / norm(direction)) * direction;
    const Vec3   extent = setup.domain_upper - setup.domain_lower;
    const double s      = h_c / 8.;
    std::vector<ExchangeParticle> points(solids.position.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      {
        points[i].position = solids.position[i];
        points[i].volume   = solids.volume[i];
      }
    const std::size_t first = points.size();
    for (const Vec3 &x :
         self_response_points(centre, e, s, 0.45 * std::min({extent.x, extent.y, extent.z})))
      {
        ExchangeParticle p;
        p.position = box.wrap(x);
        points.push_back(p);
      }

    // The impulse: the probe's force held over the first fluid step.
    if (rank != 0)
      points.clear();
    std::unique_ptr<SphBackend> kicked = copy(), left = copy();
    SelfResponseTable           table;
    table.spacing = s;
    for (unsigned int m = 0; m < n_memory; ++m)
      {
        std::vector<ExchangeParticle> with = points;
        if (m == 0 && rank == 0)
          with[first].reaction_force = probe_force * e;
        std::vector<ParticleFluidSample> u[2];
        SphBackend                      *fluids[2] = {kicked.get(), left.get()};
        for (unsigned int k = 0; k < 2; ++k)
          {
            fluids[k]->receive(k == 0 ? with : points);
            fluids[k]->deposit(false);
            fluids[k]->advance(settings.fluid_step);
            u[k] = fluids[k]->sample();
          }
        std::vector<double> response(rank == 0 ? points.size() - first : 0, 0.);
        for (std::size_t q = 0; q < response.size(); ++q)
          if (u[0][first + q].found)
            response[q] =
              dot(u[0][first + q].velocity - u[1][first + q].velocity, e) / probe_force;
        if (distributed)
          response = dealii::Utilities::MPI::broadcast(communicator, response, 0);
        add_self_response_row(table, response);
      }
    auto correction = std::make_unique<SelfInducedVelocity>(std::move(table), box);

    // The velocity a steady force induces at its deposit by the end of the
    // memory, against the particle's own Stokes mobility 1 / (3 pi mu d).
    const double mobility = correction->table().steady_response_at_deposit();
    std::ostringstream text;
    text << std::setprecision(4) << "  self-induced velocity correction: response measured over "
         << n_memory << " fluid steps (" << n_memory * settings.fluid_step
         << " s) on two copies of the SPH fluid in "
         << std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()
         << " s; steady-force self mobility = " << mobility * 3. * M_PI * mu * largest_diameter
         << " of the Stokes mobility\n";
    summary = text.str();
    return correction;
  }
} // namespace sluice
