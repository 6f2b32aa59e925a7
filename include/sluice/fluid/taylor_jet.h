#pragma once
// A number that carries its first derivatives in (x, y, z, t) and its second
// derivatives in (x, y, z): forward-mode differentiation to second order. It lets
// the manufactured solution be written once as a formula, with the forcing terms
// (which need grad u, laplacian u, grad div u, grad p, d eps/dt ...) computed
// exactly instead of by hand.

#include <array>
#include <cmath>

namespace sluice
{
  struct TaylorJet
  {
    double                v = 0.;
    std::array<double, 4> d{};  // d/dx, d/dy, d/dz, d/dt
    std::array<double, 9> dd{}; // d2/dx_i dx_j, i, j spatial, row-major

    TaylorJet() = default;
    TaylorJet(const double value) : v(value) {}

    /// The independent variable number k (0..3 = x, y, z, t) at the given value.
    static TaylorJet variable(const unsigned int k, const double value)
    {
      TaylorJet j(value);
      j.d[k] = 1.;
      return j;
    }

    double second(const unsigned int i, const unsigned int j) const { return dd[3 * i + j]; }
  };

  /// phi(f) with phi' = d1 and phi'' = d2 evaluated at f.v (the chain rule).
  inline TaylorJet chain(const TaylorJet &f, const double value, const double d1, const double d2)
  {
    TaylorJet r(value);
    for (unsigned int k = 0; k < 4; ++k)
      r.d[k] = d1 * f.d[k];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        r.dd[3 * i + j] = d2 * f.d[i] * f.d[j] + d1 * f.dd[3 * i + j];
    return r;
  }

  inline TaylorJet operator+(const TaylorJet &a, const TaylorJet &b)
  {
    TaylorJet r(a.v + b.v);
    for (unsigned int k = 0; k < 4; ++k)
      r.d[k] = a.d[k] + b.d[k];
    for (unsigned int k = 0; k < 9; ++k)
      r.dd[k] = a.dd[k] + b.dd[k];
    return r;
  }

  inline TaylorJet operator-(const TaylorJet &a)
  {
    return chain(a, -a.v, -1., 0.);
  }

  inline TaylorJet operator-(const TaylorJet &a, const TaylorJet &b)
  {
    return a + (-b);
  }

  inline TaylorJet operator*(const TaylorJet &a, const TaylorJet &b)
  {
    TaylorJet r(a.v * b.v);
    for (unsigned int k = 0; k < 4; ++k)
      r.d[k] = a.d[k] * b.v + a.v * b.d[k];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        r.dd[3 * i + j] = a.dd[3 * i + j] * b.v + a.d[i] * b.d[j] + a.d[j] * b.d[i] +
                          a.v * b.dd[3 * i + j];
    return r;
  }

  inline TaylorJet operator/(const TaylorJet &a, const TaylorJet &b)
  {
    const double inv = 1. / b.v;
    return a * chain(b, inv, -inv * inv, 2. * inv * inv * inv);
  }

  inline TaylorJet sin(const TaylorJet &f)
  {
    return chain(f, std::sin(f.v), std::cos(f.v), -std::sin(f.v));
  }

  inline TaylorJet cos(const TaylorJet &f)
  {
    return chain(f, std::cos(f.v), -std::sin(f.v), -std::cos(f.v));
  }

  inline TaylorJet exp(const TaylorJet &f)
  {
    const double e = std::exp(f.v);
    return chain(f, e, e, e);
  }
} // namespace sluice
