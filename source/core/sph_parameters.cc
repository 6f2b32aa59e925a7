// The 'sph' subsection (see the header).

#include <sluice/core/parameter_declaration.h>
#include <sluice/core/scene_parameters.h>
#include <sluice/core/sph_parameters.h>

#include <deal.II/base/utilities.h>

#include <algorithm>

namespace sluice
{
  using namespace dealii;

  void declare_sph_parameters(ParameterHandler &prm)
  {
    const auto vector = Patterns::List(Patterns::Double(), 3, 3, ",");
    prm.enter_subsection("sph");
    declare(prm, "kernel", "wendland_c2", Patterns::Selection("wendland_c2|cubic_spline"),
            "Smoothing kernel, both of support 2h: Wendland's C2 (Robinson et al. 2014) or the "
            "cubic spline M4 (doc/sph.md).");
    declare(prm, "particle spacing", "0.001", Patterns::Double(0.),
            "[m] dx of the lattice the fluid and wall particles start on; each has the mass "
            "rho_0 dx^3.", "(0, inf)");
    declare(prm, "smoothing factor", "1.5", Patterns::Double(1., 3.),
            "[-] sigma in h = sigma (m / rho)^(1/3): h = 1.5 dx at the reference density.");
    declare(prm, "smoothing length", "variable", Patterns::Selection("variable|fixed"),
            "'variable': h = sigma (m / rho_hat)^(1/3) at every step, with Price's Omega in "
            "the continuity and pressure sums (Robinson et al. 2014, Eqs. 10-11 and 19), so "
            "that h follows the fluid fraction; 'fixed': each particle keeps the h it starts "
            "with and Omega = 1 (classic weakly compressible SPH, as LIGGGHTS' SPH styles).");
    declare(prm, "density", "1000", Patterns::Double(0.),
            "[kg/m^3] The fluid's reference density rho_0.", "(0, inf)");
    declare(prm, "viscosity", "0.001", Patterns::Double(0.),
            "[Pa s] Dynamic viscosity mu.");
    declare(prm, "viscosity form", "morris", Patterns::Selection("morris|signal_velocity"),
            "How mu enters the momentum equation: 'morris', Morris, Fox & Zhu's (1997) laminar "
            "term; 'signal_velocity', Monaghan's (1997) signal-velocity viscosity with its "
            "coefficient tied to mu (Robinson et al. 2014, Eqs. 13-14; doc/sph.md): a central "
            "pair force that also keeps angular momentum.");
    declare(prm, "artificial viscosity", "0.1", Patterns::Double(0., 2.),
            "[-] alpha of Monaghan's artificial viscosity, between approaching particles only; "
            "it damps the acoustic noise of weak compressibility (without it a free surface "
            "goes unstable).");
    declare(prm, "artificial pressure", "0", Patterns::Double(0., 1.),
            "[-] epsilon of Monaghan's (2000) artificial pressure against the tensile "
            "instability: particles in tension (P < 0) repel by epsilon |P| / rho^2 times "
            "(W(r) / W(dx))^4; 0: off, 0.2 usual.");
    declare(prm, "density diffusion", "0", Patterns::Double(0., 1.),
            "[-] delta of delta-SPH (Molteni & Colagrossi 2009): a diffusive term in the "
            "continuity equation, delta h c_s times the density's SPH Laplacian, with the "
            "hydrostatic part taken out (Fourtakas et al. 2019); 0: off, 0.1 usual.");
    declare(prm, "density evolution", "continuity", Patterns::Selection("continuity|summation"),
            "How the density advances: 'continuity', the continuity equation with Price's "
            "Omega (Robinson et al. 2014, Eqs. 10-11); 'summation', the kernel sum at every "
            "step, for comparison (a free surface's deficient sums pull it together).");
    declare(prm, "xsph", "0", Patterns::Double(0., 1.),
            "[-] epsilon of XSPH (Monaghan 1989): particles drift with their velocity plus "
            "epsilon times its kernel-weighted mean difference from their neighbours'; 0: off, "
            "0.5 usual.");
    declare(prm, "time integration", "leap_frog",
            Patterns::Selection("leap_frog|predictor_corrector"),
            "The step: 'leap_frog', kick-drift-kick with the rates at a predicted velocity "
            "(Price 2012; one evaluation of the rates a step); 'predictor_corrector', "
            "Monaghan's (1989) predictor-corrector that Gao & Sun (section 4) name beside it "
            "(the rates at a predicted half step, then the whole step with them: two "
            "evaluations a step, doc/sph.md).");
    declare(prm, "sound speed", "0", Patterns::Double(0.),
            "[m/s] c_s of Tait's equation; 0: 10 times the larger of 'characteristic "
            "velocity' and sqrt(2 g H), H the fluid block's height along gravity's "
            "non-periodic part, so that the density varies by less than 1%.");
    declare(prm, "characteristic velocity", "0", Patterns::Double(0.),
            "[m/s] The largest speed the flow reaches, for the automatic sound speed.");
    declare(prm, "time step", "0", Patterns::Double(0.),
            "[s] The SPH step; 0: 'time step fraction' times the stable step at the start "
            "(CFL 0.25 h / (c_s + |v|), viscous 0.125 h^2 rho / mu, force 0.25 sqrt(h / |a|)). "
            "The run stops when the stable step falls below it.");
    declare(prm, "time step fraction", "0.5", Patterns::Double(0., 1.),
            "[-] Of the stable step at the start, for the automatic step; the run stops when "
            "the stable step falls below the step (the flow became twice as fast or "
            "accelerated 4 times more, at the default).", "(0, 1]");
    declare(prm, "fluid lower corner", "0, 0, 0", vector,
            "[m] The block filled with fluid particles, on the lattice from lower corner + "
            "dx/2.");
    declare(prm, "fluid upper corner", "0, 0, 0", vector, "[m] Its upper corner.");
    declare(prm, "walls", "", Patterns::Anything(),
            "Faces of the domain that are solid walls, of the 'wall model' (by default wall "
            "particles: Adami et al. 2012), e.g. 'z-' or 'x-, x+, z-'; the wall particles or "
            "boundary particles lie outside the domain.",
            "empty, or a comma-separated list of x-, x+, y-, y+, z-, z+ (not periodic faces)");
    declare(prm, "wall model", "particles", Patterns::Selection("particles|lennard_jones"),
            "What the 'walls' are: 'particles', layers of wall particles with Adami et al.'s "
            "(2012) boundary condition (pressure with the hydrostatic term, no slip); "
            "'lennard_jones', one layer of repulsive boundary particles dx/2 outside the face at "
            "spacing dx/2, each pushing fluid particles closer than dx with Monaghan's (1994) "
            "force D [(dx/r)^12 - (dx/r)^4] r / r^2 per unit mass (free slip; doc/sph.md).");
    declare(prm, "lennard-jones strength", "0", Patterns::Double(0.),
            "[m^2/s^2] D of the Lennard-Jones walls; 0: c_s^2 / 40, which is Monaghan's 5 g H "
            "at the automatic sound speed 10 sqrt(2 g H).");
    declare(prm, "solid walls", "false", Patterns::Bool(),
            "Whether the scene's DEM walls - the planes of 'walls' (its box faces among them "
            "when 'walls/box' is true) and its triangle meshes, moving or not - hold the fluid "
            "too: each fluid particle, a sphere of radius dx/2, meets them by a normal "
            "spring-dashpot contact (Gao & Sun, section 4; free slip, doc/sph.md). The wall "
            "load is reported; in a coupled scene (cfd-dem, 'fluid backend = sph') the fluid's "
            "torque and power on each mesh too.");
    declare(prm, "solid wall stiffness", "0", Patterns::Double(0.),
            "[N/m] k of the solid walls' contact; 0: rho_0 c_s^2 dx / 4, which holds the "
            "pressure of a 1% density rise at an overlap of 4% of dx. The run stops when a "
            "particle comes within dx/4 of a wall (too soft).");
    declare(prm, "solid wall restitution", "0.1", Patterns::Double(0., 1.),
            "[-] The restitution of a fluid particle meeting a solid wall, which sets the "
            "contact's damping (as the DEM's linear law).", "(0, 1]");
    declare(prm, "validation", "none",
            Patterns::Selection("none|hydrostatic|poiseuille|dam_break|solid_wall_load"),
            "'hydrostatic': a column at rest on a floor; the bottom layer's pressure against "
            "rho_0 g (H - z), the density drift and the spurious velocities. 'poiseuille': the "
            "start-up of plane Poiseuille flow between walls on the two faces of one direction, "
            "driven by gravity along a periodic one; the layers' velocities against Morris et "
            "al.'s (1997) series at nu t / L^2 = 0.0225, 0.045, 0.1125 and the end, relative to "
            "the steady centre-line velocity. 'dam_break': a column twice as high as wide "
            "against the x- wall collapses along +x on a z- floor (Martin & Moyce 1952, "
            "a = 2.25 in); the surge front x/a against their measurements at "
            "T = t sqrt(2 g / a) up to the end time, relative to theirs. 'solid_wall_load': "
            "fluid coming to rest in a vessel of 'solid walls'; the walls' load along gravity "
            "at the end against the fluid's weight.");
    declare(prm, "tolerance", "0", Patterns::Double(0.),
            "[-] Largest accepted validation error (exit 3 above it); 0: none.");
    prm.leave_subsection();
  }

