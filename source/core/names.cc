// The name tables (see the header); the order is the order --print-parameters
// lists the choices in.

#include <sluice/core/names.h>

namespace sluice
{
#define SLUICE_NAMES(Enum, ...)                        \
  template <>                                          \
  const NameTable<Enum> &names()                       \
  {                                                    \
    static const NameTable<Enum> table{__VA_ARGS__};   \
    return table;                                      \
  }

  SLUICE_NAMES(Physics, {Physics::dem, "dem"}, {Physics::fluid, "fluid"},
               {Physics::cfd_dem, "cfd-dem"}, {Physics::sph, "sph"})
  SLUICE_NAMES(NormalContactModel, {NormalContactModel::linear, "linear"},
               {NormalContactModel::hertz_mindlin, "hertz_mindlin"})
  SLUICE_NAMES(RollingResistanceModel, {RollingResistanceModel::none, "none"},
               {RollingResistanceModel::constant_torque, "constant_torque"},
               {RollingResistanceModel::viscous, "viscous"})
  SLUICE_NAMES(InsertionMethod, {InsertionMethod::lattice, "lattice"},
               {InsertionMethod::random, "random"}, {InsertionMethod::file, "file"},
               {InsertionMethod::list, "list"})
  SLUICE_NAMES(IfOutputExists, {IfOutputExists::stop, "stop"},
               {IfOutputExists::overwrite, "overwrite"}, {IfOutputExists::new_directory, "new"})
  SLUICE_NAMES(ValidationCase, {ValidationCase::none, "none"},
               {ValidationCase::hertz_impact, "hertz_impact"},
               {ValidationCase::restitution, "restitution"},
               {ValidationCase::sliding_to_rolling, "sliding_to_rolling"},
               {ValidationCase::settle, "settle"},
               {ValidationCase::mesh_plane_equivalence, "mesh_plane_equivalence"},
               {ValidationCase::energy_balance, "energy_balance"},
               {ValidationCase::clump_impact, "clump_impact"},
               {ValidationCase::clump_rotation, "clump_rotation"})
  SLUICE_NAMES(VansFormulation, {VansFormulation::model_a, "model A"},
               {VansFormulation::model_b, "model B"})
  SLUICE_NAMES(PorousDrag, {PorousDrag::none, "none"}, {PorousDrag::ergun, "ergun"})
  SLUICE_NAMES(FluidMeshType, {FluidMeshType::box, "box"}, {FluidMeshType::cylinder, "cylinder"},
               {FluidMeshType::channel_with_cylinder, "channel_with_cylinder"},
               {FluidMeshType::gmsh, "gmsh"})
  SLUICE_NAMES(BoundaryType, {BoundaryType::no_slip, "no-slip"}, {BoundaryType::slip, "slip"},
               {BoundaryType::velocity, "velocity"},
               {BoundaryType::traction_free, "traction-free"},
               {BoundaryType::periodic, "periodic"})
  SLUICE_NAMES(TimeIntegration, {TimeIntegration::steady, "steady"},
               {TimeIntegration::bdf1, "bdf1"}, {TimeIntegration::bdf2, "bdf2"})
  SLUICE_NAMES(LinearPreconditioner, {LinearPreconditioner::ilu, "ilu"},
               {LinearPreconditioner::amg, "amg"},
               {LinearPreconditioner::lu, "lu"})
  SLUICE_NAMES(RefinementIndicator, {RefinementIndicator::velocity, "velocity"},
               {RefinementIndicator::porosity, "porosity"}, {RefinementIndicator::both, "both"})
  SLUICE_NAMES(FluidValidationCase, {FluidValidationCase::none, "none"},
               {FluidValidationCase::poiseuille, "poiseuille"},
               {FluidValidationCase::packed_bed_ergun, "packed_bed_ergun"},
               {FluidValidationCase::manufactured_solution, "manufactured_solution"},
               {FluidValidationCase::reference_value, "reference_value"})
  SLUICE_NAMES(CouplingFormulation, {CouplingFormulation::set_i, "set_i"},
               {CouplingFormulation::set_ii, "set_ii"}, {CouplingFormulation::set_iii, "set_iii"})
  SLUICE_NAMES(DragClosure, {DragClosure::stokes, "stokes"},
               {DragClosure::dallavalle, "dallavalle"}, {DragClosure::di_felice, "di_felice"},
               {DragClosure::rong, "rong"}, {DragClosure::wen_yu, "wen_yu"},
               {DragClosure::ergun, "ergun"}, {DragClosure::gidaspow, "gidaspow"},
               {DragClosure::syamlal_obrien, "syamlal_obrien"},
               {DragClosure::beetstra, "beetstra"}, {DragClosure::koch_hill, "koch_hill"},
               {DragClosure::hoelzer_sommerfeld, "hoelzer_sommerfeld"})
  SLUICE_NAMES(ProjectionScheme, {ProjectionScheme::kernel, "kernel"},
               {ProjectionScheme::centroid, "centroid"})
  SLUICE_NAMES(CouplingValidationCase, {CouplingValidationCase::none, "none"},
               {CouplingValidationCase::sedimentation, "sedimentation"},
               {CouplingValidationCase::porous_block, "porous_block"},
               {CouplingValidationCase::packed_bed, "packed_bed"},
               {CouplingValidationCase::fluidized_bed, "fluidized_bed"},
               {CouplingValidationCase::rayleigh_taylor, "rayleigh_taylor"},
               {CouplingValidationCase::segregation, "segregation"})

#undef SLUICE_NAMES
} // namespace sluice
