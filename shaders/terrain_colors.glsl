// The planet's surface colours (rgb, linear reflectance) for terrain.frag, as specialization
// constants from kTerrainFragSpecColors on (TerrainPass::createDrawPipeline, in this order), not
// read from FrameUniforms, which keeps only the three water.frag reads: they are fixed for a
// planet (an edit in the viewer rebuilds the renderer), and as constants the ground's material
// blends cost lavapipe ~1.5-2 ms less a frame at 50 m (docs/benchmarks.md, "The ground's colours
// as constants").
#ifndef PLANET_TERRAIN_COLORS_GLSL
#define PLANET_TERRAIN_COLORS_GLSL

#include "shared/render_params.h"

// Colour `index` of the list, as the constant vec3 `name` (from three float constants).
#define TERRAIN_COLOR(name, index)                                                           \
  layout(constant_id = kTerrainFragSpecColors + 3u * index) const float name##R = 0.0f;      \
  layout(constant_id = kTerrainFragSpecColors + 3u * index + 1u) const float name##G = 0.0f; \
  layout(constant_id = kTerrainFragSpecColors + 3u * index + 2u) const float name##B = 0.0f; \
  const vec3 name = vec3(name##R, name##G, name##B)

TERRAIN_COLOR(kColorDeepWater, 0u);
TERRAIN_COLOR(kColorShallowWater, 1u);
TERRAIN_COLOR(kColorBeach, 2u);
TERRAIN_COLOR(kColorLowland, 3u);
TERRAIN_COLOR(kColorHighland, 4u);
TERRAIN_COLOR(kColorCliff, 5u);
TERRAIN_COLOR(kColorSnow, 6u);
TERRAIN_COLOR(kColorConifer, 7u);
TERRAIN_COLOR(kColorForest, 8u);
TERRAIN_COLOR(kColorGrass, 9u);
TERRAIN_COLOR(kColorDryGrass, 10u);
TERRAIN_COLOR(kColorDesert, 11u);
TERRAIN_COLOR(kColorTundra, 12u);
TERRAIN_COLOR(kColorScree, 13u);

#undef TERRAIN_COLOR

#endif
