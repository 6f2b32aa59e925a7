#pragma once
// The assertion the unit tests share: a failed check prints what was checked,
// the value found and the value expected, and is counted; main() returns
// non-zero if any failed.

#include <cstdio>

namespace sluice::unit
{
  inline int failures = 0;

  inline void check(const bool ok, const char *what, const double got, const double expected)
  {
    if (!ok)
      {
        std::printf("FAILED: %s: got %.17g, expected %.17g\n", what, got, expected);
        ++failures;
      }
  }
} // namespace sluice::unit
