#pragma once
// Declaring .prm entries so that --print-parameters shows, for each, its default,
// unit (in brackets at the start of the documentation), range and meaning.

#include <sluice/core/vector3.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace sluice
{
  /// Declares an entry whose documentation ends with the values it accepts.
  /// 'allowed' replaces the pattern's own description when it is not empty.
  void declare(dealii::ParameterHandler &prm, const std::string &name,
               const std::string &default_value, const dealii::Patterns::PatternBase &pattern,
               const std::string &documentation, const std::string &allowed = "");

  /// The largest double, as the upper end of open ranges.
  double unbounded();

  /// An entry of three comma-separated numbers (declared with a pattern that
  /// checks them) as a vector.
  Vec3 get_vector(dealii::ParameterHandler &prm, const std::string &name);
} // namespace sluice
