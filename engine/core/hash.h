// Small integer mixing shared by deterministic generators (seeded tables, test points).
#pragma once

#include <cstdint>

namespace planet {

// SplitMix64's output function (Steele, Lea, Flood 2014): spreads every bit of x over all 64.
inline uint64_t splitMix64Mix(uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace planet
