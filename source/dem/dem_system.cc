// The DEM's set-up and per-step neighbour and contact work (see the header).

#include <sluice/dem/dem_system.h>
#include <sluice/dem/insertion.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

namespace sluice
{
  namespace
  {
    const char *model_name(const NormalContactModel m)
    {
      return m == NormalContactModel::linear ? "linear" : "hertz_mindlin";
    }
  } // namespace

  DemSystem::DemSystem(const SceneParameters &parameters, MPI_Comm communicator,
                       const unsigned int n_extra)
    : p(parameters)
    , comm(communicator)
    , properties(parameters)
    , box(parameters.lower_corner, parameters.upper_corner, parameters.periodic)
  {
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &n_ranks);
    // ---- Checks that need the particles and materials, before any output ----
    std::vector<ParticleRecord> records = create_particles(p);
    if (records.empty())
      throw InputError("error in '" + p.file_name +
                       "': the scene has no particles ('insertion/number of particles' = 0 "
                       "or an empty list)");
    r_min = records[0].radius;
    r_max = records[0].radius;
    std::set<unsigned int> types_present;
    for (const auto &r : records)
      {
        r_min = std::min(r_min, r.radius);
        r_max = std::max(r_max, r.radius);
        types_present.insert(r.type);
      }
    const std::vector<unsigned int> types(types_present.begin(), types_present.end());
    t_contact = properties.shortest_contact_time(types, r_min, !p.walls.empty());
    t_rayleigh = std::numeric_limits<double>::max();
    for (const unsigned int t : types)
      t_rayleigh = std::min(t_rayleigh, properties.rayleigh_time(t, r_min));
    const double dt_limit = p.maximum_time_step_ratio * t_contact;
    dt = p.automatic_time_step ? p.time_step_fraction * t_contact : p.time_step;
    if (!p.automatic_time_step && dt > dt_limit)
      {
        std::ostringstream msg;
        msg.precision(4);
        msg << "error in '" << p.file_name << "': entry 'simulation/time step' = " << dt
            << " s is above the contact-stability limit " << dt_limit << " s (= "
            << p.maximum_time_step_ratio << " x the shortest contact time t_c = " << t_contact
            << " s of the " << model_name(p.normal_model)
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

    // deal.II 9.4's ghost-particle exchange on a p4est mesh keeps one periodic
    // image per vertex, so along an edge where two periodic directions meet,
    // particles are not ghosted to a rank that is a neighbour only across that
    // edge. Rather than lose those contacts silently, refuse the combination.
    if (n_ranks > 1 && (p.periodic[0] + p.periodic[1] + p.periodic[2]) > 1)
      throw InputError("error in '" + p.file_name +
                       "': entries 'domain/periodic x, y, z': with more than one MPI rank at "
                       "most one direction may be periodic (deal.II 9.4 does not exchange "
                       "ghost particles across periodic edges); run on one rank, or make only "
                       "one direction periodic");

    friction = p.any_friction();
    skin = p.neighbour_skin > 0. ? p.neighbour_skin : 0.2 * r_max;
    const double range          = 2. * r_max + skin;
    const unsigned int history_slots = (n_ranks > 1 && friction) ? p.max_contacts_per_particle : 0;
    contact_kernel = select_contact_kernel(p.normal_model, friction, p.rolling_model);

    exchange = std::make_unique<ParticleExchange>(comm, box, range, records.size(), history_slots,
                                                  n_extra);
    exchange->insert(records, p);
    n_inserted = exchange->n_global_particles();
    if (n_inserted != records.size())
      throw InputError("error in '" + p.file_name + "': " +
                       std::to_string(records.size() - n_inserted) +
                       " particles could not be placed in the domain");
    records.clear();
    records.shrink_to_fit();

    exchange->fill_storage(particles, histories, p.density);
    list.build(particles, box, p.walls, r_max, skin, friction, histories);

    wall_forces.resize(p.walls.size());
    compute_contacts();
  }

  void DemSystem::update_neighbours()
  {
    double moved_2 = list.max_displacement_square(particles);
    if (n_ranks > 1)
      MPI_Allreduce(MPI_IN_PLACE, &moved_2, 1, MPI_DOUBLE, MPI_MAX, comm);
    if (moved_2 > 0.25 * skin * skin)
      {
        histories.clear();
        list.collect_histories(particles, histories);
        n_lost += exchange->migrate(particles, histories, box);
        exchange->fill_storage(particles, histories, p.density);
        list.build(particles, box, p.walls, r_max, skin, friction, histories);
      }
    else if (n_ranks > 1)
      exchange->update_ghosts(particles);
  }

  void DemSystem::compute_contacts()
  {
    stats = contact_kernel(particles, list, properties, p.walls, box, dt, wall_forces);
  }
} // namespace sluice
