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

// Shading attributes at `offsetPlanet` (planet frame, metres from the nadir point of a sphere
// of `radius`): face Δa, Δb of the patch textures, colour noise, sin(latitude) (the layout of
// kRenderBindingAttributes). `nadir` is the nadir direction and `refMinusNadir` the patch
// reference point minus it (unit sphere, planet frame).
vec4 terrainSurfaceAttributes(vec3 offsetPlanet, real radius, vec3 nadir, vec3 refMinusNadir, vec4 faceNormal,
                              vec4 faceAxisA, vec4 faceAxisB, real bandFrequency) {
  // Planet-frame direction, good to float precision (colour and latitude only).
  vec3 directionPlanet = nadir + offsetPlanet / radius;
  // Colour noise: four fBm octaves from bandWavelengthM down (tens of km to a few km). It frays
  // the colour-band edges and picks the vegetation (terrain.frag); float is enough here.
  NoiseParams band;
  band.type = kNoiseFbm;
  band.octaves = 4u;
  band.hash = kNoiseHashFast;
  band.seedMix = 0x5bd1e995u;
  band.lacunarity = 2.0f;
  band.octaveWeight = 0.5f;
  band.offset = 0.0f;
  band.gain = 0.0f;
  band.count = 0u;
  band.firstIndex = 0u;
  band.lastOctaveWeight = 1.0f;
  band.elements = 0u;
  real bandNoise = evaluateFbm(band, directionPlanet * (radius * bandFrequency));
  vec2 face = patchFaceOffset(offsetPlanet / radius - refMinusNadir, faceNormal, faceAxisA, faceAxisB);
  return vec4(face.x, face.y, bandNoise, normalize(directionPlanet).z);
}

#endif
