#pragma once
// The 'imported field' subsection: a DEM scene's particles driven one way by
// a flow field read from a file (coupling/imported_field_scene.h,
// doc/geometry.md). Plain data; all quantities SI.

#include <sluice/core/coupling_parameters.h>
#include <sluice/core/vector3.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace sluice
{
  /// A closed-form check of a particle in an analytic field written to a
  /// file (coupling/imported_field_check.h).
  enum class FieldCheck
  {
    none,
    uniform_stream,   // u = U: terminal slip against the force balance
    solid_body_vortex // u = Omega e_z x x: the orbit against the linear ODE's solution
  };

  struct ImportedFieldParameters
  {
    std::string file; // .vtu, .pvtu or .pvd; empty: no imported field
    std::string velocity_array = "velocity", pressure_array = "pressure", porosity_array;
    double      length_scale   = 1.;
    double      pressure_scale = 1.;
    double      density = 1000., viscosity = 1e-3; // [kg/m^3], [Pa s]
    DragClosure drag    = DragClosure::wen_yu;
    bool        pressure_gradient_force = true;
    bool        hydrostatic_in_pressure = true;
    double      period = 0.; // [s] of a time series; 0: not periodic
    FieldCheck  check  = FieldCheck::none;
    Vec3        check_velocity;             // [m/s] U of the uniform stream
    double      check_angular_velocity = 0.; // [rad/s] Omega of the vortex

    bool active() const { return !file.empty(); }
  };

  void                    declare_imported_field_parameters(dealii::ParameterHandler &prm);
  ImportedFieldParameters read_imported_field_parameters(dealii::ParameterHandler &prm,
                                                         const std::string        &scene);
} // namespace sluice
