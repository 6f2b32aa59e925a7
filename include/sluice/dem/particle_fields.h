#pragma once
// Named per-particle fields: every quantity a particle carries beyond the
// DEM's own state (a coupled scene's frozen fluid forces, the impulse it owes
// the fluid, ...) is declared once here, with its size and what it takes part
// in. The registry then gives
//   - its offset in each particle's contiguous block of doubles
//     (ParticleStorage::extra, read in the hot loops through that offset);
//   - the ParticleHandler properties that travel with a particle changing
//     rank (the fields that migrate; ParticleExchange lays them out);
//   - the arrays the particle snapshots write (the fields marked output);
//   - what a checkpoint saves, and its signature ('name:size' of each).
// A field that does not migrate starts at zero on the rank that receives the
// particle.

#include <stdexcept>
#include <string>
#include <vector>

namespace sluice
{
  struct ParticleField
  {
    std::string  name;
    unsigned int size   = 1; // doubles
    unsigned int offset = 0; // in the particle's block
    bool         migrates = true, output = false, checkpoint = true;
  };

  class ParticleFieldRegistry
  {
  public:
    /// What a field takes part in besides its storage.
    struct Use
    {
      bool migrates = true, output = false, checkpoint = true;
    };

    /// Declares a field and returns its offset. Throws std::logic_error for a
    /// name declared twice or a field of size 0 (a programming error).
    unsigned int declare(const std::string &name, const unsigned int size, const Use use)
    {
      if (size == 0 || find(name))
        throw std::logic_error("ParticleFieldRegistry: bad or repeated field '" + name + "'");
      fields_.push_back({name, size, doubles, use.migrates, use.output, use.checkpoint});
      doubles += size;
      return fields_.back().offset;
    }

    unsigned int                      doubles_per_particle() const { return doubles; }
    const std::vector<ParticleField> &fields() const { return fields_; }

    const ParticleField *find(const std::string &name) const
    {
      for (const auto &f : fields_)
        if (f.name == name)
          return &f;
      return nullptr;
    }

    /// 'name:size' of every field a checkpoint saves, in order.
    std::string signature() const
    {
      std::string s;
      for (const auto &f : fields_)
        if (f.checkpoint)
          s += (s.empty() ? "" : " ") + f.name + ":" + std::to_string(f.size);
      return s.empty() ? "none" : s;
    }

  private:
    std::vector<ParticleField> fields_;
    unsigned int               doubles = 0;
  };
} // namespace sluice
