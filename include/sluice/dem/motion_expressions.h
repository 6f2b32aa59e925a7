#pragma once
// A wall's motion as the .prm gives it: vectors as three muparser expressions
// in the time t, and the rotation a step applies.

#include <sluice/core/vector3.h>

#include <functional>
#include <string>

namespace sluice
{
  /// A vector function of t from 'fx(t), fy(t), fz(t)' (muparser syntax, the
  /// constant pi known; commas inside parentheses belong to the expression),
  /// or an empty function for an empty text. Throws InputError naming the
  /// entry and the wall when the text does not parse.
  std::function<Vec3(double)> vector_of_time(const std::string &text, const std::string &entry,
                                             const std::string &wall,
                                             const std::string &file_name);

  /// v rotated by the angle |a| about the axis a (Rodrigues' formula).
  Vec3 rotated(const Vec3 &v, const Vec3 &a);
} // namespace sluice
