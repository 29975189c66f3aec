// Eclipses (issue 23, point 1): the bodies that can hide the sun from a body's surface, its air
// and its rings, as the shaders read them (shaders/common/eclipse.glsl). C++ fills them with
// planet::eclipseGpuParams (engine/reference/eclipse.h) each frame.
//
// Positions are relative to the camera, in the frame of the pass that reads them (the terrain's
// and sky's local frame, the ring's body frame), so that no float holds a scene-size position
// next to a small offset.
#ifndef PLANET_SHARED_ECLIPSE_PARAMS_H
#define PLANET_SHARED_ECLIPSE_PARAMS_H

#include "shared/gpu_types.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kEclipseMaxOccluders = 8u;  // = kMaxSceneBodies (planet/scene_description.h)

struct EclipseParams {
  vec4 occluders[kEclipseMaxOccluders];  // xyz: the occluding sphere's centre minus the camera (m), w: its radius (m)
  // rgb: the share of the sun's irradiance that the occluder's air bends into its shadow, per
  // share of the sun it covers (refractedIntoShadow, engine/reference/eclipse.h; 0 without air), w: unused
  vec4 refracted[kEclipseMaxOccluders];
  vec4 sun;  // x: the sun's angular radius (rad), y: occluder count, z, w: unused
};
GPU_ASSERT_SIZE(EclipseParams, 272)

// eclipse_eval.comp (tests): evaluates the shared functions at `count` queries.
GPU_CONST uint kEclipseEvalWorkgroupSize = 64u;
GPU_CONST uint kEclipseEvalBindingParams = 0u;   // EclipseParams (storage, read)
GPU_CONST uint kEclipseEvalBindingQueries = 1u;  // vec4[count] (storage, read)
GPU_CONST uint kEclipseEvalBindingResults = 2u;  // vec4[count] (storage, written)
GPU_CONST uint kEclipseEvalCovered = 0u;  // query x: k, y: s → result x: sunDiscCovered(k, s)
// query xyz: a point minus the camera, the sun in the push → result x: eclipseSunVisibleRefracted, yzw: refracted
GPU_CONST uint kEclipseEvalVisible = 1u;
struct EclipseEvalPush {
  vec4 sun;    // xyz: toward the sun (kEclipseEvalVisible)
  uint count;  // queries
  uint mode;   // kEclipseEvalCovered or kEclipseEvalVisible
  uint pad0;
  uint pad1;
};
GPU_ASSERT_SIZE(EclipseEvalPush, 32)

GPU_NAMESPACE_END

#endif
