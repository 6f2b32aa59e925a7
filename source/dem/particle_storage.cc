#include <sluice/core/sphere.h>
#include <sluice/dem/particle_storage.h>

#include <cmath>

namespace sluice
{
  void ParticleStorage::clear()
  {
    id.clear();
    position.clear();
    velocity.clear();
    angular_velocity.clear();
    force.clear();
    torque.clear();
    radius.clear();
    mass.clear();
    inverse_mass.clear();
    inverse_inertia.clear();
    type.clear();
    coordination.clear();
    extra.clear();
    n_local = 0;
  }

  void ParticleStorage::push_back(const std::uint64_t id_, const Vec3 &x, const Vec3 &v,
                                  const Vec3 &w, const double r, const unsigned int t,
                                  const double density)
  {
    const double m = sphere_mass(density, r);
    id.push_back(id_);
    position.push_back(x);
    velocity.push_back(v);
    angular_velocity.push_back(w);
    force.emplace_back();
    torque.emplace_back();
    radius.push_back(r);
    mass.push_back(m);
    inverse_mass.push_back(1. / m);
    inverse_inertia.push_back(1. / (0.4 * m * r * r)); // solid sphere, I = 2/5 m r^2
    type.push_back(t);
    coordination.push_back(0);
  }
} // namespace sluice
