// The 'cfd-dem' subsections of a scene file: declaration (default, unit, range,
// meaning of every entry) and reading.

#include <sluice/core/parameter_declaration.h>
#include <sluice/core/coupling_parameters.h>
#include <sluice/core/names.h>

#include <deal.II/base/parameter_handler.h>

namespace sluice
{
  using namespace dealii;
  using Patterns::Bool;
  using Patterns::Double;
  using Patterns::Selection;

  void declare_coupling_parameters(ParameterHandler &prm)
  {
    const double inf = unbounded();
    prm.enter_subsection("cfd-dem");
    {
      declare(prm, "fluid backend", "fe", Selection("fe|sph"),
              "What solves the fluid: 'fe', the finite-element VANS solver on the 'fluid "
              "mesh'; 'sph', the SPH fluid of the 'sph' subsection (its density, viscosity, "
              "block of fluid and walls; doc/sph.md), coupled by kernel sums with 'sph "
              "coupling length' (Robinson et al. 2014). With SPH, 'set_i' is Robinson et al.'s "
              "-grad p and 'set_ii' scales each SPH particle's pressure and viscous "
              "accelerations by its fluid fraction (-eps grad p + eps div tau).");
      declare(prm, "sph coupling length", "0", Double(0, inf),
              "[m] SPH backend: the smoothing length h_c of the kernel sums between SPH and "
              "DEM particles (fluid fraction, interpolation, reaction); 0: the SPH smoothing "
              "length 'sph/smoothing factor' x 'sph/particle spacing'. It must exceed the "
              "grains' spacing.");
      declare(prm, "particles above sph fluid", "false", Bool(),
              "SPH backend: whether particles may be above the SPH fluid's free surface, as the "
              "charge of a mill: they may start outside the fluid, and every particle's fluid "
              "forces are weighted by the share of its kernel the fluid covers (sum of V_a W "
              "over the SPH particles, at most 1), so that a grain across the surface feels "
              "part of its buoyancy and drag (doc/sph.md). false: a particle outside the fluid "
              "at the start stops the scene, naming the fluid's corners (a block that misses "
              "the particles), and the forces are not weighted.");
      declare(prm, "sph start at rest", "true", Bool(),
              "SPH backend: whether the start's damped relaxation (the particles held) must "
              "bring the fluid to rest, its largest speed below 1e-5 c_s; if not, the scene "
              "stops there (a block that does not fit its walls). false: the run goes on from "
              "what the relaxation reached, printed in the header - for a block cut to a "
              "curved shell (a drum, a mill), whose lattice rearranges for longer than the "
              "relaxation lasts.");
      declare(prm, "formulation", "set_ii", Selection(names<CouplingFormulation>().selection()),
              "Zhou et al. (2010): 'set_i' (fluid -grad p + div tau, every particle-fluid "
              "force goes back to the fluid), 'set_ii' (model A: fluid -eps grad p + eps div "
              "tau, only drag and the other non-stress forces go back), 'set_iii' (model B: "
              "particle feels drag/eps and the buoyancy -rho_f V_p g; valid for steady "
              "uniform flow). The fluid's 'fluid/formulation' follows.");
      declare(prm, "coupling", "two-way", Selection("two-way|one-way"),
              "'two-way': the particles' reaction and porosity go to the fluid; 'one-way': "
              "the fluid moves the particles and sees porosity 1 and no reaction.");
      declare(prm, "drag", "di_felice", Selection(names<DragClosure>().selection()),
              "Drag closure (doc/coupling.md): per-particle f = k (u - v). A clump body takes "
              "its volume-equivalent diameter, and any closure but 'hoelzer_sommerfeld' (a "
              "single particle of any shape) is multiplied by the shape's Hoelzer-Sommerfeld "
              "drag ratio (doc/clumps.md).");
      declare(prm, "projection", "kernel", Selection(names<ProjectionScheme>().selection()),
              "How particle volume, momentum and reaction reach the fluid mesh: 'kernel' "
              "(Gao & Sun Eqs. 23-25, K = (1 - xi^2)^4 over 'kernel radius') or 'centroid' "
              "(the shape functions of the particle's cell at its centre).");
      declare(prm, "kernel radius", "0", Double(0, inf),
              "[m] Support radius R_s of the kernel; 0: the smallest fluid cell. Must be "
              "at least two particle diameters and at most the smallest fluid cell.");
      declare(prm, "smoothing bandwidth", "0", Double(0, inf),
              "[m] Diffusion-based coarse graining after the projection (Sun & Xiao 2015): "
              "porosity, solid velocity and reaction are diffused to this width, conserving "
              "their integrals; 0 switches it off. About 2-3 cells takes the cell out of "
              "the particle's self-interaction; costs a few CG solves per fluid step.");
      declare(prm, "pressure gradient force", "true", Bool(),
              "Sets I/II: the force -V_p grad p on each particle (buoyancy and the "
              "pressure the drag builds up).");
      declare(prm, "viscous force", "false", Bool(),
              "Sets I/II: the force V_p div tau on each particle.");
      declare(prm, "virtual mass coefficient", "0", Double(0, 10),
              "[-] C_vm of the virtual-mass force C_vm rho_f V_p (Du/Dt - dv/dt), 0.5 for a "
              "sphere; 0 switches it off. Treated implicitly as added inertia.");
      declare(prm, "saffman lift", "false", Bool(),
              "Saffman (1965) shear lift 1.615 d^2 (rho_f mu)^(1/2) |w|^(-1/2) (u - v) x w, "
              "w = curl u.");
      declare(prm, "magnus lift", "false", Bool(),
              "Rubinow & Keller (1961) spin lift (pi/8) d^3 rho_f (curl u / 2 - omega_p) x "
              "(u - v).");
      declare(prm, "maximum solid fraction", "0.64", Double(0.01, 1),
              "[-] Cap on the projected solid fraction (nodes above it are counted and "
              "reported); the porosity the fluid sees is at least 1 minus this.");
      declare(prm, "fixed particles", "false", Bool(),
              "Hold every particle in place (a packed bed): the DEM does not move them, the "
              "fluid still sees them.");
      declare(prm, "self-induced velocity correction", "false", Bool(),
              "Two-way: subtract from the fluid velocity at each particle the part its own "
              "reaction induced there, so that the drag law sees the undisturbed fluid "
              "(doc/coupling.md). For dilute suspensions on cells (or SPH coupling lengths) "
              "of a few diameters, where that part reaches several percent of the slip. The "
              "fluid's response to one deposited impulse is measured at the start and "
              "convolved with each particle's force history: finite elements, one "
              "particle-free solve of 'self-induced memory' / dt steps on the scene's mesh "
              "(needs a fixed, non-adaptive mesh; assumes uniform cells and no wall within "
              "the response's reach); SPH, two copies of the fluid after the start's "
              "relaxation, with and without the impulse, at the particles' centroid "
              "(doc/sph.md).");
      declare(prm, "weight ramp time", "0", Double(0, inf),
              "[s] Lets the particles' weight beyond their buoyancy, (m - rho_f V) g, on "
              "smoothly over this time, r = (1 - cos(pi t / T)) / 2, the rest held by a "
              "support force the fluid does not get; 0: at once. A heavy suspension let go at "
              "once in the weakly compressible SPH fluid makes the column ring at its "
              "acoustic period (doc/sph.md); over a few periods it settles without. Not with "
              "'cfd-dem validation/case = sedimentation' (its equation starts at once); "
              "with another validation case, shorter than the end time.");
      declare(prm, "semi-implicit drag", "false", Bool(),
              "Two-way, finite-element fluid: the fluid also takes the drag's dependence "
              "on its own velocity into its matrix, as beta (u^n+1 - u^n) with beta = the "
              "particles' drag coefficients deposited like their volume, and returns it "
              "at the next step as an explicit source, so that the momentum it exchanges "
              "still adds up to the particles' impulses (doc/coupling.md). Lifts the "
              "stability limit dt_f beta / (eps rho_f) < 1 of the explicit reaction; the "
              "accuracy is still the coupling step's: a bubbling gas bed ran as the explicit "
              "one at twice the explicit limit and stopped bubbling at five times it. Needs "
              "a fixed (non-adaptive) mesh; not with the self-induced velocity correction.");
      declare(prm, "self-induced memory", "0", Double(0, inf),
              "[s] How far back a particle's forces count in the correction (the length of "
              "the measured response); 0: the scene's end time. Costs memory/dt fluid steps "
              "at the start (twice that with SPH) and 48 bytes per particle and step of memory.");
    }
    prm.leave_subsection();

    prm.enter_subsection("cfd-dem validation");
    {
      declare(prm, "case", "none",
              Selection(names<CouplingValidationCase>().selection()),
              "'sedimentation': particle velocity at the end against the single-particle "
              "equation integrated in time (and its history); 'porous_block': the block's "
              "settling velocity against the drag law at 'block porosity'; 'packed_bed': "
              "pressure gradient in the bed against Ergun; 'fluidized_bed': bed pressure drop "
              "(second half of the run) against the buoyant bed weight per area, and the "
              "minimum fluidization velocity of the inlet ramp against Wen & Yu; "
              "'rayleigh_taylor': the particles are first displaced downwards by "
              "(d/8)(1 - cos 2 pi x/L)(1 - cos 2 pi y/L) (L: the domain's x length; Robinson "
              "et al. 2014, Eq. 40), and the growth rate of the lowest particle's depth is "
              "compared with the two-fluid bounds (Chandrasekhar's relation with the "
              "suspension's Krieger viscosity, and the inviscid sqrt(A g k)) at 'block "
              "porosity'; 'segregation': a bed of two species (material types), the "
              "mass-weighted mean height of each above the bed's bottom (Gao & Sun Eq. 46) "
              "against time in segregation.csv (a row every millisecond) and Goldschmidt et "
              "al.'s (2003) segregation index (S - 1) / (S_max - 1), S = <h_small> / "
              "<h_large>, averaged over the second half of the run against 0 (mixed; the "
              "'tolerance' bounds the index itself).");
      declare(prm, "tolerance", "0", Double(0, inf),
              "[-] If > 0, exit with code 3 when the relative error exceeds it.");
      declare(prm, "block porosity", "0", Double(0, 1),
              "[-] Porous block, packed bed, Rayleigh-Taylor layer: the porosity of the "
              "lattice (for the reference).");
      declare(prm, "averaging start", "0", Double(0, inf),
              "[s] Porous block: compare the middle particles' velocity averaged from this "
              "time to the end (each fluid step weighted by its length) instead of the "
              "velocity at the end. A heavy block in the weakly compressible SPH fluid "
              "leaves the column ringing at its acoustic period (doc/sph.md); over whole "
              "periods the ringing averages out. 0: the velocity at the end. Only with "
              "'case = porous_block'; not before 'cfd-dem/weight ramp time' ends, and "
              "before 'simulation/end time'.");
    }
    prm.leave_subsection();
  }

