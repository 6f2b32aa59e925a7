#pragma once
// A three-component vector of doubles for the DEM hot loops.
//
// deal.II's Tensor<1,3> would do the same job, but keeping the DEM kernels free of
// deal.II headers keeps their translation units cheap to compile (see DESIGN.md §4).

#include <cmath>

namespace sluice
{
  struct Vec3
  {
    double x = 0., y = 0., z = 0.;

    constexpr Vec3() = default;
    constexpr Vec3(const double x_, const double y_, const double z_)
      : x(x_), y(y_), z(z_)
    {}

    double &operator[](const unsigned int d) { return d == 0 ? x : (d == 1 ? y : z); }
    double operator[](const unsigned int d) const { return d == 0 ? x : (d == 1 ? y : z); }

    Vec3 &operator+=(const Vec3 &b) { x += b.x; y += b.y; z += b.z; return *this; }
    Vec3 &operator-=(const Vec3 &b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
    Vec3 &operator*=(const double s) { x *= s; y *= s; z *= s; return *this; }
  };

  inline Vec3 operator+(const Vec3 &a, const Vec3 &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  inline Vec3 operator-(const Vec3 &a, const Vec3 &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  inline Vec3 operator-(const Vec3 &a) { return {-a.x, -a.y, -a.z}; }
  inline Vec3 operator*(const double s, const Vec3 &a) { return {s * a.x, s * a.y, s * a.z}; }
  inline Vec3 operator*(const Vec3 &a, const double s) { return {s * a.x, s * a.y, s * a.z}; }
  inline double dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
  inline Vec3 cross(const Vec3 &a, const Vec3 &b)
  {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  }
  inline double norm_square(const Vec3 &a) { return dot(a, a); }
  inline double norm(const Vec3 &a) { return std::sqrt(dot(a, a)); }
} // namespace sluice
