// Wall motion and the displacement test of the neighbour list (see the header).

#include <sluice/dem/wall_set.h>

#include <deal.II/base/function_parser.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <memory>

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
  } // namespace

  WallSet::WallSet(const std::vector<PlaneWall> &walls, const PeriodicBox &box,
                   const std::string &file_name)
    : box_lower_(box.lower), box_upper_(box.upper)
  {
    for (const PlaneWall &w : walls)
      {
        Plane plane;
        plane.point    = w.point;
        plane.normal   = w.normal;
        plane.material = w.material;
        planes_.push_back(plane);
        names_.push_back(w.name);
        velocity_.push_back(
          vector_of_time(w.velocity, "walls/plane velocities", w.name, file_name));
        angular_velocity_.push_back(
          vector_of_time(w.angular_velocity, "walls/plane angular velocities", w.name, file_name));
        any_moving_ = any_moving_ || velocity_.back() || angular_velocity_.back();
      }
    // The velocities at the start, for the contacts before the first step.
    for (unsigned int w = 0; w < size(); ++w)
      {
        if (velocity_[w])
          planes_[w].velocity = velocity_[w](0.);
        if (angular_velocity_[w])
          planes_[w].angular_velocity = angular_velocity_[w](0.);
      }
    mark_list_build();
  }

  void WallSet::move(const double t, const double dt)
  {
    if (!any_moving_)
      return;
    const double t_mid = t + 0.5 * dt;
    for (unsigned int w = 0; w < size(); ++w)
      {
        Plane &plane = planes_[w];
        if (velocity_[w])
          {
            plane.velocity = velocity_[w](t_mid);
            plane.point += dt * plane.velocity;
          }
        if (angular_velocity_[w])
          {
            plane.angular_velocity = angular_velocity_[w](t_mid);
            // The normal turns with the wall; a fixed step keeps it unit to round-off.
            plane.normal = rotated(plane.normal, dt * plane.angular_velocity);
            plane.normal = (1. / norm(plane.normal)) * plane.normal;
          }
      }
  }

  double WallSet::max_displacement_since_build() const
  {
    if (!any_moving_)
      return 0.;
    // The signed distance to a plane is affine in x, so the change between two
    // positions of a plane is largest at a corner of the box.
    double largest = 0.;
    for (unsigned int w = 0; w < size(); ++w)
      for (unsigned int c = 0; c < 8; ++c)
        {
          const Vec3 x(c & 1 ? box_upper_.x : box_lower_.x, c & 2 ? box_upper_.y : box_lower_.y,
                       c & 4 ? box_upper_.z : box_lower_.z);
          const double now    = dot(x - planes_[w].point, planes_[w].normal);
          const double before = dot(x - at_build_[w].point, at_build_[w].normal);
          largest             = std::max(largest, std::abs(now - before));
        }
    return largest;
  }

  void WallSet::mark_list_build()
  {
    at_build_ = planes_;
  }

  std::vector<double> WallSet::state() const
  {
    std::vector<double> numbers;
    for (const auto *set : {&planes_, &at_build_})
      for (const Plane &plane : *set)
        for (const Vec3 *v : {&plane.point, &plane.normal, &plane.velocity, &plane.angular_velocity})
          numbers.insert(numbers.end(), {v->x, v->y, v->z});
    return numbers;
  }

  void WallSet::set_state(const std::vector<double> &numbers)
  {
    std::size_t k = 0;
    for (auto *set : {&planes_, &at_build_})
      for (Plane &plane : *set)
        for (Vec3 *v : {&plane.point, &plane.normal, &plane.velocity, &plane.angular_velocity})
          {
            *v = Vec3(numbers.at(k), numbers.at(k + 1), numbers.at(k + 2));
            k += 3;
          }
  }
} // namespace sluice
