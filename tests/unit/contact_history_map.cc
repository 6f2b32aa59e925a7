// The tangential histories' hash table (contact_history_map.h) keeps what a
// std::unordered_map keeps: after random inserts and overwrites (pair keys of
// neighbouring ids, wall keys on the same ids, the table growing many times)
// every key finds its last value (keys that share their home slot too), absent keys find nothing, iteration visits
// each entry once, and clear() empties it for the next rebuild while the
// table still works.

#include <sluice/dem/contact_history_map.h>

#include "check.h"

#include <cstdio>
#include <map>
#include <random>
#include <tuple>

using namespace sluice;
using sluice::unit::check;

namespace
{
  using Reference = std::map<std::tuple<std::uint64_t, std::uint64_t, bool>, Vec3>;

  ContactHistoryKey random_key(std::mt19937_64 &rng)
  {
    // Ids of a bed of 20,000 particles: a pair's ids lie close together and
    // a particle has a wall contact as well as pair contacts.
    const std::uint64_t a = rng() % 20000;
    if (rng() % 8 == 0)
      return {a, rng() % 6, true};
    return {a, a + 1 + rng() % 300, false};
  }

  /// Every reference entry found with its value, and nothing else in the table.
  void compare(const ContactHistoryMap &map, const Reference &reference, const char *when)
  {
    unsigned int wrong = 0;
    for (const auto &[k, h] : reference)
      {
        const auto it = map.find({std::get<0>(k), std::get<1>(k), std::get<2>(k)});
        wrong += it == map.end() || !(it->second.x == h.x && it->second.y == h.y &&
                                      it->second.z == h.z);
      }
    std::size_t visited = 0;
    for (const auto &[key, h] : map)
      {
        ++visited;
        wrong += reference.count({key.first, key.second, key.wall}) != 1;
      }
    std::printf("%s: %zu entries, %u wrong\n", when, map.size(), wrong);
    check(wrong == 0, "entries found with another value, or not found", wrong, 0);
    check(visited == reference.size(), "entries visited by iteration", visited, reference.size());
    check(map.size() == reference.size(), "size()", map.size(), reference.size());
  }
} // namespace

int main()
{
  std::mt19937_64   rng(2026);
  ContactHistoryMap map;
  Reference         reference;
  check(map.find({1, 2, false}) == map.end(), "a key found in an empty table", 1, 0);
  for (unsigned int round = 0; round < 3; ++round)
    {
      for (unsigned int n = 0; n < 60000; ++n)
        {
          const ContactHistoryKey key = random_key(rng);
          const Vec3 h(static_cast<double>(n), -1e-3 * round, 1e-7 * (key.first % 7));
          map[key] = h; // an insert, or an overwrite of a repeated key
          reference[{key.first, key.second, key.wall}] = h;
        }
      // Keys built to share their home slot: (a, w + 1, pair) and (a, w,
      // wall) hash alike, so only the full comparison of keys tells them apart.
      for (std::uint64_t a = 0; a < 2000; ++a)
        for (std::uint64_t w = 0; w < 3; ++w)
          {
            const Vec3 h_pair(1. + a, 2. + w, 3.), h_wall(-1. - a, -2. - w, -3.);
            map[{a, w + 1, false}] = h_pair;
            map[{a, w, true}]      = h_wall;
            reference[{a, w + 1, false}] = h_pair;
            reference[{a, w, true}]      = h_wall;
          }
      compare(map, reference, "filled");

      // Keys absent from the reference are absent from the table, and
      // reading one through operator[] inserts a zero history.
      unsigned int found_absent = 0;
      for (unsigned int n = 0; n < 10000; ++n)
        {
          const ContactHistoryKey key{30000 + rng() % 1000, rng(), n % 2 == 0};
          found_absent += map.find(key) != map.end();
        }
      check(found_absent == 0, "absent keys found", found_absent, 0);
      const Vec3 fresh = map[{99999, 5, true}];
      reference[{99999, 5, true}] = Vec3();
      check(fresh.x == 0. && fresh.y == 0. && fresh.z == 0., "a new key's history is zero",
            norm(fresh), 0.);
      compare(map, reference, "after operator[] on a new key");

      map.clear();
      reference.clear();
      check(map.empty() && map.begin() == map.end(), "empty after clear()", map.size(), 0);
      check(map.find({0, 1, false}) == map.end(), "a key found after clear()", 1, 0);
    }
  return sluice::unit::failures == 0 ? 0 : 1;
}
