// The SPH fluid's particles on several ranks (sph/sph_exchange.h), run on 1,
// 2 and 3 ranks, in a box periodic in all three directions and in one
// periodic only along x, each with cells of 3 or more and of 2 along a
// direction:
// - every particle is owned by exactly one rank, in a cell that rank owns;
// - every particle within the reach of an owned particle (its minimum
//   image, across periodic faces, edges and corners) is held by the rank,
//   owned or as a ghost, once;
// - after every particle has moved by up to a third of the reach, the
//   redistribution keeps the first two, and each attached value arrives
//   with its particle;
// - a refresh gives every ghost its owner's new velocity and density;
// - the gathered particles are all of them, by id.
// And SphExchange::fit, at the pairs' rebuilds:
// - when the pairs reach further than the cells are wide, it cuts wider ones,
//   and every partner within the new reach is held, down to one cell;
// - when the cells were shared out for particles that have since gone
//   elsewhere, it shares them out again at the 20th rebuild (not before), the
//   busiest rank's load falls from above 1.15 times the mean to near it, and
//   the layout's checks hold;
// - a checkpoint's record of the cells gives another exchange the same owners;
//   a damaged one is refused.

#include <sluice/core/binary_io.h>
#include <sluice/sph/sph_exchange.h>

#include "check.h"
#include "sph_lattice.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>

using namespace sluice;
using sluice::unit::check;

namespace
{
  const double dx = 1e-3;

  /// The checks on the owned particles and the ghosts of every rank.
  void check_layout(const SphParticles &all, const SphParticles &P, const PeriodicBox &box,
                    const double reach, const std::string &name, MPI_Comm comm)
  {
    // Each id owned once over the ranks.
    std::vector<double> owned(all.size(), 0.);
    for (unsigned int a = 0; a < P.n_local; ++a)
      owned[P.id[a]] += 1.;
    MPI_Allreduce(MPI_IN_PLACE, owned.data(), owned.size(), MPI_DOUBLE, MPI_SUM, comm);
    unsigned int wrong = 0;
    for (const double n : owned)
      wrong += n != 1.;
    check(wrong == 0, (name + ": particles not owned exactly once").c_str(), wrong, 0);

    // Each particle held once, and every partner within reach held.
    std::map<std::uint64_t, unsigned int> held;
    for (unsigned int a = 0; a < P.size(); ++a)
      ++held[P.id[a]];
    unsigned int twice = 0, missing = 0;
    for (const auto &[id, n] : held)
      twice += n > 1;
    std::map<std::uint64_t, Vec3> where;
    for (unsigned int b = 0; b < all.size(); ++b)
      where[all.id[b]] = all.position[b];
    for (unsigned int a = 0; a < P.n_local; ++a)
      for (const auto &[id, x] : where)
        if (norm(box.minimum_image(P.position[a] - x)) < reach && held.count(id) == 0)
          ++missing;
    check(twice == 0, (name + ": particles held twice").c_str(), twice, 0);
    check(missing == 0, (name + ": partners within reach missing").c_str(), missing, 0);
  }

  void check_box(const std::array<bool, 3> &periodic, const unsigned int nx,
                 const std::string &name, MPI_Comm comm)
  {
    const unsigned int ny = 12, nz = 9;
    SphParticles       all = sluice::unit::sph_lattice(nx, ny, nz, dx, 1000., 0.3);
    const PeriodicBox  box(Vec3(), dx * Vec3(nx, ny, nz), periodic);
    // Cells of 3 dx: 3 or 4 along y and z, and nx / 3 along x.
    const double reach = 3. * dx;
    SphExchange  exchange(comm, box, reach, all);
    check(std::abs(exchange.reach() - reach) <= 1e-12 * reach, (name + ": reach").c_str(),
          exchange.reach(), reach);

    SphParticles P = all;
    exchange.keep_own(P);
    exchange.redistribute(P);
    check_layout(all, P, box, exchange.reach(), name + ", at the start", comm);
    if (exchange.active())
      check(P.n_local < all.size() && P.size() > P.n_local,
            (name + ": a rank owns all particles or holds no ghosts").c_str(), P.n_local,
            all.size());

    // Every particle moves by up to reach / 3 (wrapped into the box), the
    // velocity and density of 'all' along with it; an attached value per
    // owned particle: its id.
    std::mt19937                           random(17);
    std::uniform_real_distribution<double> u(-1., 1.);
    std::vector<Vec3>                      shift(all.size());
    for (Vec3 &s : shift)
      s = (reach / (3. * std::sqrt(3.))) * Vec3(u(random), u(random), u(random));
    const auto moved = [&](const std::uint64_t id) { return box.wrap(all.position[id] + shift[id]); };
    for (unsigned int b = 0; b < all.size(); ++b)
      all.position[b] = moved(b);
    std::vector<double> tag(P.n_local);
    std::vector<Vec3>   twice(P.n_local);
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        P.position[a] = all.position[P.id[a]];
        tag[a]        = P.id[a];
        twice[a]      = 2. * P.position[a];
      }
    exchange.redistribute(P, {{&twice}, {&tag}});
    check_layout(all, P, box, exchange.reach(), name + ", after a move", comm);
    unsigned int wrong = 0;
    for (unsigned int a = 0; a < P.n_local; ++a)
      wrong += tag[a] != P.id[a] || norm(twice[a] - 2. * P.position[a]) > 0.;
    check(tag.size() == P.n_local && wrong == 0, (name + ": attachments astray").c_str(), wrong,
          0);

