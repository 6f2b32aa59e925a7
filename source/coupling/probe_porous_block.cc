// A lattice settling as one porous block in a closed column: its velocity
// against the drag law at the block's porosity.

#include <sluice/core/sphere.h>
#include <sluice/coupling/coupling_probe.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// The block's middle particles at one instant (all ranks).
    struct BlockSample
    {
      double n = 0., velocity = 0., porosity = 0., slip = 0.; // count, then means
      double slowest = 0., fastest = 0., whole_block = 0.;
    };

    /// The block's top and bottom layers see the kernel-smoothed porosity edge
    /// and drift away, so the block's velocity is that of the particles in its
    /// middle half, where the projected porosity is the block's; the spread of
    /// their velocities shows that they move as one block.
    BlockSample sample_block(ProbeView &view)
    {
      const ParticleStorage &P               = view.dem.particles;
      const Vec3             g_hat           = (1. / norm(view.p.gravity)) * view.p.gravity;
      const auto             in_block_middle = in_middle_half(P, g_hat, view.comm);
      const auto            &samples         = view.samples;
      double                 sums[4]         = {0., 0., 0., 0.};
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
      BlockSample  s;
      s.n           = sums[0];
      s.velocity    = sums[1] / n;
      s.porosity    = sums[2] / n;
      s.slip        = sums[3] / n;
      s.slowest     = slowest;
      s.fastest     = fastest;
      s.whole_block = dot(global_mean_velocity(P, view.comm), g_hat);
      return s;
    }

    class PorousBlockProbe : public CouplingProbe
    {
    public:
      /// With 'averaging start' t_a > 0: from t_a on, the middle particles'
      /// velocity and slip and the whole block's velocity, each fluid step
      /// weighted by the part of it after t_a.
      void observe(const double time, ProbeView &view) override
      {
        const double start  = view.p.coupling.averaging_start;
        const double weight = time - std::max(last_time, start);
        last_time           = time;
        if (!(start > 0.) || !(weight > 0.))
          return;
        const BlockSample s = sample_block(view);
        averaged[0] += weight;
        averaged[1] += weight * s.velocity;
        averaged[2] += weight * s.slip;
        averaged[3] += weight * s.whole_block;
      }

      /// Steady block in a closed column: k(eps, w) w = eps (rho_p - rho_f) V g
      /// per particle (every formulation), and the block settles at eps w, since
      /// the volume flux through a horizontal plane is zero.
      ProbeResult finish(ProbeView &view) override
      {
        const SceneParameters &p   = view.p;
        const double           d   = 2. * view.dem.r_max, V = sphere_volume(view.dem.r_max);
        const double           eps = p.coupling.block_porosity;
        const double w = slip_for_force(p, d, eps,
                                        eps * (particle_density(view) - view.fluid.density) * V *
                                          norm(p.gravity));
        const BlockSample s = sample_block(view);
        ProbeResult       r;
        r.name      = "porous_block";
        r.value     = averaged[0] > 0. ? averaged[1] / averaged[0] : s.velocity;
        r.reference = eps * w;
        r.error     = std::abs(r.value - r.reference) / r.reference;
        std::ostringstream check;
        check.precision(p.summary_precision);
        check << "check: porous_block middle_particles=" << s.n
              << " mean_porosity=" << s.porosity << " mean_slip=" << s.slip
              << " slip_from_drag_law=" << w
              << " velocity_spread=" << (s.fastest - s.slowest) / r.reference
              << " whole_block_velocity=" << s.whole_block;
        r.checks.push_back(check.str());
        if (averaged[0] > 0.)
          {
            std::ostringstream average;
            average.precision(p.summary_precision);
            average << "check: porous_block averaged_over=" << averaged[0]
                    << " s middle_velocity_at_end=" << s.velocity
                    << " averaged_slip=" << averaged[2] / averaged[0]
                    << " averaged_whole_block_velocity=" << averaged[3] / averaged[0];
            r.checks.push_back(average.str());
          }
        return r;
      }

      /// The time of the last step seen, then the window's length and the
      /// time integrals of the velocity, slip and whole block's velocity.
      std::vector<double> state() const override
      {
        return {last_time, averaged[0], averaged[1], averaged[2], averaged[3]};
      }
      void set_state(const std::vector<double> &s) override
      {
        if (s.size() != 5)
          return;
        last_time = s[0];
        std::copy(s.begin() + 1, s.end(), averaged);
      }

    private:
      double last_time   = 0.;
      double averaged[4] = {0., 0., 0., 0.};
    };
  } // namespace

  std::unique_ptr<CouplingProbe> make_porous_block_probe()
  {
    return std::make_unique<PorousBlockProbe>();
  }
} // namespace sluice
