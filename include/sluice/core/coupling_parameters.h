#pragma once
// What a scene file says about the particle-fluid coupling: the 'cfd-dem' and
// 'cfd-dem validation' subsections. Plain data; filled and checked in
// coupling_parameters.cc. All quantities are SI.

#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace sluice
{
  /// Fluid-particle drag closures (coupling/drag_closures.h has the formulas).
  enum class DragClosure
  {
    stokes,         // f = 3 pi mu d w
    dallavalle,     // single sphere, C_d = (0.63 + 4.8/sqrt(Re))^2, Re = rho d w / mu
    di_felice,      // Dallavalle C_d with the voidage function eps^(2-chi) (Di Felice 1994)
    rong,           // Di Felice form with Rong et al. (2013)'s chi(eps, Re)
    wen_yu,         // Wen & Yu (1966), Schiller-Naumann C_d, eps^-2.65
    ergun,          // Ergun (1952) in Gidaspow's beta form
    gidaspow,       // Ergun for eps <= 0.8, Wen-Yu above
    syamlal_obrien, // Syamlal & O'Brien (1988), terminal-velocity ratio V_r
    beetstra,       // Beetstra, van der Hoef & Kuipers (2007)
    koch_hill,      // Hill, Koch & Ladd (2001) as in Benyahia et al. (2006)
    hoelzer_sommerfeld // a single particle of any shape (Hoelzer & Sommerfeld 2008, Eq. 9)
  };

  /// How a particle's volume and force are spread onto the fluid mesh.
  enum class ProjectionScheme
  {
    kernel,  // Gao & Sun kernel over a sphere of radius R_s, normalised in the domain
    centroid // the shape functions of the particle's own cell at its centre
  };

  /// The three consistent CFD-DEM formulations of Zhou et al. (2010), Table 1.
  enum class CouplingFormulation
  {
    set_i,   // fluid: -grad p + div tau;         particle: f_d + f_grad p + f_div tau; all exchanged
    set_ii,  // fluid: -eps grad p + eps div tau; particle: the same;   only f_d (+ f'') exchanged
    set_iii  // fluid: -grad p + div tau;         particle: f_d / eps - rho_f V_p g; all exchanged
  };

  enum class CouplingValidationCase
  {
    none,
    sedimentation,   // one particle: velocity against the integrated single-particle equation
    porous_block,    // a lattice settling as a block: velocity against the drag law at eps
    packed_bed,      // fixed particles: pressure gradient against Ergun
    fluidized_bed,   // bed pressure drop against the buoyant bed weight per area
    rayleigh_taylor, // growth of a suspension layer's lowest particle against the two-fluid bounds
    segregation      // a binary mixture's mean heights per species (Eq. 46) and segregation index
  };

  /// What solves the fluid of a coupled scene.
  enum class FluidBackendKind
  {
    fe, // the finite-element VANS solver on the 'fluid mesh'
    sph // the SPH fluid of the 'sph' subsection (doc/sph.md)
  };

  struct CouplingParameters
  {
    FluidBackendKind    fluid_backend = FluidBackendKind::fe;
    double              sph_coupling_length = 0.; // [m]; 0: the SPH smoothing length
    bool                particles_above_fluid = false; // SPH: grains may start out of the fluid
    bool                sph_start_at_rest     = true;  // SPH: the start must bring it to rest
    CouplingFormulation formulation = CouplingFormulation::set_ii;
    bool                two_way     = true;
    DragClosure         drag        = DragClosure::di_felice;
    ProjectionScheme    projection  = ProjectionScheme::kernel;
    double              kernel_radius = 0.; // 0: the smallest fluid cell
    double              smoothing_bandwidth = 0.; // [m] diffusion smoothing; 0: none
    bool                pressure_gradient_force = true;
    bool                viscous_force           = false;
    double              virtual_mass_coefficient = 0.;
    bool                saffman_lift = false;
    bool                magnus_lift  = false;
    double              max_solid_fraction = 0.64;
    bool                fixed_particles    = false;
    bool                self_induced_correction = false;
    double              self_induced_memory     = 0.; // [s]; 0: the whole run
    double              weight_ramp_time        = 0.; // [s]; 0: the weight at once
    bool                semi_implicit_drag      = false; // the drag's u-part in the fluid matrix

    // subsection cfd-dem validation
    CouplingValidationCase validation = CouplingValidationCase::none;
    double                 tolerance  = 0.;
    double                 block_porosity = 0.; // porous block, packed bed: the lattice's porosity
    double                 averaging_start = 0.; // [s] porous block; 0: the velocity at the end
  };

  void declare_coupling_parameters(dealii::ParameterHandler &prm);
  void read_coupling_parameters(dealii::ParameterHandler &prm, const std::string &file_name,
                                CouplingParameters &p);
} // namespace sluice
