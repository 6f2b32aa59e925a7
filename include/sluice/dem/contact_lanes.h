#pragma once
// Hertz–Mindlin contacts side by side, one in each lane of a vector
// register: two in 128 bits (SSE2, which every x86-64 processor has), four
// in 256 bits (AVX2, chosen at run time where the processor has it).
//
// Why: the force sweep over the touching pairs waits on its square roots and
// divisions (three to five per contact, doc/performance.md), and this
// machine's divide and square-root units take a vector of doubles about as
// fast as one. Each lane does the same IEEE operations in the same order as
// contact_response<hertz_mindlin> and rolling_torque (contact_law.h) do for
// one contact (no fused multiply-add: AVX2 without FMA), so every force,
// torque and history comes out the same to the bit; unit.contact_lanes
// checks that against the one-at-a-time sweep for both widths. Where the
// scalar law branches (the Coulomb cap, no rolling torque) the lanes compute
// the other side when any lane needs it, and select.

#include <sluice/core/scene_parameters.h>
#include <sluice/core/vector3.h>
#include <sluice/dem/contact_properties.h>

#include <cmath>
#include <utility>

#if defined(__SSE2__)
#  include <emmintrin.h>
#endif

// Every lane operation is inlined, also into the kernel compiled for AVX2
// (contact_forces.cc), so that it takes that kernel's instructions.
#define SLUICE_LANE inline __attribute__((always_inline))

namespace sluice
{
  namespace lanes
  {
    /// W doubles, and a mask of W lanes (all bits set where true).
    template <unsigned int W>
    struct Types;
    template <>
    struct Types<2>
    {
      typedef double Real __attribute__((vector_size(16)));
      typedef long   Mask __attribute__((vector_size(16)));
    };
    template <>
    struct Types<4>
    {
      typedef double Real __attribute__((vector_size(32)));
      typedef long   Mask __attribute__((vector_size(32)));
    };
    template <unsigned int W>
    using Real = typename Types<W>::Real;
    template <unsigned int W>
    using Mask = typename Types<W>::Mask;

    template <unsigned int W>
    SLUICE_LANE Real<W> broadcast(const double a)
    {
      Real<W> r;
      for (unsigned int l = 0; l < W; ++l)
        r[l] = a;
      return r;
    }

    SLUICE_LANE Real<2> sqrt(const Real<2> a)
    {
#if defined(__SSE2__)
      return (Real<2>)_mm_sqrt_pd((__m128d)a);
#else
      return Real<2>{std::sqrt(a[0]), std::sqrt(a[1])};
#endif
    }

    /// Lane by lane: inside the kernel compiled for AVX2 the compiler makes
    /// one vsqrtpd of it (an AVX intrinsic could not be inlined into the
    /// generic code that calls it).
    SLUICE_LANE Real<4> sqrt(const Real<4> a)
    {
      Real<4> r;
      for (unsigned int l = 0; l < 4; ++l)
        r[l] = std::sqrt(a[l]);
      return r;
    }

    /// a where the mask is set, else b.
    template <class R, class M>
    SLUICE_LANE R select(const M m, const R a, const R b)
    {
      return m ? a : b;
    }

    /// Whether any lane's mask is set.
    template <class M>
    SLUICE_LANE bool any(const M m)
    {
      long bits = 0;
      for (unsigned int l = 0; l < sizeof(M) / sizeof(long); ++l)
        bits |= m[l];
      return bits != 0;
    }

    /// std::max(a, 0.) lane by lane, NaN passed through as std::max does.
    template <class R>
    SLUICE_LANE R max_zero(const R a)
    {
      return select(a < R{}, R{}, a);
    }

    /// A vector in each lane; the operations of Vec3 (vector3.h), term by term
    /// in the same order.
    template <unsigned int W>
    struct Vec
    {
      Real<W> x, y, z;

      SLUICE_LANE Vec3 lane(const unsigned int l) const { return {x[l], y[l], z[l]}; }
    };

