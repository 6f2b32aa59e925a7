// Coefficient functions from the .prm expressions.

#include <sluice/fluid/fluid_coefficients.h>

#include <deal.II/base/utilities.h>

namespace sluice
{
  using namespace dealii;

  void ParsedFunction::rebuild()
  {
    parser = std::make_unique<FunctionParser<3>>(n_expressions, 0., step);
    parser->set_formula(AutoDerivativeFunction<3>::FourthOrder);
    parser->initialize("x,y,z,t", expression, constants, true);
  }

  namespace
  {
    bool is_zero(const std::string &expression)
    {
      for (const auto &part : Utilities::split_string_list(expression, ';'))
        if (part != "0")
          return false;
      return true;
    }

    double domain_size(const FluidParameters &p)
    {
      if (p.mesh_type == FluidMeshType::box)
        return norm(p.upper_corner - p.lower_corner);
      if (p.mesh_type == FluidMeshType::cylinder)
        return 2. * (p.cylinder_radius + p.cylinder_half_length);
      return 1.;
    }

  } // namespace

  FluidCoefficients coefficients_from_prm(const FluidParameters &p)
  {
    const auto   c = p.constant_map();
    const double L = domain_size(p);
    FluidCoefficients k;
    if (!p.pure_fluid() && Utilities::trim(p.porosity) != "1")
      k.porosity = std::make_shared<ParsedFunction>(p.porosity, 1, 1, c, L);
    if (!is_zero(p.solid_velocity))
      k.solid_velocity = std::make_shared<ParsedFunction>(p.solid_velocity, 3, 3, c, L);
    if (!is_zero(p.momentum_source))
      k.momentum_source = std::make_shared<ParsedFunction>(p.momentum_source, 3, 3, c, L);
    if (!is_zero(p.mass_source))
      k.mass_source = std::make_shared<ParsedFunction>(p.mass_source, 1, 1, c, L);
    if (!is_zero(p.initial_velocity))
      k.initial_velocity = std::make_shared<ParsedFunction>(p.initial_velocity, 3, 3, c, L);
    for (const auto &bc : p.boundaries)
      k.boundary_velocity.push_back(
        bc.type == BoundaryType::velocity ?
          std::make_shared<ParsedFunction>(bc.velocity, 3, 4, c, L) :
          nullptr);
    return k;
  }

} // namespace sluice
