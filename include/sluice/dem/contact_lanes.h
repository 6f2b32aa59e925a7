#pragma once
// Two Hertz–Mindlin contacts side by side, one in each lane of a 128-bit
// register (SSE2, which every x86-64 processor has).
//
// Why: the force sweep over the touching pairs waits on its square roots and
// divisions (three to five per contact, doc/performance.md), and this
// machine's divide and square-root units take a pair of doubles about as fast
// as one. Each lane does the same IEEE operations in the same order as
// contact_response<hertz_mindlin> and rolling_torque (contact_law.h) do for
// one contact, so every force, torque and history comes out the same to the
// bit; unit.contact_lanes checks that against the one-at-a-time sweep. Where
// the scalar law branches (the Coulomb cap, no rolling torque) the lanes
// compute the other side when either lane needs it, and select.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/vector3.h>
#include <sluice/dem/contact_properties.h>

#include <cmath>

#if defined(__SSE2__)
#  include <emmintrin.h>
#endif

namespace sluice
{
  namespace lanes
  {
    /// Two doubles, and a mask of two lanes (all bits set where true).
    typedef double Real __attribute__((vector_size(16)));
    typedef long   Mask __attribute__((vector_size(16)));

    inline Real broadcast(const double a) { return Real{a, a}; }

    inline Real sqrt(const Real a)
    {
#if defined(__SSE2__)
      return (Real)_mm_sqrt_pd((__m128d)a);
#else
      return Real{std::sqrt(a[0]), std::sqrt(a[1])};
#endif
    }

    /// a where the mask is set, else b.
    inline Real select(const Mask m, const Real a, const Real b) { return m ? a : b; }

    /// std::max(a, 0.) lane by lane, NaN passed through as std::max does.
    inline Real max_zero(const Real a) { return select(a < Real{0., 0.}, Real{0., 0.}, a); }

    /// A vector in each lane; the operations of Vec3 (vector3.h), term by term
    /// in the same order.
    struct Vec
    {
      Real x, y, z;

      Vec3 lane(const unsigned int l) const { return {x[l], y[l], z[l]}; }
    };

