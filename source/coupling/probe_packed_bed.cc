// A fixed bed with flow through it: the mean pressure gradient at the
// particles in the middle half of the bed against Ergun at the bed porosity
// and superficial velocity.

#include <sluice/coupling/coupling_probe.h>

#include <cmath>
#include <sstream>

namespace sluice
{
  namespace
  {
    class PackedBedProbe : public CouplingProbe
    {
    public:
      ProbeResult finish(ProbeView &view) override
      {
        const SceneParameters &p  = view.p;
        const FluidParameters &fp = view.fluid;
        const ParticleStorage &P  = view.dem.particles;
        const auto in_bed_middle  = in_middle_half(P, Vec3(0., 0., 1.), view.comm);
        const auto &samples       = view.samples;
        double     sums[4]        = {0., 0., 0., 0.};
        for (unsigned int i = 0; i < P.n_local; ++i)
          if (samples[i].found && in_bed_middle(P.position[i]))
            {
              sums[0] += -samples[i].pressure_gradient[2];
              sums[1] += 1.;
              sums[2] += samples[i].porosity;
              sums[3] += samples[i].velocity[2];
            }
        MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, view.comm);
        const FluidIntegrals I = view.backend.integrals();
        const double cross_section =
          (fp.upper_corner.x - fp.lower_corner.x) * (fp.upper_corner.y - fp.lower_corner.y);
        const double U = I.flow_rates.empty() ? 0. : std::abs(I.flow_rates[0]) / cross_section;
        const double eps = p.coupling.block_porosity, d = 2. * view.dem.r_max, mu = fp.viscosity;
        ProbeResult  r;
        r.name      = "packed_bed";
        r.value     = sums[0] / std::max(sums[1], 1.);
        r.reference = 150. * mu * (1. - eps) * (1. - eps) * U / (eps * eps * eps * d * d) +
                      1.75 * fp.density * (1. - eps) * U * U / (eps * eps * eps * d);
        r.error = std::abs(r.value - r.reference) / r.reference;
        std::ostringstream check;
        check.precision(p.summary_precision);
        check << "check: packed_bed superficial_velocity=" << U
              << " bed_particles_sampled=" << sums[1]
              << " mean_porosity=" << sums[2] / std::max(sums[1], 1.)
              << " mean_fluid_velocity=" << sums[3] / std::max(sums[1], 1.);
        r.checks.push_back(check.str());
        return r;
      }
    };
  } // namespace

  std::unique_ptr<CouplingProbe> make_packed_bed_probe()
  {
    return std::make_unique<PackedBedProbe>();
  }
} // namespace sluice
