// ParaView output of an SPH fluid's particles (see the header).

#include <sluice/dem/particle_fields.h>
#include <sluice/sph/sph_output.h>

namespace sluice
{
  namespace
  {
    ParticleFieldRegistry fields()
    {
      ParticleFieldRegistry            r;
      const ParticleFieldRegistry::Use shown{true, true, true};
      r.declare("density", 1, shown);
      r.declare("pressure", 1, shown);
      r.declare("smoothing_length", 1, shown);
      r.declare("porosity", 1, shown);
      return r;
    }

    /// The particles as the .vtu writer takes them.
    ParticleStorage as_storage(const SphParticles &P, const double dx)
    {
      ParticleStorage S;
      S.n_extra = 4;
      for (unsigned int a = 0; a < P.n_local; ++a)
        {
          S.id.push_back(P.id[a]);
          S.position.push_back(P.position[a]);
          S.velocity.push_back(P.velocity[a]);
          S.angular_velocity.emplace_back();
          S.force.push_back(P.mass[a] * P.acceleration[a]);
          S.torque.emplace_back();
          S.radius.push_back(0.5 * dx);
          S.mass.push_back(P.mass[a]);
          S.inverse_mass.push_back(1. / P.mass[a]);
          S.inverse_inertia.push_back(0.);
          S.type.push_back(P.wall[a]);
          S.coordination.push_back(0);
          S.extra.insert(S.extra.end(),
                         {P.density[a], P.pressure[a], P.smoothing[a], P.porosity[a]});
        }
      S.n_local = S.size();
      return S;
    }
  } // namespace

  SphOutput::SphOutput(const std::string &directory, const std::string &base)
    : vtu(directory, base, 0, 1, fields())
  {}

  void SphOutput::write(const SphParticles &P, const double dx, const double time)
  {
    vtu.write(as_storage(P, dx), time);
  }

  std::string SphOutput::write_files(const SphParticles &P, const double dx,
                                     const unsigned int index) const
  {
    return vtu.write_files(as_storage(P, dx), index);
  }
} // namespace sluice
