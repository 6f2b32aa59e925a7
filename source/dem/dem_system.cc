// The DEM's set-up and per-step neighbour and contact work (see the header).

#include <sluice/core/names.h>
#include <sluice/dem/clump_insertion.h>
#include <sluice/dem/dem_system.h>
#include <sluice/dem/insertion.h>
#include <sluice/dem/state_check.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// The scene's per-particle fields, with a clump body's in a clump scene.
    ParticleFieldRegistry with_body_fields(ParticleFieldRegistry fields, const SceneParameters &p)
    {
      if (p.clumps.active())
        ClumpSystem::declare_fields(fields);
      return fields;
    }
  } // namespace

  DemSystem::DemSystem(const SceneParameters &parameters, MPI_Comm communicator,
                       const ParticleFieldRegistry &particle_fields)
    : p(parameters)
    , comm(communicator)
    , fields(with_body_fields(particle_fields, parameters))
    , properties(parameters)
    , box(parameters.lower_corner, parameters.upper_corner, parameters.periodic)
    , walls(parameters.walls, parameters.meshes, box, parameters.file_name)
  {
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &n_ranks);
    // ---- Checks that need the particles and materials, before any output ----
    if (p.clumps.active())
      clumps = std::make_unique<ClumpSystem>(p.clumps, fields);
    std::vector<ParticleRecord> records =
      clumps ? create_clump_bodies(p, clumps->templates) : create_particles(p);
    const bool                  streams = p.stream.inlet != StreamRegion::none;

    // A stream may start an empty scene; without one nothing would move.
    if (records.empty() && !streams)
      throw InputError("error in '" + p.file_name +
                       "': the scene has no particles ('insertion/number of particles' = 0 "
                       "or an empty list) and no stream");
    // The spheres that touch: a clump's members.
    const auto contact_radii = [&](const ParticleRecord &r) {
      if (!clumps)
        return std::make_pair(r.radius, r.radius);
      const std::vector<double> &radii = clumps->templates[r.clump_template].radii;
      return std::make_pair(r.clump_scale * *std::min_element(radii.begin(), radii.end()),
                            r.clump_scale * *std::max_element(radii.begin(), radii.end()));
    };
    r_min = !records.empty() ? contact_radii(records[0]).first :
            clumps          ? std::numeric_limits<double>::max() :
                              p.stream.radius;
    r_max = r_min;
    double bounding_max = 0.; // a body's largest bounding radius
    std::set<unsigned int> types_present;
    for (const auto &r : records)
      {
        const auto [lo, hi] = contact_radii(r);
        r_min = std::min(r_min, lo);
        r_max = std::max(r_max, hi);
        bounding_max = std::max(bounding_max, r.radius);
        types_present.insert(r.type);
      }
    // A stream's spheres too decide the step, the cells and the skin (in a
    // clump scene, any body its templates can make).
    if (streams && clumps)
      for (std::size_t k = 0; k < clumps->templates.size(); ++k)
        {
          const ClumpTemplateParameters &t = p.clumps.templates[k];
          const std::vector<double>     &radii = clumps->templates[k].radii;
          const double s_max = std::max(t.scale, t.scale_max);
          r_min = std::min(r_min, t.scale * *std::min_element(radii.begin(), radii.end()));
          r_max = std::max(r_max, s_max * *std::max_element(radii.begin(), radii.end()));
          bounding_max = std::max(bounding_max, s_max * clumps->templates[k].bounding_radius());
          types_present.insert(p.stream.type);
        }
    else if (streams)
      {
        r_min = std::min(r_min, p.stream.radius);
        r_max = std::max(r_max, std::max(p.stream.radius, p.stream.radius_max));
        types_present.insert(p.stream.type);
      }
    const std::vector<unsigned int> types(types_present.begin(), types_present.end());
    const bool any_walls = !p.walls.empty() || !p.meshes.empty();
    t_contact = properties.shortest_contact_time(types, r_min, any_walls);
    t_rayleigh = std::numeric_limits<double>::max();
    for (const unsigned int t : types)
      t_rayleigh = std::min(t_rayleigh, properties.rayleigh_time(t, r_min));
    const double dt_limit = p.maximum_time_step_ratio * t_contact;
    t_damping = properties.shortest_damping_time_step(types, r_min, any_walls,
                                                      p.restitution_accuracy);
    dt = p.automatic_time_step ? std::min(p.time_step_fraction * t_contact, t_damping) :
                                 p.time_step;
    if (!p.automatic_time_step && dt > dt_limit)
      {
        std::ostringstream msg;
        msg.precision(4);
        msg << "error in '" << p.file_name << "': entry 'simulation/time step' = " << dt
            << " s is above the contact-stability limit " << dt_limit << " s (= "
            << p.maximum_time_step_ratio << " x the shortest contact time t_c = " << t_contact
            << " s of the " << name_of(p.normal_model)
            << " law for the smallest particles, radius " << r_min
            << " m, at the characteristic velocity " << p.characteristic_velocity
            << " m/s); use a step <= " << dt_limit << " s or 'auto'";
        throw InputError(msg.str());
      }
    for (unsigned int d = 0; d < 3; ++d)
      if (p.periodic[d] && p.upper_corner[d] - p.lower_corner[d] < 2. * (2. * r_max + 0.4 * r_max))
        throw InputError("error in '" + p.file_name + "': entry 'domain/periodic " +
                         std::string(1, "xyz"[d]) +
                         "': a periodic direction must be at least two interaction ranges "
                         "(4.8 largest radii) long");

    friction = p.any_friction();
    skin = p.neighbour_skin > 0. ? p.neighbour_skin : 0.2 * r_max;
    max_step_displacement = 0.5 * r_min;
    body_radius_max = bounding_max;
    // Ghost bodies must bring every member within reach of an owned one.
    const double range = clumps ? 2. * bounding_max + skin : 2. * r_max + skin;
    const bool carry_histories = n_ranks > 1 && friction;
    select_kernels();

    BodyTransport transport;
    if (clumps)
      transport = {true, clumps->member_stride};
    list.member_stride = clumps ? clumps->member_stride : 0;
    exchange = std::make_unique<ParticleExchange>(comm, box, range, records.size(), carry_histories,
                                                  fields, transport);
    exchange->insert(records, p);
    n_inserted = exchange->n_global_particles();
    if (n_inserted != records.size())
      throw InputError("error in '" + p.file_name + "': " +
                       std::to_string(records.size() - n_inserted) +
                       " particles could not be placed in the domain");
    records.clear();
    records.shrink_to_fit();

    exchange->fill_storage(handler_particles(), histories, p.density);
    if (clumps)
      {
        clumps->set_mass_properties(p.density, false);
        clumps->set_momenta_from_angular_velocity(0, n_inserted);
      }
    refresh_members();
    build_list();
    // A fixed bed may be an overlapping lattice on purpose; it never moves.
    if (!p.coupling.fixed_particles)
      check_initial_state(particles, list, walls, box, p.maximum_initial_overlap, p.file_name,
                          comm, list.member_stride);

    wall_forces.resize(walls.n_walls());
    compute_contacts();
    if (clumps)
      clumps->gather(particles);
    // Only a scene that will run hears of its step.
    if (!p.automatic_time_step && dt > t_damping && rank == 0)
      std::cerr << std::setprecision(4) << "sluice: warning: 'simulation/time step' = " << dt
                << " s under-resolves the strongest dashpot: the realised restitution will be "
                   "off by about "
                << 100. * p.restitution_accuracy * dt / t_damping
                << "% (a step <= " << t_damping << " s keeps it within "
                << 100. * p.restitution_accuracy
                << "%, 'simulation/restitution accuracy'; or use 'auto')\n";
  }

  void DemSystem::build_list()
  {
    list.build(particles, box, walls, r_max, skin, friction, histories);
    walls.mark_list_build();
  }

  void DemSystem::update_neighbours()
  {
    // The list test and the health checks share one reduction: the largest
    // displacement since the build (infinite if a position is not finite), the
    // largest speed of this step's drift and the deepest overlap of the last
    // contact pass.
    double worst[3] = {list.max_displacement_square(particles), particles.max_drift_speed_2,
                       stats.max_overlap_ratio};
    if (n_ranks > 1)
      MPI_Allreduce(MPI_IN_PLACE, worst, 3, MPI_DOUBLE, MPI_MAX, comm);
    const double moved_2 = worst[0];
    if (!(moved_2 < std::numeric_limits<double>::infinity()) ||
        !(worst[1] * dt * dt <= max_step_displacement * max_step_displacement) ||
        !(worst[2] <= p.maximum_overlap))
      fail(moved_2, worst[1]);
    // A wall listed within the skin of a particle closes that gap by its own
    // motion, so it too may move half the skin.
    if (moved_2 > 0.25 * skin * skin || walls.max_displacement_since_build() > 0.5 * skin ||
        replacement_due)
      {
        clock.lap(Stage::rest);
        histories.clear();
        list.collect_histories(particles, histories);
        clock.lap(Stage::histories);
        const unsigned long long lost = exchange->migrate(handler_particles(), histories, box);
        clock.lap(Stage::migrate);
        if (lost > 0)
          report_lost(lost);
        if (replacement_due)
          {
            exchange->replace(remove_ids, add_records, add_ids, box);
            n_added += add_records.size();
            n_removed += remove_ids.size();
            replacement_due = false;
            remove_ids.clear();
            add_ids.clear();
            add_records.clear();
          }
        exchange->fill_storage(handler_particles(), histories, p.density);
        refresh_members();
        clock.lap(Stage::fill);
        build_list();
        clock.lap(Stage::list);
      }
    else if (n_ranks > 1)
      {
        clock.lap(Stage::rest);
        exchange->update_ghosts(handler_particles());
        if (clumps)
          clumps->move_members(particles, clumps->bodies.n_local);
        clock.lap(Stage::ghosts);
      }
  }

  void DemSystem::refresh_members()
  {
    if (!clumps)
      return;
    clumps->set_mass_properties(p.density);
    clumps->expand(particles);
  }


  void DemSystem::fail(const double moved_2, const double speed_2) const
  {
    const StepInfo where{step,          step * dt, dt, max_step_displacement,
                         p.characteristic_velocity, list.member_stride};
    if (!(moved_2 < std::numeric_limits<double>::infinity()) || std::isnan(speed_2))
      fail_non_finite(particles, where, comm);
    if (speed_2 * dt * dt > max_step_displacement * max_step_displacement)
      fail_fast_particle(particles, where, comm);
    fail_deep_overlap(particles, list, walls, box, p.maximum_overlap, where, comm);
  }

  void DemSystem::report_lost(const unsigned long long lost)
  {
    // The first loss is worth a line (unless the scene has an outlet); the
    // rest are counted in the summary.
    if (n_lost == 0 && !p.outlet && rank == 0)
      {
        const ParticleExchange::Loss &first = exchange->first_loss();
        const std::string more =
          lost > 1 ? ", with " + std::to_string(lost - 1) + " more in that step" : "";
        std::cerr << "sluice: warning: particle " << first.id << " left the domain at step "
                  << step << " (t = " << to_text(step * dt) << " s) at ("
                  << to_text(first.position.x) << ", " << to_text(first.position.y) << ", "
                  << to_text(first.position.z) << ")" << more << "; it is removed, and later losses are counted in the summary ('lost='). "
                     "Close the domain with walls, or set 'domain/outlet = true' where leaving "
                     "is expected\n";
      }
    n_lost += lost;
  }

  void DemSystem::schedule_replacement(std::vector<std::uint64_t> remove,
                                       std::vector<ParticleRecord> records,
                                       std::vector<std::uint64_t>  ids)
  {
    remove_ids      = std::move(remove);
    add_records     = std::move(records);
    add_ids         = std::move(ids);
    replacement_due = !remove_ids.empty() || !add_records.empty();
  }

  void DemSystem::compute_contacts()
  {
    clock.lap(Stage::rest);
    stats = contact_kernel(particles, list, properties, walls, box, dt, wall_forces,
                           contact_observer);
    if (mesh_kernel)
      mesh_kernel(particles, list, properties, walls, dt, wall_forces, mesh_loads,
                  contact_observer, stats);
    clock.lap(Stage::contacts);
  }

  void DemSystem::select_kernels()
  {
    const bool observed = contact_observer != nullptr;
    contact_kernel      = select_contact_kernel(p.normal_model, friction, p.rolling_model,
                                           walls.any_moving(), observed);
    if (walls.n_meshes() > 0)
      mesh_kernel = select_mesh_contact_kernel(p.normal_model, friction, p.rolling_model, observed);
  }

  void DemSystem::observe(ContactObserver *const observer)
  {
    contact_observer = observer;
    select_kernels();
  }
} // namespace sluice
