// One particle settling from rest: its velocity through the whole history
// against the single-particle equation of motion integrated accurately. A
// clump body settles with the drag of its shape: its union volume,
// volume-equivalent diameter and sphericities along gravity, computed
// directly (the run interpolates them in a table), in the orientation it
// keeps (the drag acts at the centroid and exerts no torque).

#include <sluice/core/mpi_extremum.h>
#include <sluice/core/sphere.h>
#include <sluice/coupling/coupling_probe.h>
#include <sluice/coupling/drag_closures.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// The single-particle equation of motion along the scene's gravity,
    /// (m + m_a) dv/dt = (m - rho_f V b) g + k(|u - v|) (u - v) with u = 0
    /// (b = 1 when buoyancy is part of the model), by RK4 with steps of
    /// tau / 2000; returns v(t) at the requested times.
    std::vector<Vec3> single_particle_velocity(const SceneParameters &p, const FluidShape &shape,
                                               const double density, const Vec3 &v0,
                                               const std::vector<double> &times)
    {
      const auto  &c   = p.coupling;
      const double d = shape.diameter, V = shape.volume, m = density * V;
      const double rho = p.fluid.density;
      const bool   buoyancy =
        c.formulation == CouplingFormulation::set_iii || c.pressure_gradient_force;
      const double m_eff  = m + c.virtual_mass_coefficient * rho * V;
      const Vec3   weight = (m - (buoyancy ? rho * V : 0.)) * p.gravity;
      const auto   accel  = [&](const Vec3 &v) {
        DragState s;
        s.eps       = 1.;
        s.density   = rho;
        s.viscosity = p.fluid.viscosity;
        s.diameter  = d;
        s.slip      = norm(v);
        s.sphericity            = shape.sphericities.sphericity;
        s.crosswise_sphericity  = shape.sphericities.crosswise;
        s.lengthwise_sphericity = shape.sphericities.lengthwise;
        return (1. / m_eff) * (weight - particle_drag_coefficient(c.drag, s) * v);
      };
      DragState s0;
      s0.density = rho, s0.viscosity = p.fluid.viscosity, s0.diameter = d, s0.slip = 1e-12;
      const double tau = m_eff / particle_drag_coefficient(DragClosure::stokes, s0);
      std::vector<Vec3> out;
      Vec3              v = v0;
      double            t = 0.;
      for (const double target : times)
        {
          while (t < target)
            {
              const double h  = std::min(tau / 2000., target - t);
              const Vec3   k1 = accel(v), k2 = accel(v + 0.5 * h * k1),
                         k3 = accel(v + 0.5 * h * k2), k4 = accel(v + h * k3);
              v += (h / 6.) * (k1 + 2. * k2 + 2. * k3 + k4);
              t += h;
            }
          out.push_back(v);
        }
      return out;
    }

    /// Collective: the first particle's shape for a slip along gravity, from
    /// whichever rank owns it (a sphere of the largest radius in a sphere scene).
    FluidShape settling_shape(const ProbeView &view)
    {
      if (!view.dem.clumps)
        return FluidShape{sphere_volume(view.dem.r_max), 2. * view.dem.r_max, Sphericities()};
      const ParticleStorage &P = view.dem.handler_particles();
      FluidShape             f;
      if (P.n_local > 0)
        f = view.shapes.exact_shape(0, view.p.gravity);
      // The lowest rank that owns a body sends its shape.
      const int owner = rank_of_greatest(P.n_local > 0 ? 1. : 0., view.comm).rank;
      double numbers[5] = {f.volume, f.diameter, f.sphericities.sphericity,
                           f.sphericities.crosswise, f.sphericities.lengthwise};
      share_from(owner, numbers, 5, view.comm);
      return FluidShape{numbers[0], numbers[1], Sphericities{numbers[2], numbers[3], numbers[4]}};
    }

    class SedimentationProbe : public CouplingProbe
    {
    public:
      void start(ProbeView &view) override
      {
        v0 = global_mean_velocity(view.dem.handler_particles(), view.comm);
      }

      void observe(const double time, ProbeView &view) override
      {
        times.push_back(time);
        velocities.push_back(global_mean_velocity(view.dem.handler_particles(), view.comm));
      }

      ProbeResult finish(ProbeView &view) override
      {
        const SceneParameters  &p     = view.p;
        const Vec3              v_end = global_mean_velocity(view.dem.handler_particles(), view.comm);
        const FluidShape        shape = settling_shape(view);
        const std::vector<Vec3> exact =
          single_particle_velocity(p, shape, particle_density(view), v0, times);
        const Vec3   g_hat   = (1. / norm(p.gravity)) * p.gravity;
        double       history = 0.;
        const double scale   = std::abs(dot(exact.back(), g_hat));
        for (unsigned int k = 0; k < exact.size(); ++k)
          history = std::max(history, std::abs(dot(velocities[k] - exact[k], g_hat)) / scale);
        ProbeResult r;
        r.name      = "sedimentation";
        r.value     = dot(v_end, g_hat);
        r.reference = dot(exact.back(), g_hat);
        r.error     = std::abs(r.value - r.reference) / std::abs(r.reference);
        // The porosity the particle sees includes its own volume, spread over the kernel.
        double lowest_porosity = 1.;
        for (const ParticleFluidSample &sample : view.samples)
          if (sample.found)
            lowest_porosity = std::min(lowest_porosity, sample.porosity);
        MPI_Allreduce(MPI_IN_PLACE, &lowest_porosity, 1, MPI_DOUBLE, MPI_MIN, view.comm);
        std::ostringstream check;
        check.precision(p.summary_precision);
        check << "check: sedimentation velocity_history_max_relative_deviation=" << history
              << " porosity_at_particle=" << lowest_porosity;
        r.checks.push_back(check.str());
        if (!shape.sphericities.spherical())
          {
            // What the reference took of the body's shape.
            std::ostringstream body;
            body.precision(p.summary_precision);
            body << "check: settling body volume=" << shape.volume
                 << " volume_equivalent_diameter=" << shape.diameter
                 << " sphericity=" << shape.sphericities.sphericity
                 << " crosswise_sphericity=" << shape.sphericities.crosswise
                 << " lengthwise_sphericity=" << shape.sphericities.lengthwise;
            r.checks.push_back(body.str());
          }
        return r;
      }

      /// v0, then (t, v) per observation.
      std::vector<double> state() const override
      {
        std::vector<double> s{v0.x, v0.y, v0.z};
        for (std::size_t k = 0; k < times.size(); ++k)
          s.insert(s.end(), {times[k], velocities[k].x, velocities[k].y, velocities[k].z});
        return s;
      }
      void set_state(const std::vector<double> &s) override
      {
        if (s.size() < 3)
          return;
        v0 = Vec3(s[0], s[1], s[2]);
        for (std::size_t k = 3; k + 3 < s.size(); k += 4)
          {
            times.push_back(s[k]);
            velocities.emplace_back(s[k + 1], s[k + 2], s[k + 3]);
          }
      }

    private:
      Vec3                v0;
      std::vector<double> times;
      std::vector<Vec3>   velocities;
    };
  } // namespace

  std::unique_ptr<CouplingProbe> make_sedimentation_probe()
  {
    return std::make_unique<SedimentationProbe>();
  }
} // namespace sluice
