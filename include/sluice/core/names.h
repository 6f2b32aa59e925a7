#pragma once
// The .prm name of every enumerated choice, in one table per enum: the
// declaration of an entry takes its Selection from the table, reading a
// scene turns a name into the value, and output prints the name back, so a
// choice is spelled in exactly one place.

#include <sluice/core/coupling_parameters.h>
#include <sluice/core/fluid_parameters.h>
#include <sluice/core/scene_parameters.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sluice
{
  template <typename Enum>
  class NameTable
  {
  public:
    NameTable(std::initializer_list<std::pair<Enum, const char *>> entries) : entries(entries) {}

    const char *name(const Enum value) const
    {
      for (const auto &[v, n] : entries)
        if (v == value)
          return n;
      return "?";
    }

    /// Throws std::invalid_argument naming the allowed names.
    Enum value(const std::string &name) const
    {
      for (const auto &[v, n] : entries)
        if (name == n)
          return v;
      throw std::invalid_argument("unknown name '" + name + "'; allowed: " + selection());
    }

    /// 'a|b|c' for a deal.II Selection pattern, leaving out 'except'.
    std::string selection(const std::vector<Enum> &except = {}) const
    {
      std::string all;
      for (const auto &[v, n] : entries)
        if (std::find(except.begin(), except.end(), v) == except.end())
          all += (all.empty() ? "" : "|") + std::string(n);
      return all;
    }

  private:
    std::vector<std::pair<Enum, const char *>> entries;
  };

  /// The table of one enum (core/names.cc).
  template <typename Enum>
  const NameTable<Enum> &names();

  template <typename Enum>
  std::string name_of(const Enum value)
  {
    return names<Enum>().name(value);
  }

  template <typename Enum>
  Enum value_of(const std::string &name)
  {
    return names<Enum>().value(name);
  }

  template <> const NameTable<Physics> &names();
  template <> const NameTable<NormalContactModel> &names();
  template <> const NameTable<RollingResistanceModel> &names();
  template <> const NameTable<InsertionMethod> &names();
  template <> const NameTable<IfOutputExists> &names();
  template <> const NameTable<ValidationCase> &names();
  template <> const NameTable<VansFormulation> &names();
  template <> const NameTable<PorousDrag> &names();
  template <> const NameTable<FluidMeshType> &names();
  template <> const NameTable<BoundaryType> &names();
  template <> const NameTable<TimeIntegration> &names();
  template <> const NameTable<LinearPreconditioner> &names();
  template <> const NameTable<RefinementIndicator> &names();
  template <> const NameTable<FluidValidationCase> &names();
  template <> const NameTable<CouplingFormulation> &names();
  template <> const NameTable<DragClosure> &names();
  template <> const NameTable<ProjectionScheme> &names();
  template <> const NameTable<CouplingValidationCase> &names();
} // namespace sluice