  SphParameters read_sph_parameters(ParameterHandler &prm, const std::string &scene)
  {
    SphParameters s;
    const auto    fail = [&](const std::string &entry, const std::string &what) {
      throw InputError("error in '" + scene + "': entry 'sph/" + entry + "' " + what);
    };
    prm.enter_subsection("sph");
    s.kernel                  = prm.get("kernel");
    s.spacing                 = prm.get_double("particle spacing");
    s.smoothing_factor        = prm.get_double("smoothing factor");
    s.fixed_smoothing_length  = prm.get("smoothing length") == "fixed";
    s.density                 = prm.get_double("density");
    s.viscosity               = prm.get_double("viscosity");
    s.viscosity_form          = prm.get("viscosity form");
    s.artificial_viscosity    = prm.get_double("artificial viscosity");
    s.artificial_pressure     = prm.get_double("artificial pressure");
    s.density_diffusion       = prm.get_double("density diffusion");
    s.summation_density       = prm.get("density evolution") == "summation";
    s.xsph                    = prm.get_double("xsph");
    s.time_integration        = prm.get("time integration");
    s.sound_speed             = prm.get_double("sound speed");
    s.characteristic_velocity = prm.get_double("characteristic velocity");
    s.time_step               = prm.get_double("time step");
    s.time_step_fraction      = prm.get_double("time step fraction");
    s.fluid_lower             = get_vector(prm, "fluid lower corner");
    s.fluid_upper             = get_vector(prm, "fluid upper corner");
    for (std::string face : Utilities::split_string_list(prm.get("walls"), ','))
      {
        face = Utilities::trim(face);
        const std::vector<std::string> faces = {"x-", "x+", "y-", "y+", "z-", "z+"};
        if (std::find(faces.begin(), faces.end(), face) == faces.end())
          fail("walls", "has '" + face + "'; allowed: x-, x+, y-, y+, z-, z+");
        s.walls.push_back(face);
      }
    s.wall_model             = prm.get("wall model");
    s.lennard_jones_strength = prm.get_double("lennard-jones strength");
    s.solid_walls            = prm.get_bool("solid walls");
    s.solid_wall_stiffness   = prm.get_double("solid wall stiffness");
    s.solid_wall_restitution = prm.get_double("solid wall restitution");
    if (!(s.solid_wall_restitution > 0.))
      fail("solid wall restitution", "is 0; it must lie in (0, 1] (a contact without "
                                     "rebound is not a linear spring-dashpot)");
    const std::string validation = prm.get("validation");
    s.validation = validation == "hydrostatic" ? SphValidationCase::hydrostatic :
                   validation == "poiseuille"  ? SphValidationCase::poiseuille :
                   validation == "dam_break"   ? SphValidationCase::dam_break :
                   validation == "solid_wall_load" ? SphValidationCase::solid_wall_load :
                                                 SphValidationCase::none;
    s.tolerance  = prm.get_double("tolerance");
    prm.leave_subsection();
    if (!(s.spacing > 0.) || !(s.density > 0.))
      fail("particle spacing", "and 'density' must be > 0");
    if (s.time_step_fraction <= 0.)
      fail("time step fraction", "must be in (0, 1]");
    if (s.validation == SphValidationCase::solid_wall_load && !s.solid_walls)
      fail("validation", "is 'solid_wall_load', which weighs the load on the 'solid walls': "
                         "set 'sph/solid walls = true'");
    return s;
  }
} // namespace sluice
