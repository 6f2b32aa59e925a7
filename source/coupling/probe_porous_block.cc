// A lattice settling as one porous block in a closed column: its velocity
// against the drag law at the block's porosity.

#include <sluice/core/sphere.h>
#include <sluice/coupling/coupling_probe.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace sluice
{
  namespace
  {
    class PorousBlockProbe : public CouplingProbe
    {
    public:
      /// Steady block in a closed column: k(eps, w) w = eps (rho_p - rho_f) V g
      /// per particle (every formulation), and the block settles at eps w, since
      /// the volume flux through a horizontal plane is zero. The block's top and
      /// bottom layers see the kernel-smoothed porosity edge and drift away, so
      /// the value is the velocity of the particles in the middle half of the
      /// block, where the projected porosity is the block's; the spread of their
      /// velocities shows that they move as one block.
      ProbeResult finish(ProbeView &view) override
      {
        const SceneParameters &p  = view.p;
        const ParticleStorage &P  = view.dem.particles;
        const double           d  = 2. * view.dem.r_max, V = sphere_volume(view.dem.r_max);
        const double           eps = p.coupling.block_porosity;
        const double w = slip_for_force(p, d, eps,
                                        eps * (particle_density(view) - view.fluid.density) * V *
                                          norm(p.gravity));
        const Vec3     g_hat           = (1. / norm(p.gravity)) * p.gravity;
        const auto     in_block_middle = in_middle_half(P, g_hat, view.comm);
        const auto     samples         = view.backend.sample();
        double         sums[4]         = {0., 0., 0., 0.};
        double slowest = std::numeric_limits<double>::max(), fastest = -slowest;
        for (unsigned int i = 0; i < P.n_local; ++i)
          if (samples[i].found && in_block_middle(P.position[i]))
            {
              const double v = dot(P.velocity[i], g_hat);
              sums[0] += 1.;
              sums[1] += v;
              sums[2] += samples[i].porosity;
              sums[3] += dot(P.velocity[i] - samples[i].velocity, g_hat);
              slowest = std::min(slowest, v);
              fastest = std::max(fastest, v);
            }
        MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, view.comm);
        MPI_Allreduce(MPI_IN_PLACE, &slowest, 1, MPI_DOUBLE, MPI_MIN, view.comm);
        MPI_Allreduce(MPI_IN_PLACE, &fastest, 1, MPI_DOUBLE, MPI_MAX, view.comm);
        const double n = std::max(sums[0], 1.);
        ProbeResult  r;
        r.name      = "porous_block";
        r.value     = sums[1] / n;
        r.reference = eps * w;
        r.error     = std::abs(r.value - r.reference) / r.reference;
        std::ostringstream check;
        check.precision(p.summary_precision);
        check << "check: porous_block middle_particles=" << sums[0]
              << " mean_porosity=" << sums[2] / n << " mean_slip=" << sums[3] / n
              << " slip_from_drag_law=" << w
              << " velocity_spread=" << (fastest - slowest) / r.reference
              << " whole_block_velocity=" << dot(global_mean_velocity(P, view.comm), g_hat);
        r.checks.push_back(check.str());
        return r;
      }
    };
  } // namespace

  std::unique_ptr<CouplingProbe> make_porous_block_probe()
  {
    return std::make_unique<PorousBlockProbe>();
  }
} // namespace sluice
