// Newton's third law in the contact kernel: for a cluster of overlapping spheres
// with random velocities and spins, no walls and no gravity, the contact forces
// must sum to zero and the contact torques plus the moments of the forces about
// the origin must sum to zero, to round-off, for every contact law the scene can
// select (linear / Hertz-Mindlin, with and without friction, each rolling model).
// Several steps are taken so that the tangential springs carry history.
// After each step the contact pass's touching list holds exactly the listed
// pairs that overlap, and every other pair's tangential history is +0 (a
// contact that opens again starts from an unstretched spring).

#include <sluice/dem/contact_forces.h>

#include <cmath>
#include <cstdio>
#include <random>

using namespace sluice;

static bool plus_zero(const double v) { return v == 0. && !std::signbit(v); }

int main()
{
  int failures = 0;
  for (const auto normal : {NormalContactModel::linear, NormalContactModel::hertz_mindlin})
    for (const bool friction : {false, true})
      for (const auto rolling : {RollingResistanceModel::none, RollingResistanceModel::constant_torque,
                                 RollingResistanceModel::viscous})
        {
          SceneParameters p;
          p.density          = {2500., 7800.};
          p.young_modulus    = {1e7, 5e7};
          p.poisson_ratio    = {0.3, 0.25};
          p.normal_model     = normal;
          p.friction         = friction ? 0.4 : 0.;
          p.rolling_friction = rolling == RollingResistanceModel::none ? 0. : 0.1;
          p.rolling_model    = rolling;
          const ContactProperties properties(p);

          // 200 spheres packed tighter than contact in a 1 cm cube.
          std::mt19937_64                        rng(42);
          std::uniform_real_distribution<double> u(0., 1.);
          ParticleStorage                        P;
          for (unsigned int i = 0; i < 200; ++i)
            {
              const unsigned int type = i % 2;
              P.push_back(i, Vec3(0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng)),
                          Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5),
                          Vec3(100. * (u(rng) - 0.5), 100. * (u(rng) - 0.5), 100. * (u(rng) - 0.5)),
                          0.0008 + 0.0004 * u(rng), type, p.density[type]);
            }
          P.n_local = P.size();

          const PeriodicBox box(Vec3(-0.01, -0.01, -0.01), Vec3(0.02, 0.02, 0.02), {{false, false, false}});
          const WallSet walls;
          std::vector<Vec3>            wall_forces;
          NeighbourList                list;
          list.build(P, box, walls, 0.0012, 0.0002, friction, ContactHistoryMap());
          const ContactForceKernel kernel = select_contact_kernel(normal, friction, rolling, false);

          double       worst_force = 0., worst_moment = 0., n_contacts = 0.;
          unsigned int bad_lists = 0;
          for (unsigned int step = 0; step < 5; ++step)
            {
              const ContactStatistics stats = kernel(P, list, properties, walls, box, 1e-6, wall_forces, nullptr);
              n_contacts = stats.n_particle_contacts;
              Vec3   total_force, total_moment;
              double force_scale = 0., moment_scale = 0.;
              for (unsigned int i = 0; i < P.size(); ++i)
                {
                  total_force += P.force[i];
                  total_moment += P.torque[i] + cross(P.position[i], P.force[i]);
                  force_scale += norm(P.force[i]);
                  moment_scale += norm(P.torque[i]) + norm(cross(P.position[i], P.force[i]));
                }
              for (unsigned int i = 0; i < P.n_local; ++i)
                {
                  unsigned int c = list.touching_offset[i];
                  for (unsigned int k = list.offset[i]; k < list.offset[i + 1]; ++k)
                    {
                      const unsigned int j      = list.partner[k];
                      const double       r_sum  = P.radius[i] + P.radius[j];
                      const bool         touch  = norm_square(P.position[i] - P.position[j]) <
                                         r_sum * r_sum;
                      const bool         listed = c < list.touching_offset[i + 1] &&
                                          list.touching[c] == k;
                      c += listed;
                      bad_lists += touch != listed;
                      const Vec3 &h = friction ? list.history[k] : Vec3();
                      if (!touch)
                        bad_lists += !(plus_zero(h.x) && plus_zero(h.y) && plus_zero(h.z));
                    }
                  bad_lists += c != list.touching_offset[i + 1];
                }
              worst_force  = std::max(worst_force, norm(total_force) / force_scale);
              worst_moment = std::max(worst_moment, norm(total_moment) / moment_scale);
              for (unsigned int i = 0; i < P.size(); ++i) // move a little
                P.position[i] += 1e-6 * P.velocity[i];
            }
          const bool ok = n_contacts > 100 && worst_force < 1e-13 && worst_moment < 1e-13 &&
                          bad_lists == 0;
          std::printf("%-14s friction=%d rolling=%d contacts=%4.0f |sum F|/sum|F|=%.1e "
                      "|sum M|/sum|M|=%.1e touching_list_errors=%u %s\n",
                      normal == NormalContactModel::linear ? "linear" : "hertz_mindlin", friction,
                      static_cast<int>(rolling), n_contacts, worst_force, worst_moment, bad_lists,
                      ok ? "ok" : "FAILED");
          failures += !ok;
        }
  return failures == 0 ? 0 : 1;
}
