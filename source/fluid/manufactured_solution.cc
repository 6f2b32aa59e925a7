// The manufactured fields and the forcing they imply. Momentum, in the
// non-conservative form the solver uses (equal to the conservative one when the
// continuity equation holds):
//   model A: rho eps (du/dt + (grad u) u) + eps grad p - eps div tau = f
//   model B: rho eps (du/dt + (grad u) u) +     grad p -     div tau = f
// with div tau = mu (lap u + 1/3 grad div u) for tau = mu (grad u + grad u^T
// - 2/3 div u I); continuity d(eps)/dt + eps div u + u . grad eps = s.

#include <sluice/fluid/manufactured_solution.h>

#include <cmath>

namespace sluice
{
  ManufacturedSolution::ManufacturedSolution(const double density, const double viscosity,
                                             const VansFormulation formulation,
                                             const bool transient, const bool polynomial)
    : density(density)
    , viscosity(viscosity)
    , formulation(formulation)
    , transient(transient)
    , polynomial(polynomial)
  {}

  ManufacturedSolution::Fields ManufacturedSolution::fields(const dealii::Point<3> &p,
                                                           const double time) const
  {
    const double pi = M_PI;
    const TaylorJet x = TaylorJet::variable(0, p[0]), y = TaylorJet::variable(1, p[1]),
                    z = TaylorJet::variable(2, p[2]), t = TaylorJet::variable(3, time);
    // Amplitudes in time: 1 for the steady solution.
    const TaylorJet a_u   = transient ? 1. + 0.5 * sin(2. * t) : TaylorJet(1.);
    const TaylorJet a_eps = transient ? cos(t) : TaylorJet(1.);

    Fields f;
    if (polynomial)
      {
        f.u[0] = a_u * (x * (1. - x) + y * z);
        f.u[1] = a_u * (y * (1. - x) + 0.5 * z * z);
        f.u[2] = a_u * (0.5 * x * y - z * z);
        f.p    = a_u * (x + 2. * y - z);
        // Linear in space: then every integral of the weak form is exact in
        // Gauss(3) quadrature and the discrete solution equals the exact one.
        f.eps = 0.7 + a_eps * (0.1 * x - 0.1 * y + 0.05 * z);
        return f;
      }
    f.u[0] = a_u * sin(pi * x) * cos(pi * y) * cos(pi * z);
    f.u[1] = a_u * cos(pi * x) * sin(pi * y) * cos(pi * z) * 0.5;
    f.u[2] = a_u * cos(pi * x) * cos(pi * y) * sin(pi * z) * 0.25;
    f.p    = a_u * sin(pi * x) * sin(pi * y) * cos(pi * z);
    // Porosity between 0.5 and 0.9.
    f.eps = 0.7 + 0.2 * a_eps * sin(pi * x) * cos(pi * y) * sin(pi * z + 0.3);
    return f;
  }

  dealii::Tensor<1, 3> ManufacturedSolution::velocity(const dealii::Point<3> &x,
                                                       const double t) const
  {
    const Fields f = fields(x, t);
    return dealii::Tensor<1, 3>({f.u[0].v, f.u[1].v, f.u[2].v});
  }

  double ManufacturedSolution::pressure(const dealii::Point<3> &x, const double t) const
  {
    return fields(x, t).p.v;
  }

  double ManufacturedSolution::porosity(const dealii::Point<3> &x, const double t) const
  {
    return fields(x, t).eps.v;
  }

  dealii::Tensor<1, 3> ManufacturedSolution::porosity_gradient(const dealii::Point<3> &x,
                                                                const double t) const
  {
    const Fields f = fields(x, t);
    return dealii::Tensor<1, 3>({f.eps.d[0], f.eps.d[1], f.eps.d[2]});
  }

  dealii::Tensor<1, 3> ManufacturedSolution::momentum_source(const dealii::Point<3> &x,
                                                              const double t) const
  {
    const Fields f   = fields(x, t);
    const double eps = f.eps.v;
    dealii::Tensor<1, 3> source;
    for (unsigned int i = 0; i < 3; ++i)
      {
        double convection = 0., laplacian = 0., grad_div = 0.;
        for (unsigned int j = 0; j < 3; ++j)
          {
            convection += f.u[i].d[j] * f.u[j].v;
            laplacian += f.u[i].second(j, j);
            grad_div += f.u[j].second(j, i);
          }
        const double inertia  = density * eps * (f.u[i].d[3] + convection);
        const double div_tau  = viscosity * (laplacian + grad_div / 3.);
        const double pressure = f.p.d[i];
        source[i] = formulation == VansFormulation::model_a ?
                      inertia + eps * pressure - eps * div_tau :
                      inertia + pressure - div_tau;
      }
    return source;
  }

  double ManufacturedSolution::mass_source(const dealii::Point<3> &x, const double t) const
  {
    const Fields f = fields(x, t);
    double       s = f.eps.d[3];
    for (unsigned int j = 0; j < 3; ++j)
      s += f.eps.v * f.u[j].d[j] + f.u[j].v * f.eps.d[j];
    return s;
  }
} // namespace sluice
