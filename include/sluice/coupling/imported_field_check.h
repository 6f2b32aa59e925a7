#pragma once
// The closed forms an imported analytic field is checked against
// ('imported field/check'; prm/geometry/imported_field.prm):
//
// uniform stream u = U, p = rho_f g . x: a particle's terminal slip w solves
// the force balance k(|w|) w = (m - m_f) g (m_f = rho_f V_p; the drag
// closure's k, found by bisection since k depends on |w|).
//
// solid-body vortex u = Omega e_z x x, p = rho_f Omega^2 r^2 / 2 + rho_f g . x,
// Stokes drag k = 3 pi mu d: in the plane, with Z = x + i y,
//   m Z'' + k Z' + (m_f Omega^2 - i k Omega) Z = (m - m_f)(g_x + i g_y),
// solved as Z_p + A e^(l1 t) + B e^(l2 t) (l the roots of m l^2 + k l + c);
// along z the settling solution z0 + v_inf t + (v_z0 - v_inf) tau (1 - e^(-t/tau)).
// The error of the orbit is that of its radial drift, r(T) - r(0).
//
// Every step, the field sampled at each particle is compared with the
// analytic one: the largest relative interpolation error of u and grad p.

#include <sluice/core/imported_field_parameters.h>
#include <sluice/coupling/fluid_backend.h>
#include <sluice/coupling/fluid_shapes.h>
#include <sluice/dem/particle_storage.h>

#include <mpi.h>

#include <iosfwd>
#include <vector>

namespace sluice
{
  class ImportedFieldCheck
  {
  public:
    ImportedFieldCheck(const ImportedFieldParameters &parameters, const Vec3 &gravity);

    bool active() const { return check != FieldCheck::none; }

    /// At the start: every particle's initial position and velocity (all ranks).
    void start(const ParticleStorage &P, MPI_Comm comm);
    /// The sampled field at one particle against the analytic one.
    void observe(const Vec3 &x, const ParticleFluidSample &s);

    /// Collective: the check lines and the result line for rank 0; 'error'
    /// the largest over the particles (shapes: their volumes and drag shapes).
    std::string finish(const ParticleStorage &P, const FluidShapes &shapes, double time,
                       double wall_s, MPI_Comm comm, double &error) const;

    /// Collective: the largest interpolation errors over all ranks, and the
    /// particles' initial states.
    std::vector<double> state(MPI_Comm comm) const;
    void                set_state(const std::vector<double> &state);

  private:
    FieldCheck check;
    Vec3       U, g;
    double     omega, rho_f, mu;
    DragClosure drag;
    bool        hydrostatic;
    // id, x0, v0 per particle.
    std::vector<double> initial;
    double              max_velocity_error = 0., max_gradient_error = 0.;
    Vec3                analytic_velocity(const Vec3 &x) const;
    Vec3                analytic_pressure_gradient(const Vec3 &x) const;
  };
} // namespace sluice
