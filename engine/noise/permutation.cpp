#include "noise/permutation.h"

#include "core/hash.h"

#include <map>
#include <memory>
#include <mutex>

namespace planet::noise {
namespace {

// Ken Perlin's permutation of 0..255 (Perlin 2002, "Improving Noise"; the same table appears
// in Gustavson 2005). Data, not code: these numbers define the reference noise.
constexpr uint8_t kPerlin[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,  69,  142,
    8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203,
    117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165,
    71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,
    55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,
    18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250,
    124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189,
    28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114,
    67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180,
};

// SplitMix64 (Steele, Lea, Flood 2014): a small, well-mixed, portable generator.
uint64_t splitMix64(uint64_t& state) { return splitMix64Mix(state += 0x9e3779b97f4a7c15ull); }

PermutationTable makeTable(uint32_t seed) {
  uint32_t perm[256];
  for (int i = 0; i < 256; ++i) perm[i] = kPerlin[i];
  if (seed != 0) {
    uint64_t state = seed;
    for (uint32_t i = 255; i > 0; --i) {
      uint32_t j = uint32_t(splitMix64(state) % (i + 1));
      std::swap(perm[i], perm[j]);
    }
  }
  PermutationTable table;
  for (int i = 0; i < 512; ++i) table[i] = perm[i & 255];
  return table;
}

}  // namespace

const PermutationTable& permutationTable(uint32_t seed) {
  // Tables are built once per seed and kept: callers hold references across threads.
  static std::mutex mutex;
  static std::map<uint32_t, std::unique_ptr<PermutationTable>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[seed];
  if (!slot) slot = std::make_unique<PermutationTable>(makeTable(seed));
  return *slot;
}

}  // namespace planet::noise
