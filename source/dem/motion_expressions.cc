// Wall motions from expressions in t (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/dem/motion_expressions.h>

#include <deal.II/base/function_parser.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

namespace sluice
{
  namespace
  {
    /// Splits "a, max(b, c), d" at the commas outside parentheses.
    std::vector<std::string> split_components(const std::string &text)
    {
      std::vector<std::string> parts(1);
      int                      depth = 0;
      for (const char ch : text)
        {
          depth += (ch == '(') - (ch == ')');
          if (ch == ',' && depth == 0)
            parts.emplace_back();
          else
            parts.back() += ch;
        }
      return parts;
    }
  } // namespace

  /// A vector function of t from three expressions (muparser syntax, the
  /// constant pi known), or an empty function for an empty text.
  std::function<Vec3(double)> vector_of_time(const std::string &text, const std::string &entry,
                                             const std::string &wall,
                                             const std::string &file_name)
  {
    if (text.find_first_not_of(" \t") == std::string::npos)
      return {};
    const std::vector<std::string> parts = split_components(text);
    const std::string where = "error in '" + file_name + "': entry '" + entry + "' for wall '" +
                              wall + "' = '" + text + "'";
    if (parts.size() != 3)
      throw InputError(where + " has " + std::to_string(parts.size()) +
                       " components; expected three expressions in t, 'fx(t), fy(t), fz(t)'");
    auto f = std::make_shared<dealii::FunctionParser<1>>(3);
    // deal.II prints muparser's diagnosis to std::cerr before it throws; the
    // message below says the same in one line.
    std::ostringstream muparser_text;
    std::streambuf    *cerr_buffer = std::cerr.rdbuf(muparser_text.rdbuf());
    try
      {
        f->initialize("t", parts, {{"pi", M_PI}});
        // Each component is parsed at its first evaluation.
        for (unsigned int c = 0; c < 3; ++c)
          (void)f->value(dealii::Point<1>(0.), c);
        std::cerr.rdbuf(cerr_buffer);
      }
    catch (const std::exception &e)
      {
        std::cerr.rdbuf(cerr_buffer);
        const std::string what = e.what(), key = "The parser said: ";
        const std::size_t at = what.find(key);
        const std::string why =
          at == std::string::npos ? "" :
                                    ": " + what.substr(at + key.size(),
                                                       what.find('\n', at) - at - key.size());
        throw InputError(where + " does not parse as three expressions in t" + why);
      }
    return [f](const double t) {
      const dealii::Point<1> x(t);
      return Vec3(f->value(x, 0), f->value(x, 1), f->value(x, 2));
    };
  }

  /// Rotates v by the angle |a| about the axis a (Rodrigues).
  Vec3 rotated(const Vec3 &v, const Vec3 &a)
  {
    const double angle = norm(a);
    if (!(angle > 0.))
      return v;
    const Vec3   k = (1. / angle) * a;
    const double c = std::cos(angle), s = std::sin(angle);
    return c * v + s * cross(k, v) + (1. - c) * dot(k, v) * k;
  }
} // namespace sluice
