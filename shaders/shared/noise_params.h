// Parameters of one noise evaluation, shared by the compute shader (push constants) and the
// CPU reference. The meaning of every field is in shaders/common/noise.glsl.
#ifndef PLANET_SHARED_NOISE_PARAMS_H
#define PLANET_SHARED_NOISE_PARAMS_H

#include "shared/gpu_types.h"

GPU_NAMESPACE_BEGIN

// Noise types (NoiseParams.type).
GPU_CONST uint kNoiseSimplex = 0u;  // one octave of N(p)
GPU_CONST uint kNoiseFbm = 1u;
GPU_CONST uint kNoiseRidged = 2u;
GPU_CONST uint kNoiseHybrid = 3u;
GPU_CONST uint kNoiseHetero = 4u;
GPU_CONST uint kNoiseCascade = 5u;
GPU_CONST uint kNoiseCraters = 6u;  // impact craters of many sizes (airless bodies)
GPU_CONST uint kNoiseDamped = 7u;   // fBm whose detail fades where the octaves before are steep
GPU_CONST uint kNoiseEroded = 8u;   // fBm base carved by gullies running down its slope
GPU_CONST uint kNoiseFaults = 9u;   // random great-circle faults (seed 000), summed per point
GPU_CONST uint kNoiseMpd = 10u;     // midpoint displacement on the octahedron (seed 000)
GPU_CONST uint kNoiseMpdIco = 11u;  // midpoint displacement on the icosahedron (seed 004)
GPU_CONST uint kNoiseTypeCount = 12u;

// Lattice hashes (NoiseParams.hash).
GPU_CONST uint kNoiseHashFast = 0u;       // ALU-only integer hash of (i, j, k, seed)
GPU_CONST uint kNoiseHashReference = 1u;  // Perlin's permutation table (seed-permuted)

GPU_CONST uint kNoiseMaxOctaves = 32u;
GPU_CONST uint kNoisePermutationSize = 512u;  // 256 entries, stored twice (no index wrap)

// Bindings of the point-evaluation compute shader (set 0).
GPU_CONST uint kNoiseBindingPoints = 0u;       // vec4[count], w unused (one aligned load per point)
GPU_CONST uint kNoiseBindingValues = 1u;       // float[count]
GPU_CONST uint kNoiseBindingPermutation = 2u;  // uint[kNoisePermutationSize]
GPU_CONST uint kNoiseWorkgroupSize = 256u;

struct NoiseParams {
  uint type;           // kNoise*
  uint octaves;        // 1..kNoiseMaxOctaves (mpd, mpd_ico: subdivision levels; faults: 1)
  uint hash;           // kNoiseHash*
  uint seedMix;        // the seed after noiseSeedMix(), so the fast hash needs no per-point setup
  float lacunarity;    // L: octave i samples p * L^i
  float octaveWeight;  // L^-H: octave i is weighted by octaveWeight^i (pow computed once, on the CPU)
  float offset;        // ridged / hybrid / hetero / cascade offset; craters: rim perturbation;
                       // eroded: base octaves (floor, at least 1); faults: transition width (radians)
  float gain;          // ridged feedback gain; damped: slope damping (k = gain / 16); eroded: gully depth;
                       // mpd multifractal: k
  uint count;          // points to evaluate (GPU only)
  uint firstIndex;     // index of the first point of this dispatch (GPU only)
  float lastOctaveWeight;  // (0, 1]: the last of `octaves` counts this much (1: fully), the octave fade
  uint elements;           // faults: the number of faults; mpd, mpd_ico: 1 multifractal, 0 plain; else 0
};
GPU_ASSERT_SIZE(NoiseParams, 48)

GPU_NAMESPACE_END

#endif
