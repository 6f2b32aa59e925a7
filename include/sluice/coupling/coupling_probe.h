#pragma once
// The validation cases of coupled scenes as probes: each watches the run
// through the DEM's particles and the fluid interface (fluid_backend.h), so
// any fluid backend can run it, and ends in one result with its reference
// (the 'result:' line). One file per case: probe_<case>.cc.

#include <sluice/core/scene_parameters.h>
#include <sluice/coupling/fluid_backend.h>
#include <sluice/coupling/fluid_shapes.h>
#include <sluice/dem/dem_system.h>

#include <mpi.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace sluice
{
  /// What a probe may look at (and, before the start, set up).
  struct ProbeView
  {
    const SceneParameters &p;
    const FluidParameters &fluid; // as the coupling formulation set it
    DemSystem             &dem;
    const FluidShapes     &shapes; // the particles' volumes, diameters, sphericities
    FluidBackend          &backend;
    /// The fluid at the particles after the last exchange (before the
    /// self-induced correction), in the order of the DEM's local particles.
    const std::vector<ParticleFluidSample> &samples;
    MPI_Comm                                comm;
    /// Where the scene writes, for a probe's own files; set before the start.
    std::string output_directory = {};
  };

  struct ProbeResult
  {
    std::string              name;
    double                   value = 0., reference = 0., error = 0.;
    std::vector<std::string> checks; // 'check:' lines, printed before the result
  };

  class CouplingProbe
  {
  public:
    virtual ~CouplingProbe() = default;
    /// Before the output is prepared and the fluid starts: may place the
    /// particles, or refuse the scene with an InputError (collective).
    virtual void prepare(ProbeView &) {}
    /// After the fluid's start at t = 0 (collective).
    virtual void start(ProbeView &) {}
    /// After every fluid step (collective).
    virtual void observe(double /*time*/, ProbeView &) {}
    /// At the end (collective; the result on every rank).
    virtual ProbeResult finish(ProbeView &view) = 0;

    /// Whether it writes files of its own into the output directory (which
    /// is then prepared as for any other output).
    virtual bool writes_files() const { return false; }

    /// What it has measured so far, as numbers for a checkpoint (the same on
    /// every rank), and back on restart.
    virtual std::vector<double> state() const { return {}; }
    virtual void                set_state(const std::vector<double> &) {}
  };

  /// The probe of the scene's 'cfd-dem validation/case', or null for none.
  std::unique_ptr<CouplingProbe> make_coupling_probe(CouplingValidationCase validation);

  // ---- Shared by the probes ----

  /// The mean velocity of all particles (all ranks).
  Vec3 global_mean_velocity(const ParticleStorage &P, MPI_Comm comm);

  /// Whether a particle lies in the middle half, along the direction e, of
  /// the span of all particles (all ranks): where a bed's or a block's
  /// projected porosity is its own, away from the smoothed edges.
  std::function<bool(const Vec3 &)> in_middle_half(const ParticleStorage &P, const Vec3 &e,
                                                   MPI_Comm comm);

  /// The density of the scene's particles (of the first local particle's type).
  double particle_density(const ProbeView &view);

  /// The slip speed w with k(eps, w) w = target (the drag force grows with w).
  double slip_for_force(const SceneParameters &p, double d, double eps, double target);

  // The probes (probe_*.cc).
  std::unique_ptr<CouplingProbe> make_sedimentation_probe();
  std::unique_ptr<CouplingProbe> make_porous_block_probe();
  std::unique_ptr<CouplingProbe> make_packed_bed_probe();
  std::unique_ptr<CouplingProbe> make_fluidized_bed_probe();
  std::unique_ptr<CouplingProbe> make_rayleigh_taylor_probe();
  std::unique_ptr<CouplingProbe> make_segregation_probe();
} // namespace sluice
