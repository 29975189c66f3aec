// The reference hash's permutation table: Ken Perlin's 256-entry table (as used by his
// improved noise and by Gustavson's simplex reference code) for seed 0, a seeded shuffle of
// it for other seeds. Stored twice (512 entries) so that nested lookups need no wrap.
#pragma once

#include <array>
#include <cstdint>

#include "shared/noise_params.h"

namespace planet::noise {

using PermutationTable = std::array<uint32_t, gpu::kNoisePermutationSize>;

// Seed 0: Perlin's table, so values equal the published reference implementation. Other
// seeds: a Fisher-Yates shuffle of it driven by SplitMix64(seed), identical on every platform.
const PermutationTable& permutationTable(uint32_t seed);

}  // namespace planet::noise
