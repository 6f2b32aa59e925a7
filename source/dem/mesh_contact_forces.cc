// The mesh contact pass (see the header).

#include <sluice/dem/contact_law.h>
#include <sluice/dem/mesh_contact.h>
#include <sluice/dem/mesh_contact_forces.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sluice
{
  namespace
  {
    /// The history a new contact (mesh m, triangle t, point p) of a sphere at x
    /// of radius r inherits from the last pass's contacts 'before' (those not
    /// 'taken' yet), by the rule of the header; zero if none qualifies.
    Vec3 inherited_history(const MeshContactHistory *before, const unsigned int n_before,
                           std::vector<bool> &taken, const WallSet &walls, const unsigned int m,
                           const unsigned int t, const Vec3 &p, const Vec3 &x, const double r)
    {
      for (unsigned int k = 0; k < n_before; ++k)
        if (!taken[k] && before[k].triangle.mesh == m && before[k].triangle.triangle == t)
          {
            taken[k] = true;
            return before[k].history;
          }
      const TriangleMesh &mesh    = walls.meshes()[m].mesh();
      unsigned int        nearest = n_before;
      double              best_2  = r * r;
      for (unsigned int k = 0; k < n_before; ++k)
        if (!taken[k] && before[k].triangle.mesh == m)
          {
            const auto  &v = mesh.triangles[before[k].triangle.triangle];
            const double d_2 =
              norm_square(p - closest_point_on_triangle(x, mesh.vertices[v[0]],
                                                        mesh.vertices[v[1]], mesh.vertices[v[2]])
                                .point);
            if (d_2 < best_2)
              {
                best_2  = d_2;
                nearest = k;
              }
          }
      if (nearest == n_before)
        return Vec3();
      taken[nearest] = true;
      return before[nearest].history;
    }

    template <NormalContactModel normal, bool tangential, RollingResistanceModel rolling,
              bool observed>
    void mesh_contact_forces(ParticleStorage &P, NeighbourList &L, const ContactProperties &props,
                             const WallSet &walls, const double dt,
                             std::vector<Vec3> &wall_forces, MeshWallLoads &loads,
                             ContactObserver *const observer, ContactStatistics &stats)
    {
      const unsigned int n_meshes = walls.n_meshes(), n_planes = walls.n_planes();
      loads.torque.assign(n_meshes, Vec3());
      loads.power.assign(n_meshes, 0.);
      // This pass's contacts replace the last pass's.
      std::vector<unsigned int>       next_offset(P.n_local + 1, 0);
      std::vector<MeshContactHistory> next;
      next.reserve(L.mesh_contact.size() + 16);
      std::vector<unsigned int> triangles;
      std::vector<MeshContact>  contacts;
      std::vector<unsigned int> contact_mesh;
      std::vector<bool>         taken;
      const double              v_char = props.characteristic_velocity;

      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          const Vec3   xi = P.position[i], vi = P.velocity[i], wi = P.angular_velocity[i];
          const double ri = P.radius[i];
          contacts.clear();
          contact_mesh.clear();
          for (unsigned int k = L.mesh_offset[i]; k < L.mesh_offset[i + 1];)
            {
              const unsigned int m = L.mesh_candidate[k].mesh;
              triangles.clear();
              for (; k < L.mesh_offset[i + 1] && L.mesh_candidate[k].mesh == m; ++k)
                triangles.push_back(L.mesh_candidate[k].triangle);
              mesh_contacts(walls.meshes()[m].mesh(), xi, ri, triangles, contacts);
              contact_mesh.resize(contacts.size(), m);
            }

          const MeshContactHistory *before = L.mesh_contact.data() + L.mesh_contact_offset[i];
          const unsigned int n_before = L.mesh_contact_offset[i + 1] - L.mesh_contact_offset[i];
          taken.assign(n_before, false);
          for (std::size_t c = 0; c < contacts.size(); ++c)
            {
              const MeshContact &contact = contacts[c];
              const unsigned int m       = contact_mesh[c];
              const MeshWall    &wall    = walls.meshes()[m];
              const Vec3         n       = contact.normal;
              const double       overlap = contact.overlap;
              const double       arm     = ri - overlap; // centre to the surface
              const Vec3         at      = xi - arm * n; // the contact point
              const Vec3         v_wall  = wall.velocity_at(at);
              const Vec3         v_c     = vi - cross(arm * wi, n) - v_wall;
              const PairProperties &pair = props(P.type[i], wall.material());
              Vec3                  h;
              if constexpr (tangential)
                h = inherited_history(before, n_before, taken, walls, m, contact.triangle,
                                      contact.point, xi, ri);
              Vec3   F, F_t;
              double F_n;
              contact_response<normal, tangential>(pair, props, n, overlap, ri, P.mass[i], v_c,
                                                   tangential ? &h : nullptr, dt, F, F_t, F_n);
              if constexpr (tangential)
                next.push_back({{m, contact.triangle}, h});
              Vec3 M;
              if constexpr (rolling != RollingResistanceModel::none)
                M = rolling_torque<rolling>(pair.rolling_friction, ri, F_n,
                                            wi - wall.angular_velocity(), v_char);
              if constexpr (observed)
                {
                  const unsigned int t   = walls.triangle_offset(m) + contact.triangle;
                  const double       v_n = dot(v_c, n);
                  if (overlap + dt * v_n <= 0.)
                    {
                      const double energy = 0.5 * P.mass[i] * v_n * v_n;
                      observer->impact(P.id[i], i, P.type[i], n_planes + m, true, energy);
                      observer->triangle_impact(t, energy);
                    }
                  const ElasticParts e = elastic_parts<normal>(pair, props, overlap, ri, P.mass[i]);
                  observer->contact({i, ContactEnergyRecord::none, n_planes + m, t, n, arm, 0., F,
                                     F_n - e.normal_force, F_t, M, v_wall,
                                     wall.angular_velocity(), 1.});
                  observer->stored(true, 1., e.normal_energy,
                                   tangential ? 0.5 * e.tangential_stiffness * norm_square(h) : 0.);
                  if constexpr (tangential)
                    observer->triangle_load(t, P.type[i],
                                            std::max(F_n, 0.) * norm(v_c - v_n * n) * dt);
                }
              P.force[i] += F;
              wall_forces[n_planes + m] -= F;
              loads.torque[m] -= cross(at - wall.origin(), F);
              loads.power[m] += dot(F, v_wall);
              if constexpr (tangential)
                P.torque[i] -= arm * cross(n, F_t);
              if constexpr (rolling != RollingResistanceModel::none)
                P.torque[i] += M;
              ++P.coordination[i];
              stats.n_wall_contacts += 1.;
              if (overlap > stats.max_overlap_ratio * ri)
                stats.max_overlap_ratio = overlap / ri;
            }
          next_offset[i + 1] = next.size();
        }
      L.mesh_contact_offset.swap(next_offset);
      L.mesh_contact.swap(next);
    }

    template <NormalContactModel normal, bool tangential, RollingResistanceModel rolling>
    MeshContactKernel select_observed(const bool observed)
    {
      return observed ? &mesh_contact_forces<normal, tangential, rolling, true> :
                        &mesh_contact_forces<normal, tangential, rolling, false>;
    }

    template <NormalContactModel normal, bool tangential>
    MeshContactKernel select_rolling(const RollingResistanceModel rolling, const bool observed)
    {
      switch (rolling)
        {
          case RollingResistanceModel::constant_torque:
            return select_observed<normal, tangential, RollingResistanceModel::constant_torque>(
              observed);
          case RollingResistanceModel::viscous:
            return select_observed<normal, tangential, RollingResistanceModel::viscous>(observed);
          default:
            return select_observed<normal, tangential, RollingResistanceModel::none>(observed);
        }
    }

    template <NormalContactModel normal>
    MeshContactKernel select_tangential(const bool tangential,
                                        const RollingResistanceModel rolling, const bool observed)
    {
      return tangential ? select_rolling<normal, true>(rolling, observed) :
                          select_rolling<normal, false>(rolling, observed);
    }
  } // namespace

  MeshContactKernel select_mesh_contact_kernel(const NormalContactModel     normal,
                                               const bool                   tangential,
                                               const RollingResistanceModel rolling,
                                               const bool                   observed)
  {
    return normal == NormalContactModel::linear ?
             select_tangential<NormalContactModel::linear>(tangential, rolling, observed) :
             select_tangential<NormalContactModel::hertz_mindlin>(tangential, rolling, observed);
  }
} // namespace sluice
