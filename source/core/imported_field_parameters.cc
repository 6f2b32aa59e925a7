// The 'imported field' subsection (see the header).

#include <sluice/core/imported_field_parameters.h>
#include <sluice/core/names.h>
#include <sluice/core/parameter_declaration.h>
#include <sluice/core/scene_parameters.h>

#include <filesystem>

namespace sluice
{
  using namespace dealii;

  void declare_imported_field_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("imported field");
    declare(prm, "file", "", Patterns::Anything(),
            "A flow field that drives the particles one way (nothing goes back to the fluid "
            "and no fluid system is built): a .vtu or .pvtu unstructured grid, or a .pvd time "
            "series of them, relative to the scene file's directory; empty: none.",
            "empty, or a .vtu, .pvtu or .pvd file");
    declare(prm, "velocity array", "velocity", Patterns::Anything(),
            "Name of the point or cell array (3 components) with the fluid velocity [m/s].");
    declare(prm, "pressure array", "pressure", Patterns::Anything(),
            "Name of the point or cell array with the pressure (times 'pressure scale': Pa); "
            "read only with the pressure gradient force.");
    declare(prm, "porosity array", "", Patterns::Anything(),
            "Name of the array with the fluid's volume fraction, which the drag closure "
            "sees; empty: 1 (a dilute stream).");
    declare(prm, "length scale", "1", Patterns::Double(0.),
            "[m per file unit] The file's coordinates times this are metres (0.001 for mm).",
            "(0, inf)");
    declare(prm, "pressure scale", "1", Patterns::Double(),
            "[Pa per file unit] The file's pressure times this is Pa (the fluid density for "
            "OpenFOAM's kinematic p / rho).");
    declare(prm, "fluid density", "1000", Patterns::Double(0.), "[kg/m^3] rho_f.", "(0, inf)");
    declare(prm, "fluid viscosity", "1e-3", Patterns::Double(0.), "[Pa s] Dynamic viscosity.",
            "(0, inf)");
    declare(prm, "drag", "wen_yu", Patterns::Selection(names<DragClosure>().selection()),
            "Drag closure (doc/coupling.md; Gao & Sun use Wen-Yu). Clump bodies as in "
            "'cfd-dem/drag'.");
    declare(prm, "pressure gradient force", "true", Patterns::Bool(),
            "Add -V_p grad p, with grad p from the field's pressure.");
    declare(prm, "hydrostatic pressure", "true", Patterns::Bool(),
            "true: the field's pressure includes the hydrostatic rho_f g . x (as Sluice's "
            "own fluid output does), so the pressure gradient force carries the buoyancy; "
            "false: it does not (OpenFOAM's p_rgh), and -rho_f V_p g is added.");
    declare(prm, "period", "0", Patterns::Double(0.),
            "[s] A .pvd series repeats with this period (a rotating impeller's frames; at "
            "least the span of its times, the last frame blending into the first); 0: not "
            "periodic, and the field is held at its first and last frames outside them.");
    declare(prm, "check", "none", Patterns::Selection("none|uniform_stream|solid_body_vortex"),
            "Validation against a closed form, for a field written from an analytic one: "
            "uniform_stream (u = 'check velocity' everywhere: each particle's terminal slip "
            "against the force balance of the drag closure, buoyancy included) or "
            "solid_body_vortex (u = Omega e_z x x about the z axis, p = rho_f Omega^2 r^2 / 2 "
            "(+ rho_f g . x): each particle's orbit against the solution of its linear "
            "equation of motion; needs 'drag = stokes'). Prints the field's interpolation "
            "error and a result line; 'validation/tolerance' applies.");
    declare(prm, "check velocity", "0, 0, 0", Patterns::List(Patterns::Double(), 3, 3, ","),
            "[m/s] U of the uniform stream.");
    declare(prm, "check angular velocity", "0", Patterns::Double(),
            "[rad/s] Omega of the solid-body vortex.");
    prm.leave_subsection();
  }

  ImportedFieldParameters read_imported_field_parameters(ParameterHandler &prm,
                                                         const std::string &scene)
  {
    ImportedFieldParameters f;
    prm.enter_subsection("imported field");
    f.file = prm.get("file");
    if (!f.file.empty() && std::filesystem::path(f.file).is_relative())
      f.file = (std::filesystem::path(scene).parent_path() / f.file).lexically_normal().string();
    const std::string extension = std::filesystem::path(f.file).extension().string();
    if (!f.file.empty() && extension != ".vtu" && extension != ".pvtu" && extension != ".pvd")
      throw InputError("error in '" + scene + "': entry 'imported field/file' is '" +
                       prm.get("file") + "'; allowed: a .vtu, .pvtu or .pvd file");
    f.velocity_array          = prm.get("velocity array");
    f.pressure_array          = prm.get("pressure array");
    f.porosity_array          = prm.get("porosity array");
    f.length_scale            = prm.get_double("length scale");
    f.pressure_scale          = prm.get_double("pressure scale");
    f.density                 = prm.get_double("fluid density");
    f.viscosity               = prm.get_double("fluid viscosity");
    f.drag                    = value_of<DragClosure>(prm.get("drag"));
    f.pressure_gradient_force = prm.get_bool("pressure gradient force");
    f.hydrostatic_in_pressure = prm.get_bool("hydrostatic pressure");
    f.period                  = prm.get_double("period");
    const std::string check   = prm.get("check");
    f.check = check == "uniform_stream"    ? FieldCheck::uniform_stream :
              check == "solid_body_vortex" ? FieldCheck::solid_body_vortex :
                                             FieldCheck::none;
    f.check_velocity          = get_vector(prm, "check velocity");
    f.check_angular_velocity  = prm.get_double("check angular velocity");
    prm.leave_subsection();
    for (const auto &[value, entry] : {std::pair{f.length_scale, "length scale"},
                                       {f.density, "fluid density"},
                                       {f.viscosity, "fluid viscosity"}})
      if (!(value > 0.))
        throw InputError("error in '" + scene + "': entry 'imported field/" + entry +
                         "' must be > 0");
    if (f.check == FieldCheck::solid_body_vortex && f.drag != DragClosure::stokes)
      throw InputError("error in '" + scene + "': entry 'imported field/check' is "
                       "'solid_body_vortex', whose closed form needs 'imported field/drag = "
                       "stokes' (a linear drag)");
    if (f.check != FieldCheck::none && !f.active())
      throw InputError("error in '" + scene + "': entry 'imported field/check' is set but "
                       "'imported field/file' is empty");
    return f;
  }
} // namespace sluice
