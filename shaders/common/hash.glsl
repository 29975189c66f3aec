// The integer hashes of the shared GLSL, written once in the GLSL/C++ common subset (see
// definitions.glsl): included by noise.glsl, rings.glsl and stars.glsl.
//
// The include guard is GLSL's only. In C++ every kernel struct that includes a shared file
// (engine/noise/noise_kernel.h, engine/reference/*) takes these as member functions of its
// own, so each struct needs its own copy, and no struct includes two files that include this.
#if !defined(PLANET_COMMON_HASH_GLSL) || defined(__cplusplus)
#ifndef __cplusplus
#define PLANET_COMMON_HASH_GLSL
#endif

// Chris Wellons' "lowbias32": a bijection of the 32-bit integers with full avalanche (every
// input bit flips each output bit with probability close to 1/2).
uint lowbias32(uint x) {
  uint h = x;
  h ^= h >> 16u;
  h *= 0x7feb352du;
  h ^= h >> 15u;
  h *= 0x846ca68bu;
  h ^= h >> 16u;
  return h;
}

// PCG hash (O'Neill 2014, PCG-RXS-M-XS 32/32; recommended for GPUs by Jarzynski & Olano,
// "Hash Functions for GPU Rendering", JCGT 2020): one LCG step, then a random-shift xorshift,
// a multiply and a final xorshift. A bijection of the 32-bit integers.
uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

#endif
