// The DEM's walls as obstacles to the SPH fluid (see the header).

#include <sluice/sph/sph_solid_walls.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sluice
{
  SphSolidWalls::SphSolidWalls(const WallSet &walls, const SolidWallLaw &law, const Vec3 &lower,
                               const Vec3 &upper)
    : walls_(&walls), law_(law)
  {
    // Cells of about two particle diameters (at most 128 a direction): a
    // particle looks at its own cell's triangles only.
    Vec3                        cell;
    std::array<unsigned int, 3> n;
    for (unsigned int d = 0; d < 3; ++d)
      {
        const double length = std::max(upper[d] - lower[d], law.radius);
        n[d]    = std::clamp(static_cast<unsigned int>(length / (4. * law.radius)), 1u, 128u);
        cell[d] = length / n[d];
      }
    for (const MeshWall &mesh : walls.meshes())
      {
        bins_.emplace_back(lower, cell, n);
        bins_.back().build(mesh.mesh(), law.radius);
      }
  }

  void SphSolidWalls::rebind(const WallSet &walls)
  {
    AssertThrow(walls_ != nullptr && walls.n_planes() == walls_->n_planes() &&
                  walls.n_meshes() == walls_->n_meshes(),
                dealii::ExcMessage("SphSolidWalls::rebind: not the same walls"));
    walls_ = &walls;
  }

  Vec3 SphSolidWalls::contact_force(const SphParticles &P, const unsigned int a,
                                    const unsigned int wall, const Vec3 &normal,
                                    const double overlap, const Vec3 &wall_velocity,
                                    const Vec3 &lever)
  {
    const double k       = law_.stiffness;
    const double damping = 2. * law_.damping_ratio * std::sqrt(k * P.mass[a]);
    const double v_n     = dot(P.velocity[a] - wall_velocity, normal);
    // The dashpot may not pull: a particle leaving fast loses its contact.
    const Vec3 F = std::max(0., k * overlap - damping * v_n) * normal;
    force_[wall] -= F;
    torque_[wall] -= cross(lever, F);
    power_[wall] += dot(F, wall_velocity);
    max_overlap_ = std::max(max_overlap_, overlap);
    return F;
  }

  void SphSolidWalls::add_accelerations(SphParticles &P)
  {
    if (empty())
      return;
    const WallSet &W = *walls_;
    force_.assign(W.n_walls(), Vec3());
    torque_.assign(W.n_walls(), Vec3());
    power_.assign(W.n_walls(), 0.);
    max_overlap_ = 0.;
    for (unsigned int m = 0; m < W.n_meshes(); ++m)
      if (W.meshes()[m].moving())
        bins_[m].build(W.meshes()[m].mesh(), law_.radius);
    const double R = law_.radius;
    for (unsigned int a = 0; a < P.n_local; ++a)
      {
        if (P.wall[a])
          continue;
        const Vec3 x = P.position[a];
        Vec3       F;
        for (unsigned int w = 0; w < W.n_planes(); ++w)
          {
            const Plane &plane    = W[w];
            const double distance = dot(x - plane.point, plane.normal);
            const Vec3   point    = x - distance * plane.normal;
            if (distance < R)
              F += contact_force(P, a, w, plane.normal, R - distance, plane.velocity_at(point),
                                 point);
          }
        for (unsigned int m = 0; m < W.n_meshes(); ++m)
          {
            candidates_.assign(bins_[m].begin(x), bins_[m].end(x));
            if (candidates_.empty())
              continue;
            contacts_.clear();
            const MeshWall &mesh = W.meshes()[m];
            mesh_contacts(mesh.mesh(), x, R, candidates_, contacts_);
            for (const MeshContact &c : contacts_)
              F += contact_force(P, a, W.n_planes() + m, c.normal, c.overlap,
                                 mesh.velocity_at(c.point), c.point - mesh.origin());
          }
        P.acceleration[a] += (1. / P.mass[a]) * F;
      }
  }

  double SphSolidWalls::stable_time_step(const SphParticles &P) const
  {
    if (empty() || !(law_.stiffness > 0.))
      return std::numeric_limits<double>::max();
    double m_min = std::numeric_limits<double>::max();
    for (unsigned int a = 0; a < P.n_local; ++a)
      if (!P.wall[a])
        m_min = std::min(m_min, P.mass[a]);
    return 0.2 * std::sqrt(m_min / law_.stiffness);
  }
} // namespace sluice
