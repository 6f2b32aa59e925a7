#pragma once
// The line every validation scene ends with, read by tests, scripts/validate
// and doc/validation.md: its error against the reference and its wall time.

#include <iomanip>
#include <ostream>
#include <string>

namespace sluice
{
  /// 'result: <name> value=.. reference=.. error=.. wall_s=..' (the numbers in
  /// the stream's precision, the wall time in 4 digits).
  inline void write_result_line(std::ostream &out, const std::string &name, const double value,
                                const double reference, const double error, const double wall_s)
  {
    const std::streamsize precision = out.precision();
    out << "result: " << name << " value=" << value << " reference=" << reference
        << " error=" << error << std::setprecision(4) << " wall_s=" << wall_s
        << std::setprecision(precision) << "\n";
  }
} // namespace sluice
