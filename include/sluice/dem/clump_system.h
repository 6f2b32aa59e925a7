#pragma once
// A clump scene's rigid bodies in the DEM step (issue 14; doc/clumps.md).
//
// The bodies are the particles of the ParticleExchange: each body's centroid,
// velocity, angular velocity in space and radius (its bounding radius) are
// the exchange's own state, and its orientation, body-frame angular momentum,
// template and scale are per-particle fields (clump_fields), so whole bodies
// migrate, are ghosted and are checkpointed like spheres. Between list
// rebuilds they live in 'bodies' (owned first, then ghosts).
//
// The contact passes run unchanged on the members, expanded from the bodies
// into the DEM's particle arrays: member k of body b has the id
// b * member_stride + k, its centre at x + R r_k, velocity v + w x R r_k and
// the body's angular velocity, and the body's mass (the dashpots see the
// body's mass, as LIGGGHTS' multisphere does). Their forces and torques are
// summed onto the bodies, F = sum F_k, T = sum (R r_k) x F_k + T_k, and the
// bodies move by velocity Verlet for the centroid and the symplectic
// splitting of rigid_rotation.h for the orientation.

#include <sluice/core/clump_parameters.h>
#include <sluice/dem/clump_template.h>
#include <sluice/dem/particle_fields.h>
#include <sluice/dem/particle_storage.h>
#include <sluice/dem/rigid_rotation.h>

#include <vector>

namespace sluice
{
  /// The templates of a scene's 'clumps' subsection, at scale 1.
  std::vector<ClumpTemplate> make_clump_templates(const ClumpParameters &parameters);

  class ClumpSystem
  {
  public:
    /// Declares the bodies' fields (clump_fields) in the registry the
    /// exchange is built with.
    static void declare_fields(ParticleFieldRegistry &fields);
    /// fields: a registry with the bodies' fields declared.
    ClumpSystem(const ClumpParameters &parameters, const ParticleFieldRegistry &fields);

    /// After the exchange filled 'bodies': each body's mass and principal
    /// moments from its template, scale and density, and (from_momentum) an
    /// owned body's angular velocity in space from its momentum.
    void set_mass_properties(const std::vector<double> &densities, bool from_momentum = true);
    /// For bodies just inserted: the body-frame momentum from the angular
    /// velocity in space the record gave (L = I R^T w), for those with ids in
    /// [first_id, end_id).
    void set_momenta_from_angular_velocity(std::uint64_t first_id, std::uint64_t end_id);

    /// Rebuilds the member arrays from the bodies (owned bodies' members are
    /// the owned members); the order follows the bodies'.
    void expand(ParticleStorage &members);
    /// Moves the members with their bodies (positions and velocities; the
    /// arrays keep their layout), from 'first' body on; notes the fastest
    /// owned member's squared speed for the DEM's health check.
    void move_members(ParticleStorage &members, unsigned int first = 0) const;
    /// The owned members' velocities from their bodies' (positions as they
    /// are): after a kick, which leaves the levers R r_k unchanged.
    void update_member_velocities(ParticleStorage &members) const;
    /// The owned bodies' forces and torques from their members'.
    void gather(const ParticleStorage &members);

    /// L += h R^T T and w = R L / I (owned bodies): the rotation's half kick;
    /// the centroids' is the scene's kick (velocity_verlet.h, fluid_kick.h).
    void kick_rotation(double h);
    /// x += dt v and the free rotation over dt (owned bodies); notes the
    /// fastest body's squared speed.
    void drift(double dt);

    /// The member id of member k of body id b, and the body id of a member.
    std::uint64_t member_id(std::uint64_t body, unsigned int k) const
    {
      return body * member_stride + k;
    }
    std::uint64_t body_of(std::uint64_t member) const { return member / member_stride; }

    const ClumpTemplate &template_of(unsigned int body) const
    {
      return templates[template_index(body)];
    }
    unsigned int template_index(unsigned int body) const
    {
      return static_cast<unsigned int>(bodies.extra_of(body)[template_at]);
    }
    double               scale_of(unsigned int body) const { return bodies.extra_of(body)[scale_at]; }
    RigidRotation        rotation_of(unsigned int body) const;
    const PrincipalInertia &inertia_of(unsigned int body) const { return inertia[body]; }
    /// Body index of each member, in the members' arrays' order (expand()).
    const std::vector<unsigned int> &member_body() const { return body_index; }

    /// Rotational kinetic energy of the owned bodies [J].
    double rotational_energy() const;

    std::vector<ClumpTemplate> templates; // at scale 1
    unsigned int               member_stride = 1;
    ParticleStorage            bodies;

  private:
    unsigned int momentum_at = 0, orientation_at = 0, template_at = 0, scale_at = 0;
    std::vector<PrincipalInertia> inertia; // per body (owned and ghost) [kg m^2]
    // Per member (expand()): its body's index and its offset in the body frame.
    std::vector<unsigned int> body_index;
    std::vector<Vec3>         body_frame_offset;
    mutable std::vector<Vec3> lever; // R r_k, for gather()
  };
} // namespace sluice