    inline Vec pack(const Vec3 &a, const Vec3 &b)
    {
      return {Real{a.x, b.x}, Real{a.y, b.y}, Real{a.z, b.z}};
    }
    inline Vec  operator+(const Vec &a, const Vec &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
    inline Vec  operator-(const Vec &a, const Vec &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
    inline Vec  operator*(const Real s, const Vec &a) { return {s * a.x, s * a.y, s * a.z}; }
    inline Real dot(const Vec &a, const Vec &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
    inline Vec  cross(const Vec &a, const Vec &b)
    {
      return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    }
    inline Vec select(const Mask m, const Vec &a, const Vec &b)
    {
      return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
    }
  } // namespace lanes

  /// What one touching pair brings to the sweep: the centres' difference
  /// x_i - x_j (nearest image), the two spheres, the pair's material and its
  /// tangential history (null without one).
  struct ContactInput
  {
    Vec3                  d;
    double                r_i, r_j, m_i, m_j;
    Vec3                  v_i, v_j, w_i, w_j;
    const PairProperties *pair;
    Vec3                 *history;
  };

  /// What the sweep adds up afterwards, in the list's order: the force on i
  /// (on j its opposite), the torques' decrements on i and j, the overlap and
  /// the rolling resistance's torque on i (on j its opposite).
  struct ContactOutput
  {
    Vec3   force, torque_i, torque_j;
    double overlap;
    Vec3   rolling_torque;
  };

  /// The Hertz–Mindlin contacts a and b (contact_forces.cc's expressions for
  /// the geometry, contact_response<hertz_mindlin> for the law and
  /// rolling_torque<rolling> for the rolling resistance), the histories
  /// updated in place. b may be a's copy with a null history, to fill the
  /// second lane.
  template <bool tangential, RollingResistanceModel rolling>
  __attribute__((always_inline)) inline void
  hertz_mindlin_in_lanes(const ContactInput &a, const ContactInput &b, const double dt,
                         const double v_char, ContactOutput &out_a, ContactOutput &out_b)
  {
    using namespace lanes;
    const Vec  d       = pack(a.d, b.d);
    const Real r_i     = Real{a.r_i, b.r_i}, r_j = Real{a.r_j, b.r_j};
    const Real m_i     = Real{a.m_i, b.m_i}, m_j = Real{a.m_j, b.m_j};
    const Real r_sum   = r_i + r_j;
    const Real dist    = lanes::sqrt(dot(d, d));
    const Vec  n       = (broadcast(1.) / dist) * d;
    const Real overlap = r_sum - dist;
    const Real m_eff   = m_i * m_j / (m_i + m_j);
    const Real R_eff   = r_i * r_j / r_sum;
    const Real arm_i = r_i - broadcast(0.5) * overlap, arm_j = r_j - broadcast(0.5) * overlap;
    const Vec  v_c = pack(a.v_i, b.v_i) - pack(a.v_j, b.v_j) -
                    cross(arm_i * pack(a.w_i, b.w_i) + arm_j * pack(a.w_j, b.w_j), n);

    // contact_response<hertz_mindlin>, term by term.
    const Real E_star  = Real{a.pair->E_star, b.pair->E_star};
    const Real damping = Real{a.pair->damping_ratio, b.pair->damping_ratio};
    const Real v_n     = dot(v_c, n);
    const Real c_a     = lanes::sqrt(R_eff * overlap);
    const Real S_n     = broadcast(2.) * E_star * c_a;
    const Real c_n =
      broadcast(2.) * broadcast(sqrt_five_sixths) * damping * lanes::sqrt(S_n * m_eff);
    const Real normal_force = broadcast(2. / 3.) * S_n * overlap - c_n * v_n;
    Vec        force        = normal_force * n;
    Vec        F_t{};
    if constexpr (tangential)
      {
        const Real G_star = Real{a.pair->G_star, b.pair->G_star};
        const Real ratio  = Real{a.pair->sqrt_tangential_to_normal_stiffness,
                                b.pair->sqrt_tangential_to_normal_stiffness};
        const Real mu     = Real{a.pair->friction, b.pair->friction};
        const Real k_t    = broadcast(8.) * G_star * c_a;
        const Real c_t    = c_n * ratio;
        const Vec  v_t    = v_c - v_n * n;
        Vec        h      = pack(*a.history, b.history ? *b.history : *a.history);
        h                 = h - dot(h, n) * n;
        h                 = h + broadcast(dt) * v_t;
        F_t               = (-k_t) * h - c_t * v_t;
        const Real limit  = mu * max_zero(normal_force);
        const Real F_t_2  = dot(F_t, F_t);
        const Mask slides = F_t_2 > limit * limit;
        // Most contacts of a packed bed stick: the cap's square root and
        // divisions only when one of the two slides.
        if (slides[0] | slides[1])
          {
            const Vec capped = (limit / lanes::sqrt(F_t_2)) * F_t;
            F_t              = select(slides, capped, F_t);
            h                = select(slides, (broadcast(-1.) / k_t) * F_t, h);
          }
        *a.history        = h.lane(0);
        if (b.history)
          *b.history = h.lane(1);
        force = force + F_t;
      }
    const Vec n_cross_F = cross(n, F_t);
    const Vec torque_i  = arm_i * n_cross_F, torque_j = arm_j * n_cross_F;
    Vec       M{};
    if constexpr (rolling != RollingResistanceModel::none)
      {
        // rolling_torque<rolling>: none where the spins agree or mu_r is 0.
        const Vec  w_rel = pack(a.w_i, b.w_i) - pack(a.w_j, b.w_j);
        const Real w     = lanes::sqrt(dot(w_rel, w_rel));
        const Real mu_r  = Real{a.pair->rolling_friction, b.pair->rolling_friction};
        Real       magnitude = mu_r * R_eff * max_zero(normal_force);
        if constexpr (rolling == RollingResistanceModel::viscous)
          magnitude = magnitude * (R_eff * w / broadcast(v_char));
        const Mask rolls = (w > Real{0., 0.}) & (mu_r != Real{0., 0.});
        M                = select(rolls, (-magnitude / w) * w_rel, Vec{});
      }
    out_a = {force.lane(0), torque_i.lane(0), torque_j.lane(0), overlap[0], M.lane(0)};
    out_b = {force.lane(1), torque_i.lane(1), torque_j.lane(1), overlap[1], M.lane(1)};
  }
} // namespace sluice
