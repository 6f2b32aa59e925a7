// A suspension layer above clear fluid (Robinson et al. 2014): the growth
// rate of the layer's lowest particle against the two-fluid bounds.

#include <sluice/coupling/coupling_probe.h>
#include <sluice/coupling/rayleigh_taylor.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace sluice
{
  namespace
  {
    class RayleighTaylorProbe : public CouplingProbe
    {
    public:
      /// The layer starts in the mode of wavenumber sqrt(2) 2 pi / L, its
      /// lowest particle d/2 below the rest (Robinson et al. 2014, Eq. 40).
      void prepare(ProbeView &view) override
      {
        const SceneParameters &p = view.p;
        ParticleStorage       &P = view.dem.particles;
        const double           L = length(p);
        for (unsigned int i = 0; i < P.n_local; ++i)
          {
            const double X = 2. * M_PI * (P.position[i].x - p.lower_corner.x) / L;
            const double Y = 2. * M_PI * (P.position[i].y - p.lower_corner.y) / L;
            P.position[i].z -= 0.25 * P.radius[i] * (1. - std::cos(X)) * (1. - std::cos(Y));
          }
        view.dem.update_neighbours();
      }

      void start(ProbeView &view) override { observe(0., view); }

      void observe(const double time, ProbeView &view) override
      {
        const ParticleStorage &P   = view.dem.particles;
        double                 low = std::numeric_limits<double>::max(), sum = 0.;
        for (unsigned int i = 0; i < P.n_local; ++i)
          {
            low = std::min(low, P.position[i].z);
            sum += P.position[i].z;
          }
        MPI_Allreduce(MPI_IN_PLACE, &low, 1, MPI_DOUBLE, MPI_MIN, view.comm);
        MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, view.comm);
        times.push_back(time);
        heights.emplace_back(
          low, sum / std::max<double>(1., view.dem.n_inserted - view.dem.n_lost));
      }

      /// The depth of the lowest particle below its undisturbed layer,
      /// a = z_low(0) + d/2 - z_low - (zbar(0) - zbar) (the layer's uniform
      /// settling removed), grows as a0 cosh(n t) in the linear regime. The fit
      /// uses the steps while k a <= 0.5 and the front is in the upper half of
      /// the clear fluid below the layer.
      ProbeResult finish(ProbeView &view) override
      {
        const FluidParameters &fp  = view.fluid;
        const double           d   = 2. * view.dem.r_max;
        const double           k   = std::sqrt(2.) * 2. * M_PI / length(view.p);
        const double           eps = view.p.coupling.block_porosity, g = norm(view.p.gravity);
        const double           z_front0    = heights[0].first;
        const double           clear_depth = z_front0 - view.p.lower_corner.z;
        std::vector<double>    t_fit, a_fit;
        for (std::size_t i = 0; i < heights.size(); ++i)
          {
            const double a =
              z_front0 + 0.5 * d - heights[i].first - (heights[0].second - heights[i].second);
            if (k * a > 0.5 || heights[i].first < z_front0 - 0.5 * clear_depth)
              break;
            t_fit.push_back(times[i]);
            a_fit.push_back(a);
          }
        const double rho1 = fp.density, mu1 = fp.viscosity;
        const double rho2 = eps * rho1 + (1. - eps) * particle_density(view);
        const double lower =
          rayleigh_taylor_growth_rate(rho1, mu1, rho2, krieger_viscosity(mu1, 1. - eps), k, g);
        // The bounds of the two-fluid model: the heavy layer with the Krieger
        // viscosity of the suspension (lower) and without viscosity (upper,
        // sqrt(A g k)); viscosity only slows the growth. The rate with the
        // clear fluid's viscosity in both layers is printed for comparison.
        const double upper       = inviscid_growth_rate(rho1, rho2, k, g);
        const double clear_fluid = rayleigh_taylor_growth_rate(rho1, mu1, rho2, mu1, k, g);
        ProbeResult  r;
        r.name  = "rayleigh_taylor";
        r.value = fit_growth_rate_from_rest(t_fit, a_fit);
        // The nearer bound; the error is the distance outside [lower, upper].
        r.reference = std::abs(r.value - lower) < std::abs(r.value - upper) ? lower : upper;
        r.error = r.value < lower || r.value > upper ? std::abs(r.value - r.reference) / r.reference :
                                                       0.;
        std::ostringstream check;
        check.precision(view.p.summary_precision);
        check << "check: rayleigh_taylor lower_bound_krieger=" << lower
              << " upper_bound_inviscid=" << upper << " clear_fluid_viscosity=" << clear_fluid
              << " fitted_steps=" << t_fit.size()
              << " fit_end_time=" << (t_fit.empty() ? 0. : t_fit.back())
              << " final_amplitude=" << (a_fit.empty() ? 0. : a_fit.back());
        r.checks.push_back(check.str());
        return r;
      }

      /// (t, lowest, mean height) per observation.
      std::vector<double> state() const override
      {
        std::vector<double> s;
        for (std::size_t k = 0; k < times.size(); ++k)
          s.insert(s.end(), {times[k], heights[k].first, heights[k].second});
        return s;
      }
      void set_state(const std::vector<double> &s) override
      {
        for (std::size_t k = 0; k + 2 < s.size(); k += 3)
          {
            times.push_back(s[k]);
            heights.emplace_back(s[k + 1], s[k + 2]);
          }
      }

    private:
      /// The periodic width of the scene's domain: the finite-element mesh's
      /// box, or the SPH fluid's, which has no mesh.
      static double length(const SceneParameters &p)
      {
        return p.upper_corner.x - p.lower_corner.x;
      }

      std::vector<double>                    times;
      std::vector<std::pair<double, double>> heights; // lowest and mean particle height
    };
  } // namespace

  std::unique_ptr<CouplingProbe> make_rayleigh_taylor_probe()
  {
    return std::make_unique<RayleighTaylorProbe>();
  }
} // namespace sluice