    template <unsigned int W>
    SLUICE_LANE Vec<W> operator+(const Vec<W> &a, const Vec<W> &b)
    {
      return {a.x + b.x, a.y + b.y, a.z + b.z};
    }
    template <unsigned int W>
    SLUICE_LANE Vec<W> operator-(const Vec<W> &a, const Vec<W> &b)
    {
      return {a.x - b.x, a.y - b.y, a.z - b.z};
    }
    template <unsigned int W>
    SLUICE_LANE Vec<W> operator*(const Real<W> s, const Vec<W> &a)
    {
      return {s * a.x, s * a.y, s * a.z};
    }
    template <unsigned int W>
    SLUICE_LANE Real<W> dot(const Vec<W> &a, const Vec<W> &b)
    {
      return a.x * b.x + a.y * b.y + a.z * b.z;
    }
    template <unsigned int W>
    SLUICE_LANE Vec<W> cross(const Vec<W> &a, const Vec<W> &b)
    {
      return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    }
    template <unsigned int W, class M>
    SLUICE_LANE Vec<W> select(const M m, const Vec<W> &a, const Vec<W> &b)
    {
      return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
    }
  } // namespace lanes

  /// What one touching pair brings to the sweep: the centres' difference
  /// x_i - x_j (nearest image), the two spheres, the pair's material and its
  /// tangential history (null without friction).
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

  namespace lanes
  {
    // Lane l takes in[l]'s member: a number, a vector, a material property of
    // the pair, the tangential history. (Index sequences rather than loops,
    // so that the inputs need not pass through memory.)
    template <auto member, unsigned int W, std::size_t... l>
    SLUICE_LANE Real<W> of(const ContactInput (&in)[W], std::index_sequence<l...>)
    {
      return Real<W>{(in[l].*member)...};
    }
    template <auto member, unsigned int W, std::size_t... l>
    SLUICE_LANE Vec<W> vec_of(const ContactInput (&in)[W], std::index_sequence<l...>)
    {
      return {Real<W>{(in[l].*member).x...}, Real<W>{(in[l].*member).y...},
              Real<W>{(in[l].*member).z...}};
    }
    template <auto member, unsigned int W, std::size_t... l>
    SLUICE_LANE Real<W> pair_of(const ContactInput (&in)[W], std::index_sequence<l...>)
    {
      return Real<W>{(in[l].pair->*member)...};
    }
    template <unsigned int W, std::size_t... l>
    SLUICE_LANE Vec<W> history_of(const ContactInput (&in)[W], std::index_sequence<l...>)
    {
      return {Real<W>{in[l].history->x...}, Real<W>{in[l].history->y...},
              Real<W>{in[l].history->z...}};
    }

    /// Lane l of h into in[l]'s history.
    template <unsigned int W, std::size_t... l>
    SLUICE_LANE void store_histories(const Vec<W> &h, const ContactInput (&in)[W],
                                     std::index_sequence<l...>)
    {
      ((*in[l].history = h.lane(l)), ...);
    }
  } // namespace lanes

