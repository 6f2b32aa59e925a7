#pragma once
// A manufactured solution of the volume-averaged Navier-Stokes equations with a
// porosity that varies in space (and, if transient, in time), on the unit cube.
// The velocity is not solenoidal and eps u is not either, so every term of both
// momentum forms and of the continuity equation is exercised; the forcing that
// makes the fields exact is computed from the formulas by TaylorJet.

#include <sluice/core/fluid_parameters.h>
#include <sluice/fluid/taylor_jet.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

namespace sluice
{
  class ManufacturedSolution
  {
  public:
    /// polynomial_in_space: u quadratic and p linear in x (exact in Q2-Q1, so
    /// only the time discretisation errs); otherwise trigonometric.
    ManufacturedSolution(double density, double viscosity, VansFormulation formulation,
                         bool transient, bool polynomial_in_space = false);

    dealii::Tensor<1, 3> velocity(const dealii::Point<3> &x, double t) const;
    double               pressure(const dealii::Point<3> &x, double t) const;
    double               porosity(const dealii::Point<3> &x, double t) const;
    dealii::Tensor<1, 3> porosity_gradient(const dealii::Point<3> &x, double t) const;

    /// The force per volume f that the momentum equation needs on its right side.
    dealii::Tensor<1, 3> momentum_source(const dealii::Point<3> &x, double t) const;
    /// s in d(eps)/dt + div(eps u) = s.
    double mass_source(const dealii::Point<3> &x, double t) const;

  private:
    struct Fields
    {
      std::array<TaylorJet, 3> u;
      TaylorJet                p, eps;
    };
    Fields fields(const dealii::Point<3> &x, double t) const;

    double          density, viscosity;
    VansFormulation formulation;
    bool            transient;
    bool            polynomial;
  };
} // namespace sluice
