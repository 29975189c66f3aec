// Planetary rings (engine/render/ring_pass.*): the ring's parameters as the shaders read them,
// the per-frame block of ring.vert / ring.frag, and the test evaluation shader's push
// constants. The model itself is in shaders/common/rings.glsl.
//
// Frames: the ring lies in the body frame's equatorial plane z = 0, centred on the origin.
// Positions reach the GPU relative to the camera (camera-relative body frame), so no float
// ever has to hold a body-frame point next to a small offset.
#ifndef PLANET_SHARED_RING_PARAMS_H
#define PLANET_SHARED_RING_PARAMS_H

#include "shared/eclipse_params.h"
#include "shared/gpu_types.h"
#include "shared/sky_params.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kRingBindingUniforms = 0u;  // uniform RingUniforms (set 0, vertex + fragment)
// The ringed body's air (ring_air.frag only: ring.frag built with RING_AIR), fragment stage:
GPU_CONST uint kRingBindingTransmittance = 1u;       // sampler2D: the body's transmittance table
GPU_CONST uint kRingBindingMultipleScattering = 2u;  // sampler2D: the body's multiple-scattering table
// Fragments less opaque than this are discarded: they write neither colour nor depth, so the
// gaps and the faint edges leave the sky (and what a nearer atmosphere composes over it) as it is.
GPU_CONST float kRingMinAlpha = 1.0f / 512.0f;
// Steps of the march through the ringed body's air in front of a ring fragment (ring_air.frag;
// as many as a sky-view texel's ray, kSkyViewSteps, spends on a whole ray).
GPU_CONST uint kRingAirSteps = 24u;

// The annulus is drawn as kRingSegments quads between a polygon inside the inner circle and
// one around the outer circle; the fragment shader finds each pixel's exact radius, so the
// polygon only has to cover the disc and its edges are never seen.
GPU_CONST uint kRingSegments = 512u;
GPU_CONST uint kRingVertexCount = kRingSegments * 6u;  // two triangles per segment, no index buffer

GPU_CONST uint kRingMaxOctaves = 16u;
GPU_CONST uint kRingMaxGaps = 4u;
// The opacity fades to 0 over this share of the ring's width at both edges.
GPU_CONST float kRingEdgeFade = 0.02f;
// Slant paths are at most 1 / kRingMinSlantCosine times the ring's thickness (grazing views
// and a sun in the ring plane would otherwise divide by 0).
GPU_CONST float kRingMinSlantCosine = 0.001f;

// One ring. C++ builds it with planet::ringGpuParams (engine/reference/ring_density.h).
struct RingParams {
  vec4 radii;      // x: inner radius (m), y: outer radius (m), z: 1 / (outer − inner), w: casting body's radius (m)
  vec4 colour;     // rgb: linear albedo of the particles, w: overall opacity scale in [0, 1]
  vec4 variation;  // rgb: the second albedo the colour noise mixes in, w: sun angular radius (rad)
  uint seedMix;    // lowbias32(seed ^ 0x9e3779b9): the description's seed, its bits spread
  uint octaves;    // of the opacity noise, 1 .. kRingMaxOctaves
  uint gapCount;   // 0 .. kRingMaxGaps
  uint pad0;
  vec4 gaps[kRingMaxGaps];  // x: centre (ring coordinate u), y: half width (u), z: depth (share removed), w: unused
};
GPU_ASSERT_SIZE(RingParams, 128)

// The ring pass's per-frame block (one copy per frame slot).
struct RingUniforms {
  mat4 relativeToClip;  // camera-relative body-frame position (w = 1) → clip (reversed Z, infinite far)
  mat4 clipToRelative;  // its inverse: a pixel's view ray, camera-relative body frame
  vec4 camera;          // xyz: camera position in the body frame (m), w: +1 on the sun's side of the plane, else −1
  vec4 sun;             // xyz: unit vector toward the sun (body frame), w: sun irradiance (gpu::kSunIrradiance units)
  vec4 viewport;        // x: 1 / width, y: 1 / height (pixels), z: fill light (share of the irradiance), w: unused
  RingParams ring;
  EclipseParams eclipse;  // the other bodies of a scene, which hide the sun from the ring (common/eclipse.glsl)
  // The ringed body's atmosphere (ring_air.frag), its sun irradiance and disc for this frame;
  // radii.w = 0 without air.
  AtmosphereParams atmosphere;
  vec4 air;  // x: camera altitude above the body's radius (m), y: the ground sphere (m above the radius) that
             // ends a ray, z, w: unused
};
GPU_ASSERT_SIZE(RingUniforms, 304 + 272 + 112 + 16)

// ring_eval.comp (tests): evaluates the shared functions at `count` queries.
GPU_CONST uint kRingEvalWorkgroupSize = 64u;
GPU_CONST uint kRingEvalBindingParams = 0u;   // RingParams (storage, read)
GPU_CONST uint kRingEvalBindingQueries = 1u;  // vec4[count] (storage, read)
GPU_CONST uint kRingEvalBindingResults = 2u;  // vec4[count] (storage, written)
GPU_CONST uint kRingEvalSample = 0u;          // query x: u, y: footprint → result ringSample(u, footprint)
// query xyz: point (body frame), the sun in the push → x: ringShadow, y: ringPlanetShadow
GPU_CONST uint kRingEvalShadow = 1u;
GPU_CONST uint kRingEvalSlant = 2u;  // query x: alpha, y: cosine → result x: ringSlantOpacity
struct RingEvalPush {
  vec4 sun;    // xyz: toward the sun (kRingEvalShadow)
  uint count;  // queries
  uint mode;   // kRingEvalSample, kRingEvalShadow or kRingEvalSlant
  uint pad0;
  uint pad1;
};
GPU_ASSERT_SIZE(RingEvalPush, 32)

GPU_NAMESPACE_END

#endif
