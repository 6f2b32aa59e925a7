#pragma once
// The small records a scene keeps in a checkpoint besides the solvers' state
// (when the next output is due, the series index, a probe's measurements):
// lines 'key value...', numbers written in the shortest form that comes back
// exactly.

#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace sluice
{
  /// The shortest text that reads back as exactly v (15 to 17 digits).
  inline std::string exact_text(const double v)
  {
    for (const int digits : {15, 16, 17})
      {
        std::ostringstream o;
        o << std::setprecision(digits) << v;
        if (digits == 17 || std::stod(o.str()) == v)
          return o.str();
      }
    return {};
  }

  class SceneRecords
  {
  public:
    SceneRecords() = default;
    explicit SceneRecords(std::vector<std::string> lines) : lines_(std::move(lines)) {}

    void set(const std::string &key, const double value) { set_numbers(key, {value}); }
    void set_numbers(const std::string &key, const std::vector<double> &values)
    {
      std::string line = key;
      for (const double v : values)
        line += ' ' + exact_text(v);
      lines_.push_back(line);
    }
    /// One line 'key text' per entry.
    void add_all(const std::string &key, const std::vector<std::string> &texts)
    {
      for (const auto &t : texts)
        lines_.push_back(key + ' ' + t);
    }

    /// The numbers after the first line with this key (none if there is none).
    std::vector<double> numbers(const std::string &key) const
    {
      std::vector<double> values;
      for (const auto &line : lines_)
        if (line.compare(0, key.size() + 1, key + ' ') == 0 || line == key)
          {
            std::istringstream in(line.substr(key.size()));
            for (double v; in >> v;)
              values.push_back(v);
            break;
          }
      return values;
    }
    double number(const std::string &key, const double fallback) const
    {
      const std::vector<double> v = numbers(key);
      return v.empty() ? fallback : v[0];
    }
    /// The texts of every line with this key, in order.
    std::vector<std::string> all(const std::string &key) const
    {
      std::vector<std::string> texts;
      for (const auto &line : lines_)
        if (line.compare(0, key.size() + 1, key + ' ') == 0)
          texts.push_back(line.substr(key.size() + 1));
      return texts;
    }

    const std::vector<std::string> &lines() const { return lines_; }

  private:
    std::vector<std::string> lines_;
  };
} // namespace sluice
