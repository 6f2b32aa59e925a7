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
} // namespace

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  MPI_Comm                                 comm = MPI_COMM_WORLD;
  check_box({{true, true, true}}, 12, "triply periodic, 4 cells along x", comm);
  check_box({{true, true, true}}, 6, "triply periodic, 2 cells along x", comm);
  check_box({{true, false, false}}, 9, "periodic along x", comm);
  if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    std::printf("%d failed checks\n", sluice::unit::failures);
  int failures = sluice::unit::failures;
  MPI_Allreduce(MPI_IN_PLACE, &failures, 1, MPI_INT, MPI_SUM, comm);
  return failures == 0 ? 0 : 1;
}
