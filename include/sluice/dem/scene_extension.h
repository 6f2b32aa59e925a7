#pragma once
// What a higher layer adds to a DEM scene's loop without the DEM knowing it
// (the layering is core <- dem <- coupling): an imported flow field's forces
// (coupling/imported_field_scene.h) take over the step, declare the
// per-particle fields they need, keep their records in the checkpoint and
// add their lines to the header and the summary. Called once per step, never
// per contact or particle, so the virtual calls cost nothing measurable.

#include <sluice/dem/particle_fields.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace sluice
{
  class DemSystem;

  class DemSceneExtension
  {
  public:
    virtual ~DemSceneExtension() = default;

    /// The per-particle fields, declared before the scene's own.
    virtual const ParticleFieldRegistry &fields() const = 0;
    /// Once the DEM is set up (and restored by a restart): its own checks.
    virtual void attach(DemSystem &dem) = 0;
    /// The header's lines (rank 0 writes them).
    virtual void describe(std::ostream &out) const = 0;
    /// One step of the DEM (dem.advance with the extension's kick).
    virtual void advance(DemSystem &dem) = 0;
    /// Its records for a checkpoint (collective: every rank calls it, rank
    /// 0 writes them), and back on every rank (empty at the start).
    virtual std::vector<double> state() const                         = 0;
    virtual void                set_state(const std::vector<double> &) = 0;
    /// Collective: the summary's lines, for rank 0 to write.
    virtual std::string summary(DemSystem &dem) const = 0;
    /// After the summary: 0, or 3 when its validation error is above the tolerance.
    virtual int exit_code() const = 0;
  };
} // namespace sluice