    // The ghosts take their owners' new velocity and density.
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        P.velocity[a] = Vec3(P.id[a], 1., -1.);
        P.density[a]  = 1000. + P.id[a];
      }
    exchange.refresh_motion(P);
    wrong = 0;
    for (unsigned int a = P.n_local; a < P.size(); ++a)
      wrong += P.velocity[a].x != P.id[a] || P.density[a] != 1000. + P.id[a];
    check(wrong == 0, (name + ": ghosts not refreshed").c_str(), wrong, 0);

    const SphParticles gathered = exchange.active() ? exchange.gather_all(P) : P;
    wrong                       = gathered.size() != all.size();
    for (unsigned int a = 0; a < gathered.size() && wrong == 0; ++a)
      wrong += gathered.id[a] != a || norm(gathered.position[a] - all.position[a]) > 0.;
    check(wrong == 0, (name + ": gathered particles").c_str(), wrong, 0);
  }
  /// The busiest rank's owned particles over the mean.
  double busiest_over_mean(const SphParticles &P, MPI_Comm comm)
  {
    const double n       = P.n_local;
    const double busiest = dealii::Utilities::MPI::max(n, comm);
    const double total   = dealii::Utilities::MPI::sum(n, comm);
    return busiest * dealii::Utilities::MPI::n_mpi_processes(comm) / total;
  }

  void check_fit(MPI_Comm comm)
  {
    const unsigned int nx = 24, ny = 12, nz = 9;
    const SphParticles all = sluice::unit::sph_lattice(nx, ny, nz, dx, 1000., 0.3);
    const PeriodicBox  box(Vec3(), dx * Vec3(nx, ny, nz), {{true, false, false}});
    const double       reach = 3. * dx;

    // Wider cells for a longer reach.
    {
      SphExchange  exchange(comm, box, reach, all);
      SphParticles P = all;
      exchange.keep_own(P);
      const bool changed = exchange.fit(P, 5. * dx);
      check(changed == exchange.active(), "fit: wider cells not cut", changed, exchange.active());
      if (exchange.active())
        check(exchange.reach() >= 5. * dx, "fit: reach after widening", exchange.reach(), 5. * dx);
      exchange.redistribute(P);
      check_layout(all, P, box, 5. * dx, "fit, wider cells", comm);
      // Wider than half the box along every axis: one cell, one rank owns all.
      exchange.fit(P, 13. * dx);
      exchange.redistribute(P);
      check_layout(all, P, box, 13. * dx, "fit, one cell", comm);
    }

    // The cells shared out for the fluid in x < L/2 only, then all of it.
    SphParticles left;
    for (unsigned int a = 0; a < all.size(); ++a)
      if (all.position[a].x < 0.5 * box.length.x)
        {
          left.id.push_back(all.id[a]);
          for (auto [to, from] : {std::pair{&left.position, &all.position},
                                  {&left.velocity, &all.velocity},
                                  {&left.acceleration, &all.acceleration},
                                  {&left.wall_velocity, &all.wall_velocity}})
            to->push_back((*from)[a]);
          for (auto [to, from] :
               {std::pair{&left.mass, &all.mass}, {&left.density, &all.density},
                {&left.density_rate, &all.density_rate}, {&left.smoothing, &all.smoothing},
                {&left.omega, &all.omega}, {&left.pressure, &all.pressure},
                {&left.porosity, &all.porosity}})
            to->push_back((*from)[a]);
          left.wall.push_back(all.wall[a]);
        }
    left.n_local = left.size();
    SphExchange  exchange(comm, box, reach, left);
    SphParticles P = all;
    exchange.keep_own(P);
    exchange.redistribute(P);
    if (!exchange.active())
      {
        check(!exchange.fit(P, reach), "fit on one rank", 1, 0);
        return;
      }
    const double before = busiest_over_mean(P, comm);
    check(before > 1.15, "fit: the test's start is not out of balance", before, 1.15);
    unsigned int calls = 1;
    while (!exchange.fit(P, reach) && calls < 25)
      ++calls;
    check(calls == 20, "fit: shared out again after this many rebuilds", calls, 20);
    check(exchange.n_repartitions() == 1, "fit: repartitions", exchange.n_repartitions(), 1);
    exchange.redistribute(P);
    check_layout(all, P, box, reach, "fit, shared out again", comm);
    const double after = busiest_over_mean(P, comm);
    check(after < 1.1, "fit: balance after sharing out again", after, 1.1);

    // A checkpoint's record of the cells.
    SphExchange restored(comm, box, reach, left);
    restored.restore_cells(exchange.cells(), all);
    SphParticles Q = all;
    restored.keep_own(Q);
    const std::set<std::uint64_t> owned(P.id.begin(), P.id.begin() + P.n_local),
      owned_restored(Q.id.begin(), Q.id.begin() + Q.n_local);
    const unsigned int wrong = owned != owned_restored;
    check(wrong == 0, "fit: the restored cells' owners", wrong, 0);
    std::vector<std::int64_t> damaged = exchange.cells();
    damaged.back() = 99;
    bool refused = false;
    try
      {
        restored.restore_cells(damaged, all);
      }
    catch (const BinaryFormatError &)
      {
        refused = true;
      }
    check(refused, "fit: a damaged record of the cells taken", refused, true);
  }
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  MPI_Comm                                 comm = MPI_COMM_WORLD;
  check_box({{true, true, true}}, 12, "triply periodic, 4 cells along x", comm);
  check_box({{true, true, true}}, 6, "triply periodic, 2 cells along x", comm);
  check_box({{true, false, false}}, 9, "periodic along x", comm);
  check_fit(comm);
  if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    std::printf("%d failed checks\n", sluice::unit::failures);
  int failures = sluice::unit::failures;
  MPI_Allreduce(MPI_IN_PLACE, &failures, 1, MPI_INT, MPI_SUM, comm);
  return failures == 0 ? 0 : 1;
}
