#pragma once
// The per-particle fields of a coupled scene (particle_fields.h), declared
// once: what particle_fluid_forces() freezes for a fluid step, the impulse the
// particle owes the fluid, and, with the self-induced correction only, the
// distance its deposits have been carried with the undisturbed fluid and the
// part of its exchange that disturbs no fluid (self_induced_velocity.h). All
// of them migrate with the particle and are checkpointed; the fluid velocity
// and the drag coefficient are also written to the particle snapshots.

#include <sluice/dem/particle_fields.h>

namespace sluice
{
  struct CouplingFields
  {
    explicit CouplingFields(const bool self_induced_correction)
    {
      using Use       = ParticleFieldRegistry::Use;
      const Use shown = {true, true, true}, kept = {true, false, true};
      // k (k / eps in set III) [kg/s]; u at the particle [m/s]; every non-drag
      // fluid force [N]; the added mass m_a [kg]; the part of the non-drag
      // forces the fluid gets [N]; the impulse the fluid gave (exchanged part)
      // [N s]; u at the last sample [m/s].
      drag_coefficient  = registry.declare("drag_coefficient", 1, shown);
      fluid_velocity    = registry.declare("fluid_velocity", 3, shown);
      other_force       = registry.declare("other_fluid_force", 3, kept);
      added_mass        = registry.declare("added_mass", 1, kept);
      exchanged_force   = registry.declare("exchanged_force", 3, kept);
      fluid_impulse     = registry.declare("fluid_impulse", 3, kept);
      previous_velocity = registry.declare("previous_fluid_velocity", 3, kept);
      // The exchanged force the fluid fraction balances (set I: -V grad p +
      // V div tau; set III: -rho_f V g) [N]: it disturbs no fluid.
      if (self_induced_correction)
        self_balanced = registry.declare("self_induced_balanced_force", 3, kept);
      sampled_end = registry.doubles_per_particle();
      if (self_induced_correction)
        self_drift = registry.declare("self_induced_drift", 3, kept); // [m]
    }

    ParticleFieldRegistry registry;
    unsigned int drag_coefficient, fluid_velocity, other_force, added_mass, exchanged_force,
      fluid_impulse, previous_velocity;
    /// particle_fluid_forces() refills [0, sampled_end) at every sample.
    unsigned int sampled_end;
    unsigned int self_balanced = 0, self_drift = 0; // only with the self-induced correction
  };
} // namespace sluice