  /// The Hertz–Mindlin contacts in[0..W) (contact_forces.cc's expressions
  /// for the geometry, contact_response<hertz_mindlin> for the law and
  /// rolling_torque<rolling> for the rolling resistance) into *out[l], the
  /// histories updated in place. With friction each lane's history is its
  /// own: a lane that only fills the vector holds a copy of another lane's
  /// input with a scratch history and output.
  template <unsigned int W, bool tangential, RollingResistanceModel rolling>
  SLUICE_LANE void hertz_mindlin_in_lanes(const ContactInput (&in)[W], const double dt,
                                          const double v_char, ContactOutput *const (&out)[W])
  {
    using namespace lanes;
    using R             = Real<W>;
    constexpr auto lane = std::make_index_sequence<W>();
    const Vec<W>   d    = vec_of<&ContactInput::d>(in, lane);
    const R        r_i = of<&ContactInput::r_i>(in, lane), r_j = of<&ContactInput::r_j>(in, lane);
    const R        m_i = of<&ContactInput::m_i>(in, lane), m_j = of<&ContactInput::m_j>(in, lane);
    const R        r_sum   = r_i + r_j;
    const R        dist    = lanes::sqrt(dot(d, d));
    const Vec<W>   n       = (broadcast<W>(1.) / dist) * d;
    const R        overlap = r_sum - dist;
    const R        m_eff   = m_i * m_j / (m_i + m_j);
    const R        R_eff   = r_i * r_j / r_sum;
    const R        arm_i   = r_i - broadcast<W>(0.5) * overlap;
    const R        arm_j   = r_j - broadcast<W>(0.5) * overlap;
    const Vec<W>   w_i     = vec_of<&ContactInput::w_i>(in, lane);
    const Vec<W>   w_j     = vec_of<&ContactInput::w_j>(in, lane);
    const Vec<W>   v_i     = vec_of<&ContactInput::v_i>(in, lane);
    const Vec<W>   v_j     = vec_of<&ContactInput::v_j>(in, lane);
    const Vec<W>   v_c     = v_i - v_j - cross(arm_i * w_i + arm_j * w_j, n);

    // contact_response<hertz_mindlin>, term by term.
    const R E_star  = pair_of<&PairProperties::E_star>(in, lane);
    const R damping = pair_of<&PairProperties::damping_ratio>(in, lane);
    const R v_n     = dot(v_c, n);
    const R c_a     = lanes::sqrt(R_eff * overlap);
    const R S_n     = broadcast<W>(2.) * E_star * c_a;
    const R c_n =
      broadcast<W>(2.) * broadcast<W>(sqrt_five_sixths) * damping * lanes::sqrt(S_n * m_eff);
    const R normal_force = broadcast<W>(2. / 3.) * S_n * overlap - c_n * v_n;
    Vec<W>  force        = normal_force * n;
    Vec<W>  F_t{};
    if constexpr (tangential)
      {
        const R G_star = pair_of<&PairProperties::G_star>(in, lane);
        const R ratio  = pair_of<&PairProperties::sqrt_tangential_to_normal_stiffness>(in, lane);
        const R mu     = pair_of<&PairProperties::friction>(in, lane);
        const R k_t    = broadcast<W>(8.) * G_star * c_a;
        const R c_t    = c_n * ratio;
        const Vec<W> v_t = v_c - v_n * n;
        Vec<W>       h   = history_of(in, lane);
        h                = h - dot(h, n) * n;
        h                = h + broadcast<W>(dt) * v_t;
        F_t              = (-k_t) * h - c_t * v_t;
        const R    limit  = mu * max_zero(normal_force);
        const R    F_t_2  = dot(F_t, F_t);
        const auto slides = F_t_2 > limit * limit;
        // Most contacts of a packed bed stick: the cap's square root and
        // divisions only when a lane slides.
        if (any(slides))
          {
            const Vec<W> capped = (limit / lanes::sqrt(F_t_2)) * F_t;
            F_t                 = select(slides, capped, F_t);
            h                   = select(slides, (broadcast<W>(-1.) / k_t) * F_t, h);
          }
        store_histories(h, in, lane);
        force = force + F_t;
      }
    const Vec<W> n_cross_F = cross(n, F_t);
    const Vec<W> torque_i = arm_i * n_cross_F, torque_j = arm_j * n_cross_F;
    Vec<W>       M{};
    if constexpr (rolling != RollingResistanceModel::none)
      {
        // rolling_torque<rolling>: none where the spins agree or mu_r is 0.
        const Vec<W> w_rel = w_i - w_j;
        const R      w     = lanes::sqrt(dot(w_rel, w_rel));
        const R      mu_r  = pair_of<&PairProperties::rolling_friction>(in, lane);
        R            magnitude = mu_r * R_eff * max_zero(normal_force);
        if constexpr (rolling == RollingResistanceModel::viscous)
          magnitude = magnitude * (R_eff * w / broadcast<W>(v_char));
        const auto rolls = (w > R{}) & (mu_r != R{});
        M                = select(rolls, (-magnitude / w) * w_rel, Vec<W>{});
      }
    for (unsigned int l = 0; l < W; ++l)
      *out[l] = {force.lane(l), torque_i.lane(l), torque_j.lane(l), overlap[l], M.lane(l)};
  }
} // namespace sluice
