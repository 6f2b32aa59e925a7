// Closed-form checks of an imported analytic field (see the header).

#include <sluice/core/mpi_extremum.h>
#include <sluice/core/mpi_gather.h>
#include <sluice/core/result_line.h>
#include <sluice/coupling/drag_closures.h>
#include <sluice/coupling/imported_field_check.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <iomanip>
#include <sstream>

namespace sluice
{
  namespace
  {
    using Complex = std::complex<double>;

    /// |w| with k(|w|) |w| = force (k |w| grows with |w|): bisection.
    double terminal_slip(const DragClosure closure, DragState s, const double force)
    {
      const auto excess = [&](const double w) {
        s.slip = w;
        return particle_drag_coefficient(closure, s) * w - force;
      };
      double lo = 0., hi = 1e-6;
      while (excess(hi) < 0. && hi < 1e6)
        hi *= 2.;
      for (unsigned int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i)
        (excess(0.5 * (lo + hi)) < 0. ? lo : hi) = 0.5 * (lo + hi);
      return 0.5 * (lo + hi);
    }
  } // namespace

  ImportedFieldCheck::ImportedFieldCheck(const ImportedFieldParameters &p, const Vec3 &gravity)
    : check(p.check), U(p.check_velocity), g(gravity), omega(p.check_angular_velocity)
    , rho_f(p.density), mu(p.viscosity), drag(p.drag), hydrostatic(p.hydrostatic_in_pressure)
  {}

  Vec3 ImportedFieldCheck::analytic_velocity(const Vec3 &x) const
  {
    return check == FieldCheck::uniform_stream ? U : omega * Vec3(-x.y, x.x, 0.);
  }

  Vec3 ImportedFieldCheck::analytic_pressure_gradient(const Vec3 &x) const
  {
    Vec3 grad = hydrostatic ? rho_f * g : Vec3();
    if (check == FieldCheck::solid_body_vortex)
      grad += rho_f * omega * omega * Vec3(x.x, x.y, 0.);
    return grad;
  }

  void ImportedFieldCheck::start(const ParticleStorage &P, MPI_Comm comm)
  {
    std::vector<double> mine;
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        mine.push_back(static_cast<double>(P.id[i]));
        for (const Vec3 &v : {P.position[i], P.velocity[i]})
          mine.insert(mine.end(), {v.x, v.y, v.z});
      }
    initial = gathered(mine, comm);
  }

  void ImportedFieldCheck::observe(const Vec3 &x, const ParticleFluidSample &s)
  {
    const Vec3 u = analytic_velocity(x), grad = analytic_pressure_gradient(x);
    if (norm(u) > 0.)
      max_velocity_error = std::max(max_velocity_error, norm(s.velocity - u) / norm(u));
    if (norm(grad) > 0.)
      max_gradient_error =
        std::max(max_gradient_error, norm(s.pressure_gradient - grad) / norm(grad));
  }

  std::string ImportedFieldCheck::finish(const ParticleStorage &P, const FluidShapes &shapes,
                                         const double t, const double wall_s, MPI_Comm comm,
                                         double &error) const
  {
    // Per local particle: the value, its reference and the position error.
    double worst[4] = {0., 0., 0., 0.}; // error, value, reference, position error
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        const double *rec = nullptr;
        for (std::size_t k = 0; k < initial.size(); k += 7)
          if (static_cast<std::uint64_t>(initial[k]) == P.id[i])
            rec = &initial[k];
        if (!rec)
          continue; // inserted later (a stream): no closed form
        const Vec3   x0(rec[1], rec[2], rec[3]), v0(rec[4], rec[5], rec[6]);
        // A clump settles across the stream with its sphericities along gravity.
        const FluidShape shape = shapes.exact_shape(i, g);
        const double     m = P.mass[i], m_f = rho_f * shape.volume;
        DragState        s;
        s.density = rho_f, s.viscosity = mu, s.diameter = shape.diameter;
        s.sphericity            = shape.sphericities.sphericity;
        s.crosswise_sphericity  = shape.sphericities.crosswise;
        s.lengthwise_sphericity = shape.sphericities.lengthwise;
        double value = 0., reference = 0., position_error = 0.;
        if (check == FieldCheck::uniform_stream)
          {
            const Vec3   weight = (m - m_f) * g;
            const double w      = terminal_slip(drag, s, norm(weight));
            const Vec3   exact  = norm(weight) > 0. ? (w / norm(weight)) * weight : Vec3();
            value               = norm(P.velocity[i] - U);
            reference           = w;
            position_error      = norm(P.velocity[i] - U - exact) / std::max(w, 1e-300);
          }
        else
          {
            const double  k = particle_drag_coefficient(drag, s);
            const Complex c(m_f * omega * omega, -k * omega);
            const Complex Zp = (m - m_f) * Complex(g.x, g.y) / c;
            const Complex root = std::sqrt(Complex(k * k) - 4. * m * c);
            const Complex l1 = (-k + root) / (2. * m), l2 = (-k - root) / (2. * m);
            const Complex Y0 = Complex(x0.x, x0.y) - Zp, dY0(v0.x, v0.y);
            const Complex A = (dY0 - l2 * Y0) / (l1 - l2), B = Y0 - A;
            const Complex Z = Zp + A * std::exp(l1 * t) + B * std::exp(l2 * t);
            const double  tau = m / k, v_inf = (m - m_f) * g.z / k;
            const double  z = x0.z + v_inf * t + (v0.z - v_inf) * tau * (1. - std::exp(-t / tau));
            const double  r0 = std::hypot(x0.x, x0.y);
            value            = std::hypot(P.position[i].x, P.position[i].y) - r0;
            reference        = std::abs(Z) - r0;
            position_error   = norm(P.position[i] - Vec3(Z.real(), Z.imag(), z)) / std::abs(Z);
          }
        const double e = std::abs(value - reference) / std::max(std::abs(reference), 1e-300);
        if (e >= worst[0])
          worst[0] = e, worst[1] = value, worst[2] = reference;
        worst[3] = std::max(worst[3], position_error);
      }
    // The worst particle's record: its error wins (ties: any).
    share_from(rank_of_greatest(worst[0], comm).rank, worst, 3, comm);
    double maxima[3] = {worst[3], max_velocity_error, max_gradient_error};
    MPI_Allreduce(MPI_IN_PLACE, maxima, 3, MPI_DOUBLE, MPI_MAX, comm);
    error = worst[0];

    std::ostringstream out;
    out << std::setprecision(6);
    const bool stream = check == FieldCheck::uniform_stream;
    out << "check: interpolation max relative error velocity=" << maxima[1]
        << " pressure_gradient=" << maxima[2] << "\n";
    out << "check: " << (stream ? "terminal slip vector relative error=" :
                                  "position relative to the orbit radius error=")
        << maxima[0] << "\n";
    write_result_line(out, stream ? "imported_field_terminal_slip" : "imported_field_orbit_drift",
                      worst[1], worst[2], worst[0], wall_s);
    return out.str();
  }

  std::vector<double> ImportedFieldCheck::state(MPI_Comm comm) const
  {
    std::vector<double> s = {max_velocity_error, max_gradient_error};
    MPI_Allreduce(MPI_IN_PLACE, s.data(), 2, MPI_DOUBLE, MPI_MAX, comm);
    s.insert(s.end(), initial.begin(), initial.end());
    return s;
  }

  void ImportedFieldCheck::set_state(const std::vector<double> &s)
  {
    if (s.size() < 2)
      return;
    max_velocity_error = s[0];
    max_gradient_error = s[1];
    initial.assign(s.begin() + 2, s.end());
  }
} // namespace sluice