  void read_coupling_parameters(ParameterHandler &prm, const std::string & /*file_name*/,
                                CouplingParameters &p)
  {
    prm.enter_subsection("cfd-dem");
    {
      p.fluid_backend       = prm.get("fluid backend") == "sph" ? FluidBackendKind::sph :
                                                                  FluidBackendKind::fe;
      p.sph_coupling_length = prm.get_double("sph coupling length");
      p.particles_above_fluid = prm.get_bool("particles above sph fluid");
      p.sph_start_at_rest     = prm.get_bool("sph start at rest");
      p.formulation = value_of<CouplingFormulation>(prm.get("formulation"));
      p.two_way                  = prm.get("coupling") == "two-way";
      p.drag                     = value_of<DragClosure>(prm.get("drag"));
      p.projection               = value_of<ProjectionScheme>(prm.get("projection"));
      p.kernel_radius            = prm.get_double("kernel radius");
      p.smoothing_bandwidth      = prm.get_double("smoothing bandwidth");
      p.pressure_gradient_force  = prm.get_bool("pressure gradient force");
      p.viscous_force            = prm.get_bool("viscous force");
      p.virtual_mass_coefficient = prm.get_double("virtual mass coefficient");
      p.saffman_lift             = prm.get_bool("saffman lift");
      p.magnus_lift              = prm.get_bool("magnus lift");
      p.max_solid_fraction       = prm.get_double("maximum solid fraction");
      p.fixed_particles          = prm.get_bool("fixed particles");
      p.self_induced_correction  = prm.get_bool("self-induced velocity correction");
      p.self_induced_memory      = prm.get_double("self-induced memory");
      p.weight_ramp_time         = prm.get_double("weight ramp time");
      p.semi_implicit_drag       = prm.get_bool("semi-implicit drag");
    }
    prm.leave_subsection();
    prm.enter_subsection("cfd-dem validation");
    {
      p.validation     = value_of<CouplingValidationCase>(prm.get("case"));
      p.tolerance      = prm.get_double("tolerance");
      p.block_porosity = prm.get_double("block porosity");
      p.averaging_start = prm.get_double("averaging start");
    }
    prm.leave_subsection();
  }
} // namespace sluice
