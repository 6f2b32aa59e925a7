#pragma once
// The 'sph' subsection: an SPH fluid scene (simulation/physics = sph;
// doc/sph.md): the fluid, its discretisation, the block of fluid particles,
// the walls of wall particles and the validation case.

#include <sluice/core/vector3.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace sluice
{
  enum class SphValidationCase
  {
    none,
    hydrostatic, // a column at rest: bottom pressure, density drift, spurious velocities
    poiseuille,  // the start-up of plane Poiseuille flow: profiles against the series
    dam_break,   // Martin & Moyce's (1952) collapsing column: surge front against time
    solid_wall_load // fluid at rest held by solid walls: their load against its weight
  };

  struct SphParameters
  {
    std::string kernel = "wendland_c2"; // or cubic_spline
    double      spacing              = 1e-3;  // dx [m]
    double      smoothing_factor     = 1.5;   // h = sigma (m / rho)^(1/3) [-]
    bool        fixed_smoothing_length = false; // smoothing length = fixed
    double      density              = 1000.; // rho_0 [kg/m^3]
    double      viscosity            = 1e-3;  // mu [Pa s]
    std::string viscosity_form       = "morris"; // or signal_velocity
    double      artificial_viscosity = 0.1;   // alpha [-]
    double      artificial_pressure  = 0.;    // Monaghan's (2000) epsilon [-]; 0: off
    double      density_diffusion    = 0.;    // delta of delta-SPH [-]; 0: off
    bool        summation_density    = false; // density evolution = summation
    double      xsph                 = 0.;    // XSPH's epsilon [-]; 0: off
    std::string time_integration     = "leap_frog"; // or predictor_corrector
    double      sound_speed          = 0.;    // c_s [m/s]; 0: automatic
    double      characteristic_velocity = 0.; // [m/s] for the automatic c_s
    double      time_step          = 0.;      // [s]; 0: automatic
    double      time_step_fraction = 0.5;     // of the stable step, automatic [-]
    Vec3        fluid_lower, fluid_upper;     // the block of fluid particles [m]
    // Walls of wall particles on the domain's faces: 'x-', 'x+', ..., 'z+'.
    std::vector<std::string> walls;
    std::string wall_model = "particles"; // or lennard_jones (sph_repulsive_walls.h)
    double      lennard_jones_strength = 0.; // D [m^2/s^2]; 0: automatic
    // The scene's DEM walls (planes and meshes) hold the fluid too, by a
    // spring-dashpot contact (sph_solid_walls.h).
    bool        solid_walls            = false;
    double      solid_wall_stiffness   = 0.;  // k [N/m]; 0: rho_0 c_s^2 dx / 4
    double      solid_wall_restitution = 0.1; // e [-]
    SphValidationCase        validation = SphValidationCase::none;
    double                   tolerance  = 0.; // of the validation's error; 0: none
  };

  void          declare_sph_parameters(dealii::ParameterHandler &prm);
  SphParameters read_sph_parameters(dealii::ParameterHandler &prm, const std::string &scene);
} // namespace sluice
