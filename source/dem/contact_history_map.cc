#include <sluice/dem/contact_history_map.h>

#include <algorithm>

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
    while (used[s] != 0 && !(slots[s].first == key))
      s = (s + 1) & mask;
    return s;
  }

  Vec3 &ContactHistoryMap::operator[](const ContactHistoryKey &key)
  {
    // At most half full, so that a probe ends after a few slots.
    if (2 * (n_entries + 1) > slots.size())
      grow();
    const std::size_t s = slot_of(key);
    if (used[s] == 0)
      {
        used[s]  = 1;
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
    return used[s] != 0 ? make_iterator(s) : end();
  }

  ContactHistoryMap::iterator ContactHistoryMap::find(const ContactHistoryKey &key)
  {
    if (n_entries == 0)
      return end();
    const std::size_t s = slot_of(key);
    return used[s] != 0 ? make_iterator(s) : end();
  }

  void ContactHistoryMap::clear()
  {
    std::fill(used.begin(), used.end(), 0);
    n_entries = 0;
  }

  void ContactHistoryMap::grow()
  {
    std::vector<value_type>   old_slots = std::move(slots);
    std::vector<std::uint8_t> old_used  = std::move(used);
    const std::size_t         n         = std::max<std::size_t>(16, 2 * old_slots.size());
    slots.assign(n, value_type());
    used.assign(n, 0);
    shift = 64;
    for (std::size_t m = n; m > 1; m /= 2)
      --shift;
    for (std::size_t s = 0; s < old_slots.size(); ++s)
      if (old_used[s] != 0)
        {
          const std::size_t t = slot_of(old_slots[s].first);
          used[t]             = 1;
          slots[t]            = old_slots[s];
        }
  }
} // namespace sluice
