#pragma once
// The tangential histories between two neighbour-list builds, keyed by the
// particle ids of the contact (neighbour_list.h collects them before a
// rebuild and looks each listed pair up after it; the MPI exchange and the
// checkpoint read and fill them too).
//
// An open-addressing hash table with linear probing in one contiguous array:
// std::unordered_map allocated a node per contact at every rebuild and
// chased a pointer per lookup, which cost ~15% of the settle scene's run at
// N = 100,000 (doc/performance.md). Only the operations the DEM uses are
// here: insert-or-find, find, iteration, clear. Which history a key finds
// does not depend on the table's layout, so the results are those of any
// other map.

#include <sluice/core/vector3.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace sluice
{
  /// A contact's key, in the frame of the particle with the smaller id (the
  /// displacement of that particle relative to the other). Wall contacts use
  /// (particle id, wall index) with the wall flag.
  struct ContactHistoryKey
  {
    std::uint64_t first, second;
    bool          wall;
    bool operator==(const ContactHistoryKey &o) const
    {
      return first == o.first && second == o.second && wall == o.wall;
    }
  };

  class ContactHistoryMap
  {
  public:
    using value_type = std::pair<ContactHistoryKey, Vec3>;

    /// A slot whose key has this first id is empty (no particle id comes
    /// near it), so that a probe reads one slot, not a flag array besides.
    static constexpr std::uint64_t empty_id = ~std::uint64_t(0);

    /// Walks the occupied slots (in table order).
    template <typename Entry>
    class Iterator
    {
    public:
      Iterator(Entry *slot, Entry *end)
        : slot(slot), end(end)
      {
        skip_empty();
      }
      Entry &operator*() const { return *slot; }
      Entry *operator->() const { return slot; }
      Iterator &operator++()
      {
        ++slot;
        skip_empty();
        return *this;
      }
      bool operator==(const Iterator &o) const { return slot == o.slot; }
      bool operator!=(const Iterator &o) const { return slot != o.slot; }

    private:
      void skip_empty()
      {
        while (slot != end && slot->first.first == empty_id)
          ++slot;
      }
      Entry *slot, *end;
    };
    using iterator       = Iterator<value_type>;
    using const_iterator = Iterator<const value_type>;

    /// The history stored under the key; a zero one inserted if there is none.
    /// (key.first must not be empty_id.)
    Vec3 &operator[](const ContactHistoryKey &key);

    const_iterator find(const ContactHistoryKey &key) const;
    iterator       find(const ContactHistoryKey &key);

    iterator       begin() { return make_iterator(0); }
    iterator       end() { return make_iterator(slots.size()); }
    const_iterator begin() const { return make_iterator(0); }
    const_iterator end() const { return make_iterator(slots.size()); }

    std::size_t size() const { return n_entries; }
    bool        empty() const { return n_entries == 0; }
    /// Empties the table and keeps its memory for the next rebuild.
    void        clear();

  private:
    /// Where the key sits, or the empty slot that ends its probe sequence.
    std::size_t slot_of(const ContactHistoryKey &key) const;
    /// Doubles the table (at least 16 slots) and reinserts the entries.
    void        grow();

    iterator make_iterator(const std::size_t s)
    {
      return {slots.data() + s, slots.data() + slots.size()};
    }
    const_iterator make_iterator(const std::size_t s) const
    {
      return {slots.data() + s, slots.data() + slots.size()};
    }

    std::vector<value_type> slots;
    std::size_t             n_entries = 0;
    unsigned int              shift     = 64; // 64 - log2(number of slots)
  };
} // namespace sluice
