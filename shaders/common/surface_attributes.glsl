// The terrain's per-vertex shading attributes, written once in the GLSL/C++ common subset
// (definitions.glsl): the GPU height sources get them in terrain_vertex_surface.glsl, the CPU
// height source (`planet bench --compare`) in engine/reference/terrain_surface_cpu.cpp, both
// through this file. Include it after noise.glsl (C++: noise_kernel.h does).
#ifndef PLANET_COMMON_SURFACE_ATTRIBUTES_GLSL
#define PLANET_COMMON_SURFACE_ATTRIBUTES_GLSL

#include "common/definitions.glsl"

// Face-coordinate offset of a direction from the patch reference point c (DESIGN.md precision
// rule): with δ = d − c small, a − a_c = (δ·A (c·N) − (c·A) δ·N) / ((c·N)(c·N + δ·N)), every
// term a product of small numbers, so the float result keeps its relative precision. The
// face's axes carry c·axis in w (FrameUniforms::faceAxisA/B, faceNormal).
vec2 patchFaceOffset(vec3 delta, vec4 faceNormal, vec4 faceAxisA, vec4 faceAxisB) {
  real cN = faceNormal.w;
  real dN = dot(delta, vec3(faceNormal.x, faceNormal.y, faceNormal.z));
  real denominator = cN * (cN + dN);
  if (cN + dN <= real(0.05f)) return vec2(real(1e30f));  // far round the planet: outside every patch
  real da = dot(delta, vec3(faceAxisA.x, faceAxisA.y, faceAxisA.z)) * cN - faceAxisA.w * dN;
  real db = dot(delta, vec3(faceAxisB.x, faceAxisB.y, faceAxisB.z)) * cN - faceAxisB.w * dN;
  return vec2(da, db) / denominator;
}

// Octaves of the colour noise a vertex spacing can show: those of wavelength at least twice
// the spacing, the last faded in as its wavelength goes from two to four spacings (the octave
// budgets' rule, octave_budget.h), so that vertices far apart do not alias the noise into blobs
// hundreds of km wide from orbit, and the value changes continuously as a point's spacing does.
// Returns the octave count; lastWeight gets the last one's weight.
uint bandOctavesAt(real wavelength, real spacing, uint most, OUT(real) lastWeight) {
  uint octaves = 0u;
  lastWeight = real(1.0f);
  for (uint i = 0u; i < most; ++i) {
    real ratio = wavelength / (real(2.0f) * spacing);
    if (ratio < real(1.0f)) break;
    lastWeight = min(ratio - real(1.0f), real(1.0f));
    octaves = i + 1u;
    wavelength = wavelength * real(0.5f);
  }
  return octaves;
}

// fBm of the colour noise: `octaves` octaves at `frequency` (cycles per metre) and up, the
// last weighted by lastWeight; each has its own seed.
real colourNoise(vec3 pointM, real frequency, uint octaves, real lastWeight, uint seedMix) {
  if (octaves == 0u) return real(0.0f);
  NoiseParams band;
  band.type = kNoiseFbm;
  band.octaves = octaves;
  band.hash = kNoiseHashFast;
  band.seedMix = seedMix;
  band.lacunarity = 2.0f;
  band.octaveWeight = 0.5f;
  band.offset = 0.0f;
  band.gain = 0.0f;
  band.count = 0u;
  band.firstIndex = 0u;
  band.lastOctaveWeight = float(lastWeight);
  band.elements = 0u;
  return evaluateFbm(band, pointM * frequency);
}

// Shading attributes at `offsetPlanet` (planet frame, metres from the nadir point of a sphere
// of `radius`): face Δa, Δb of the patch textures, colour noise, sin(latitude) (the layout of
// kRenderBindingAttributes). `nadir` is the nadir direction and `refMinusNadir` the patch
// reference point minus it (unit sphere, planet frame). spacingM is the vertex's spacing (the
// colour noise keeps the octaves it can show); regionalWeight the weight of the regional noise.
vec4 terrainSurfaceAttributes(vec3 offsetPlanet, real radius, vec3 nadir, vec3 refMinusNadir, vec4 faceNormal,
                              vec4 faceAxisA, vec4 faceAxisB, real bandFrequency, real spacingM,
                              real regionalWeight) {
  // Planet-frame direction, good to float precision (colour and latitude only).
  vec3 directionPlanet = nadir + offsetPlanet / radius;
  vec3 pointM = directionPlanet * radius;
  // Colour noise: four fBm octaves from bandWavelengthM down (tens of km to a few km), as many
  // as the spacing shows. It frays the colour-band edges and picks the vegetation
  // (terrain.frag); float is enough here.
  real lastWeight;
  uint octaves = bandOctavesAt(real(1.0f) / bandFrequency, spacingM, 4u, lastWeight);
  real noise = colourNoise(pointM, bandFrequency, octaves, lastWeight, 0x5bd1e995u);
  // Regional noise: three octaves from 64 band wavelengths (2,560 km on Earth down to 640 km,
  // finer than any vertex spacing), so that the materials vary by region (wet and dry, warm and
  // cold, dark and bright) and not only by latitude and height.
  // Precise: the compute and the vertex-shader sources must shade alike (no fused multiply-add
  // in one stage and not in the other).
  if (regionalWeight > real(0.0f)) {
    PRECISE real regional =
        regionalWeight * colourNoise(pointM, bandFrequency * real(0.015625f), 3u, real(1.0f), 0x2f6b8a13u);
    noise = noise + regional;
  }
  vec2 face = patchFaceOffset(offsetPlanet / radius - refMinusNadir, faceNormal, faceAxisA, faceAxisB);
  return vec4(face.x, face.y, noise, normalize(directionPlanet).z);
}

#endif
