// The probe factory and what the probes share (see the header).

#include <sluice/coupling/coupling_probe.h>
#include <sluice/coupling/drag_closures.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sluice
{
  std::unique_ptr<CouplingProbe> make_coupling_probe(const CouplingValidationCase validation)
  {
    switch (validation)
      {
        case CouplingValidationCase::sedimentation:
          return make_sedimentation_probe();
        case CouplingValidationCase::porous_block:
          return make_porous_block_probe();
        case CouplingValidationCase::packed_bed:
          return make_packed_bed_probe();
        case CouplingValidationCase::fluidized_bed:
          return make_fluidized_bed_probe();
        case CouplingValidationCase::rayleigh_taylor:
          return make_rayleigh_taylor_probe();
        case CouplingValidationCase::segregation:
          return make_segregation_probe();
        default:
          return nullptr;
      }
  }

  Vec3 global_mean_velocity(const ParticleStorage &P, MPI_Comm comm)
  {
    double s[4] = {0., 0., 0., static_cast<double>(P.n_local)};
    for (unsigned int i = 0; i < P.n_local; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        s[d] += P.velocity[i][d];
    MPI_Allreduce(MPI_IN_PLACE, s, 4, MPI_DOUBLE, MPI_SUM, comm);
    return s[3] > 0. ? Vec3(s[0] / s[3], s[1] / s[3], s[2] / s[3]) : Vec3();
  }

  std::function<bool(const Vec3 &)> in_middle_half(const ParticleStorage &P, const Vec3 &e,
                                                   MPI_Comm comm)
  {
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        lo = std::min(lo, dot(P.position[i], e));
        hi = std::max(hi, dot(P.position[i], e));
      }
    MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, comm);
    MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, comm);
    return [=](const Vec3 &x) { return std::abs(dot(x, e) - 0.5 * (lo + hi)) < 0.25 * (hi - lo); };
  }

  double particle_density(const ProbeView &view)
  {
    const ParticleStorage &P = view.dem.handler_particles();
    return view.p.density[P.n_local > 0 ? P.type[0] : 0];
  }

  double slip_for_force(const SceneParameters &p, const double d, const double eps,
                        const double target)
  {
    DragState s;
    s.eps       = eps;
    s.density   = p.fluid.density;
    s.viscosity = p.fluid.viscosity;
    s.diameter  = d;
    double     lo = 0., hi = 1.;
    const auto force = [&](const double w) {
      s.slip = w;
      return particle_drag_coefficient(p.coupling.drag, s) * w;
    };
    while (force(hi) < target)
      hi *= 2.;
    for (unsigned int it = 0; it < 200; ++it)
      {
        const double mid = 0.5 * (lo + hi);
        (force(mid) < target ? lo : hi) = mid;
      }
    return 0.5 * (lo + hi);
  }
} // namespace sluice
