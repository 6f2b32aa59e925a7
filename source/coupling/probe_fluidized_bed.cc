// A bed fluidized by an inlet flow: the bed pressure drop against the buoyant
// bed weight per area, and the minimum fluidization velocity from the inlet
// ramp against Wen & Yu (1966).

#include <sluice/coupling/coupling_probe.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace sluice
{
  namespace
  {
    class FluidizedBedProbe : public CouplingProbe
    {
    public:
      /// Every fluid step's inlet flow and bed pressure drop, kept with its
      /// time: the second half is chosen at the end, so that a run stopped
      /// at T/2 and continued to T averages what the uninterrupted run does.
      void observe(const double time, ProbeView &view) override
      {
        const FluidParameters &fp = view.fluid;
        const FluidIntegrals   fi = view.backend.integrals();
        const double           U =
          fi.flow_rates.empty() ? 0. : std::abs(fi.flow_rates[0]) / cross_section(fp);
        steps.push_back({time, U, fi.pressure_drop});
      }

      /// Measured drop minus the fluid's own hydrostatics, averaged over the
      /// second half, against the buoyant weight per area.
      ProbeResult finish(ProbeView &view) override
      {
        const SceneParameters &p  = view.p;
        const FluidParameters &fp = view.fluid;
        const ParticleStorage &P  = view.dem.particles;
        const FluidIntegrals   I  = view.backend.integrals();
        double                 weight = 0.;
        for (unsigned int i = 0; i < P.n_local; ++i)
          weight += P.mass[i] * (1. - fp.density / p.density[P.type[i]]) * norm(p.gravity);
        MPI_Allreduce(MPI_IN_PLACE, &weight, 1, MPI_DOUBLE, MPI_SUM, view.comm);
        const double hydrostatic = fp.density * norm(p.gravity) * I.drop_distance;
        double       pressure_drop_sum     = 0.;
        unsigned int pressure_drop_samples = 0;
        for (const Step &step : steps)
          if (step.time > 0.5 * p.end_time)
            pressure_drop_sum += step.pressure_drop, ++pressure_drop_samples;
        ProbeResult r;
        r.name      = "fluidized_bed";
        r.value     = pressure_drop_sum / std::max(1u, pressure_drop_samples) - hydrostatic;
        r.reference = weight / cross_section(fp);
        r.error     = std::abs(r.value - r.reference) / r.reference;
        r.checks.push_back(minimum_fluidization(view, r.reference, hydrostatic));
        return r;
      }

      /// (time, U, pressure drop) per fluid step.
      std::vector<double> state() const override
      {
        std::vector<double> s;
        for (const Step &step : steps)
          s.insert(s.end(), {step.time, step.inlet_velocity, step.pressure_drop});
        return s;
      }
      void set_state(const std::vector<double> &s) override
      {
        steps.clear();
        for (std::size_t k = 0; k + 2 < s.size(); k += 3)
          steps.push_back({s[k], s[k + 1], s[k + 2]});
      }

    private:
      static double cross_section(const FluidParameters &fp)
      {
        return (fp.upper_corner.x - fp.lower_corner.x) * (fp.upper_corner.y - fp.lower_corner.y);
      }

      /// Kunii & Levenspiel: the fixed-bed branch, dp = a U + b U^2 fitted by
      /// least squares to the ramp's points (inlet flow started) between 10%
      /// and 80% of the weight per area, before the bed first carries 80%,
      /// meets the weight per area at U_mf.
      std::string minimum_fluidization(const ProbeView &view, const double reference,
                                       const double hydrostatic) const
      {
        // Sums of U^2, U^3, U^4, U p, U^2 p.
        double       s22 = 0., s23 = 0., s33 = 0., s2p = 0., s3p = 0.;
        unsigned int n_fit = 0;
        for (const Step &step : steps)
          {
            const double U = step.inlet_velocity, dp = step.pressure_drop - hydrostatic;
            if (U <= 1e-12) // before the ramp (or without an inlet): the bed settles
              continue;
            if (dp > 0.8 * reference)
              break;
            if (dp < 0.1 * reference)
              continue;
            s22 += U * U, s23 += U * U * U, s33 += U * U * U * U;
            s2p += U * dp, s3p += U * U * dp;
            ++n_fit;
          }
        std::ostringstream check;
        check.precision(view.p.summary_precision);
        const double det = s22 * s33 - s23 * s23;
        const bool   fitted = n_fit >= 3 && det > 0.;
        const double a      = fitted ? (s2p * s33 - s3p * s23) / det : 0.;
        const double b      = fitted ? (s22 * s3p - s23 * s2p) / det : 0.;
        // The positive root of a U + b U^2 = weight; none if the fitted branch
        // never reaches the weight (a bed still settling bends it down).
        const double discriminant = a * a + 4. * b * reference;
        const double U_mf =
          b != 0. ? (-a + std::sqrt(std::max(0., discriminant))) / (2. * b) : reference / a;
        if (fitted && discriminant >= 0. && std::isfinite(U_mf) && U_mf > 0.)
          {
            // Wen & Yu (1966): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7.
            const double d = 2. * view.dem.r_max, rho = view.fluid.density;
            const double mu = view.fluid.viscosity, rho_p = particle_density(view);
            const double Ar = d * d * d * rho * (rho_p - rho) * norm(view.p.gravity) / (mu * mu);
            const double wen_yu = (std::sqrt(33.7 * 33.7 + 0.0408 * Ar) - 33.7) * mu / (rho * d);
            check << "check: fluidized_bed minimum_fluidization_velocity=" << U_mf
                  << " wen_yu=" << wen_yu << " ratio=" << U_mf / wen_yu << " fit_points=" << n_fit
                  << " archimedes=" << Ar;
          }
        else if (!fitted)
          check << "check: fluidized_bed minimum_fluidization_velocity=none (the inlet ramp "
                   "has fewer than three points between 10% and 80% of the bed weight)";
        else
          check << "check: fluidized_bed minimum_fluidization_velocity=none (the fixed-bed fit "
                   "dp = a U + b U^2, a = "
                << a << ", b = " << b << ", fit_points = " << n_fit
                << ", does not reach the bed weight: the bed was not at rest during the ramp)";
        return check.str();
      }

      struct Step
      {
        double time;           // [s]
        double inlet_velocity; // superficial [m/s]; 0 without an inlet flow
        double pressure_drop;  // measured, with the fluid's hydrostatics [Pa]
      };
      std::vector<Step> steps;
    };
  } // namespace

  std::unique_ptr<CouplingProbe> make_fluidized_bed_probe()
  {
    return std::make_unique<FluidizedBedProbe>();
  }
} // namespace sluice
