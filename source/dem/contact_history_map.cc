#include <sluice/dem/contact_history_map.h>

#include <algorithm>
#include <cassert>

namespace sluice
{
  std::size_t ContactHistoryMap::slot_of(const ContactHistoryKey &key) const
  {
    // Fibonacci hashing (Knuth, TAOCP 3 §6.4) of the mixed ids: the high bits
    // of the product pick the slot, so ids that differ in their low bits
    // only still spread over the table.
    const std::uint64_t mixed =
      (key.first * 0x9E3779B97F4A7C15ull ^ (key.second + key.wall)) * 0xBF58476D1CE4E5B9ull;
    const std::size_t mask = slots.size() - 1;
    std::size_t       s    = mixed >> shift;
    while (slots[s].first.first != empty_id && !(slots[s].first == key))
      s = (s + 1) & mask;
    return s;
  }

  Vec3 &ContactHistoryMap::operator[](const ContactHistoryKey &key)
  {
    // At most half full, so that a probe ends after a few slots.
    if (2 * (n_entries + 1) > slots.size())
      grow();
    assert(key.first != empty_id);
    const std::size_t s = slot_of(key);
    if (slots[s].first.first == empty_id)
      {
        slots[s] = {key, Vec3()};
        ++n_entries;
      }
    return slots[s].second;
  }

  ContactHistoryMap::const_iterator ContactHistoryMap::find(const ContactHistoryKey &key) const
  {
    if (n_entries == 0)
      return end();
    const std::size_t s = slot_of(key);
    return slots[s].first.first != empty_id ? make_iterator(s) : end();
  }

  ContactHistoryMap::iterator ContactHistoryMap::find(const ContactHistoryKey &key)
  {
    if (n_entries == 0)
      return end();
    const std::size_t s = slot_of(key);
    return slots[s].first.first != empty_id ? make_iterator(s) : end();
  }

  void ContactHistoryMap::clear()
  {
    if (n_entries > 0)
      for (value_type &slot : slots)
        slot.first.first = empty_id;
    n_entries = 0;
  }

  void ContactHistoryMap::grow()
  {
    std::vector<value_type> old_slots = std::move(slots);
    const std::size_t       n         = std::max<std::size_t>(16, 2 * old_slots.size());
    slots.assign(n, value_type({empty_id, 0, false}, Vec3()));
    shift = 64;
    for (std::size_t m = n; m > 1; m /= 2)
      --shift;
    for (const value_type &entry : old_slots)
      if (entry.first.first != empty_id)
        slots[slot_of(entry.first)] = entry;
  }
} // namespace sluice
