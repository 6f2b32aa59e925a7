#pragma once
// The fluid's coefficient functions as the .prm writes them: expressions of
// x, y, z, t and the scene's constants, turned into deal.II functions for the
// solver (FluidCoefficients). Used by the fluid scenes and by the coupling.

#include <sluice/core/fluid_parameters.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/function.h>
#include <deal.II/base/function_parser.h>

#include <map>
#include <memory>
#include <string>

namespace sluice
{
  /// A .prm expression of x, y, z, t and the scene's constants; the constants
  /// can be changed between solves (the packed bed's superficial velocity).
  class ParsedFunction : public dealii::Function<3>
  {
  public:
    ParsedFunction(const std::string &expression, const unsigned int n_expressions,
                   const unsigned int n_components, std::map<std::string, double> constants,
                   const double length_scale)
      : dealii::Function<3>(n_components)
      , expression(expression)
      , n_expressions(n_expressions)
      , constants(std::move(constants))
      , step(1e-5 * length_scale)
    {
      rebuild();
    }

    void set_constant(const std::string &name, const double value)
    {
      constants[name] = value;
      rebuild();
    }

    double value(const dealii::Point<3> &x, const unsigned int c) const override
    {
      if (c >= n_expressions)
        return 0.;
      parser->set_time(get_time());
      return parser->value(x, c);
    }

    dealii::Tensor<1, 3> gradient(const dealii::Point<3> &x, const unsigned int c) const override
    {
      if (c >= n_expressions)
        return {};
      parser->set_time(get_time());
      return parser->gradient(x, c);
    }

  private:
    void rebuild();

    std::string                        expression;
    unsigned int                       n_expressions;
    std::map<std::string, double>      constants;
    double                             step;
    std::unique_ptr<dealii::FunctionParser<3>> parser;
  };


  /// The functions of a scene: a null pointer where the expression is zero (or
  /// the porosity one), so that the solver skips the term.
  FluidCoefficients coefficients_from_prm(const FluidParameters &parameters);
} // namespace sluice
