// The terrain pass (engine/render/terrain_pass.*): bindings and per-frame blocks shared by its
// compute shader (terrain_heights.comp) and its graphics shaders
// (terrain.vert, terrain.frag).
//
// Frames (engine/planet/clipmap_orientation.h): the mesh's local frame has +z at the camera's
// nadir. Every position the GPU sees is a float offset in the local frame from the anchor,
// the point of the radius sphere straight below the camera; the camera itself sits at
// (0, 0, cameraAltitude) in that system. Nothing of planet size ever reaches a float.
#ifndef PLANET_SHARED_RENDER_PARAMS_H
#define PLANET_SHARED_RENDER_PARAMS_H

#include "shared/eclipse_params.h"
#include "shared/gpu_types.h"
#include "shared/lights_params.h"
#include "shared/ring_params.h"
#include "shared/scheme_params.h"
#include "shared/sky_params.h"
#include "shared/terrain_params.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kPatchMaxLevelsGpu = 16u;  // = kPatchMaxLevels (engine/render/patch_layout.h)

// Bindings of set 0, shared by all four terrain shaders.
GPU_CONST uint kRenderBindingFrame = 0u;           // uniform FrameUniforms
GPU_CONST uint kRenderBindingMesh = 1u;            // ClipmapVertex[] (vec4 direction, vec4 (θ, φ, ring, level))
GPU_CONST uint kRenderBindingSurface = 2u;         // vec4[]: xyz = sea-sphere point − anchor (local), w = height m
GPU_CONST uint kRenderBindingNormals = 3u;         // vec4[]: xyz = unit normal (local), w unused
GPU_CONST uint kRenderBindingAttributes = 4u;      // vec4[]: face Δa, Δb, colour-band noise, sin(latitude)
GPU_CONST uint kRenderBindingLayers = 5u;          // TerrainLayer[kTerrainMaxLayers]
GPU_CONST uint kRenderBindingRemainders = 6u;      // vec4[kTerrainMaxLayers * kNoiseMaxOctaves]
GPU_CONST uint kRenderBindingShifts = 7u;          // uvec4[kTerrainMaxLayers * kNoiseMaxOctaves]
GPU_CONST uint kRenderBindingPermutations = 8u;    // uint[kTerrainMaxLayers * kNoisePermutationSize]
GPU_CONST uint kRenderBindingBudgets = 9u;         // RingBudget[rings + 1] (the pole last)
GPU_CONST uint kRenderBindingPatches = 10u;        // sampler2DArray: normal (planet frame), height m
GPU_CONST uint kRenderBindingTransmittance = 11u;  // sampler2D: the atmosphere's transmittance table
GPU_CONST uint kRenderBindingRelief = 12u;         // samplerCube: normal (planet frame), height m (relief_params.h)
GPU_CONST uint kRenderBindingChunks = 13u;         // uvec2[]: the height pass's vertex runs (first vertex, count)
GPU_CONST uint kRenderBindingFrameTexels = 14u;    // samplerBuffer: binding 0's FrameUniforms as RGBA32F texels
GPU_CONST uint kRenderBindingClouds = 15u;         // samplerCube: the cloud cover (engine/render/cloud_cover.h)
// The deferred shading's (TerrainSettings::deferredShading; terrain_shade.comp): the G-buffer that
// terrain.frag's TERRAIN_GBUFFER variant writes (TerrainSample, four RGBA32F storage images) and
// the HDR target (RGBA16F storage image). Written only when the pass shades deferred.
GPU_CONST uint kRenderBindingNormalHeight = 16u;
GPU_CONST uint kRenderBindingToCameraPixel = 17u;
GPU_CONST uint kRenderBindingUpJitter = 18u;
GPU_CONST uint kRenderBindingLatitudeFootprint = 19u;
GPU_CONST uint kRenderBindingShadedColor = 20u;
// sampler2D: the body's sky-view table (SkyPass, built before the draws), which the sea mirrors;
// until TerrainPass::setSkyView names it, the transmittance table stands in and the sea does not read it.
GPU_CONST uint kRenderBindingSkyView = 21u;
GPU_CONST uint kRenderBindingCount = 22u;
GPU_CONST uint kTerrainShadeWorkgroupSize = 8u;  // its workgroups: 8 × 8 pixels
GPU_CONST uint kSkyIrradianceSamplesGpu = 16u;
// terrain.frag's specialization constants (TerrainPass::createDrawPipeline; terrain_shade.comp
// takes the same, relief aside): ids 0 .. 6 its parts
// (scheme, caps, lights, eclipses, detail, ring shadow, relief), then from kTerrainFragSpecColors the
// planet's kTerrainFragColorCount surface colours, three floats each (terrain_colors.glsl).
GPU_CONST uint kTerrainFragSpecColors = 7u;
GPU_CONST uint kTerrainFragColorCount = 14u;
GPU_CONST uint kWaterWaveCount = 4u;  // = kSkyIrradianceSamples (engine/reference/atmosphere_model.h)
GPU_CONST uint kTerrainComputeWorkgroupSize = 64u;
// Per-pixel ground noise (shaders/terrain_detail.glsl): the first kGroundBiomeOctavesGpu octaves
// (wavelengths 2,500 m / 4^i: 2,500 and 625 m) fray the materials' edges, the rest (4 m / 3^i:
// 4 m .. 1.6 cm) are the ground's detail (and fray the edges further).
GPU_CONST uint kGroundOctavesGpu = 8u;
GPU_CONST uint kGroundBiomeOctavesGpu = 2u;

// Octaves of every layer at one ring's vertex spacing (engine/planet/octave_budget.h).
struct RingBudget {
  uint octaves[kTerrainMaxLayers];
  float lastOctaveWeight[kTerrainMaxLayers];
};
GPU_ASSERT_SIZE(RingBudget, 64)

struct FrameUniforms {
  mat4 viewProjection;  // local frame, camera at the origin → clip (reversed-Z, infinite far)
  mat4 localToPlanet;   // rotation (upper 3×3): local → planet frame directions
  mat4 planetToLocal;   // its transpose
  vec4 camera;    // x: camera altitude above the radius sphere (m), y: radius (m), z: time (s), w: water wave slope
  vec4 planet;    // x: sea level (m), y: 1 if the planet has an ocean, z: beach height (m), w: snow line (m)
  vec4 shading;   // x: sin(ice cap latitude), y: colour scheme (kScheme*, scheme_params.h), z: wireframe (1/0),
                  // w: ambient (fraction of the sun's irradiance; airless bodies)
  vec4 sunLocal;  // xyz: unit direction toward the sun (local frame), w: sun irradiance
  vec4 water;     // x: clarity depth (m), y: largest wave wavelength (m), z: 1 if the water pass draws, w: Cox–Munk
                  // total mean square wave slope from the preset's wind (coxMunkSlopeVariance, water_pass.h)
  // The colours water.frag reads (rgb linear; w unused). terrain.frag takes all of the planet's
  // as specialization constants instead (terrain_colors.glsl).
  vec4 colorDeepWater;
  vec4 colorShallowWater;
  vec4 colorSnow;
  // Patch textures: the face's axes in the local frame, and the reference point the per-vertex
  // face offsets (attributes.xy) are measured from.
  vec4 faceAxisA;      // xyz: A (planet frame), w: c_ref·A
  vec4 faceAxisB;      // xyz: B (planet frame), w: c_ref·B
  vec4 faceNormal;     // xyz: N (planet frame), w: c_ref·N
  vec4 refMinusNadir;  // xyz: c_ref − nadir direction (planet frame, unit sphere), w: patch level count
  // Per level (finest first): x: layer, y: 1 / (Δ·resolution), z, w: (a_ref − originA·Δ), (b_ref − originB·Δ)
  vec4 patchLevels[kPatchMaxLevelsGpu];
  // Per level, two to a vec4 (level 2k in xy, 2k + 1 in zw): where its texel (0, 0) is stored,
  // in texture coordinates (toroidal storage, shared/patch_params.h).
  vec4 patchWrap[kPatchMaxLevelsGpu / 2u];
  // Per level: the part of it its layer holds this frame, in the level's texture coordinates
  // (u₀, v₀, u₁, v₁; (0, 0, 1, 1) when whole): a level built over several frames
  // (PatchTextures::plan) is sampled only there.
  vec4 patchBounds[kPatchMaxLevelsGpu];
  AtmosphereParams atmosphere;
  // Sky irradiance on a horizontal surface for sun zenith cosines −0.2 .. 1 (atmosphere_model.h).
  vec4 skyIrradiance[kSkyIrradianceSamplesGpu];
  // Water waves: xy: wave vector along the face axes (1/m), z: phase at the face reference
  // point (computed in double, wrapped to ±π), w: the wave's share of the slope.
  vec4 waves[kWaterWaveCount];
  vec4 cameraPlanet;  // xyz: the camera in the planet frame (m, float: ring shadows only), w: 1 if the body has rings
  RingParams ring;    // the body's rings, which shadow its surface (shaders/common/rings.glsl ringShadow)
  // Ground materials (shaders/terrain_material.glsl, PlanetDescription::materials).
  vec4 climate;   // x: sea-level mean temperature at the equator (°C), y: its drop to the poles (°C, × sin² latitude),
                  // z: lapse rate (K/m), w: mean annual temperature below which snow or frost lies (°C)
  vec4 moisture;  // x: mean moisture (0 desert .. 1 rainforest), y: noise amplitude, z: coastal height (m),
                  // w: dryness of the subtropical belts
  vec4 slopes;    // x: slope (1 − cos) where bare rock begins, y: steepest slope snow holds on,
                  // z: detail relief (slope scale), w: detail albedo contrast
  // The ground noise's octaves rebased at the anchor (DESIGN.md precision rule; terrain_detail.glsl):
  vec4 groundOctaves[kGroundOctavesGpu];  // xyz: anchor · frequency minus the shift (cells), w: frequency (1/m)
  vec4 groundShifts[kGroundOctavesGpu];   // xyz: the lattice shift modulo 2^22 (exact in float), w unused
  // Seed 000's schemes and seed 004's polar caps (shaders/common/color_schemes.glsl).
  SchemeParams scheme;
  // The other bodies of a scene, which hide the sun from this one's surface (common/eclipse.glsl).
  EclipseParams eclipse;
  // City lights on the night side (shaders/common/city_lights.glsl); drawn only where the
  // pipeline's kSpecLights is set.
  LightsParams lights;
  // The cloud layer, which the sea mirrors and which shadows it (water.frag): the sky pass's
  // SkyUniforms::clouds, cloudShape and cloudMotion for the frame; cloudShape.z is 1 where the
  // frame draws clouds (all zero otherwise).
  vec4 clouds;
  vec4 cloudShape;
  vec4 cloudMotion;
  // The sky the sea mirrors (water.frag, skyViewReflection): x: the weight of the sky-view table
  // (kRenderBindingSkyView) against the sky irradiance's estimate, 1 near the ground fading to 0
  // high above it (the table is the sky seen from the camera's altitude); y: the table's ground
  // sphere (m above the radius, SkyUniforms::surface.z); zw unused.
  vec4 skyView;
};
GPU_ASSERT_SIZE(FrameUniforms, 2128 + 272 + 48 + 48 + 16)

// The texel (vec4) where each array of FrameUniforms that the shaders index with a variable
// starts, for reading it through kRenderBindingFrameTexels (why: terrain_common.glsl,
// frameArray); engine/render/terrain_pass.cpp checks them against the struct.
GPU_CONST uint kFrameTexelPatchLevels = 24u;
GPU_CONST uint kFrameTexelPatchWrap = 40u;
GPU_CONST uint kFrameTexelPatchBounds = 48u;
GPU_CONST uint kFrameTexelSkyIrradiance = 71u;
GPU_CONST uint kFrameTexelWaves = 87u;
GPU_CONST uint kFrameTexelGroundOctaves = 103u;
GPU_CONST uint kFrameTexelGroundShifts = 111u;

// Push constants of the compute passes: which vertices to work on this frame.
struct TerrainComputePush {
  uint firstVertex;  // unused since the height pass takes its vertices from the chunks binding
  uint vertexCount;  // likewise (kept for the std430 layout)
  uint numPhi;       // vertices per ring
  uint ringCount;    // rings of the mesh (the pole is vertex ringCount · numPhi)
  uint layerCount;
  uint firstRing;  // the range's outermost and innermost rings (unused since normals come from the
  uint lastRing;   // analytic gradient; kept for the std430 layout and the bench's reports)
  uint poleNeighbourRing;  // unused likewise
  float baseHeightM;
  float heightScale;
  float bandFrequency;   // cycles per metre of the colour-band noise
  float regionalWeight;  // weight of the regional colour noise (MaterialDescription::regionalNoise)
};
GPU_ASSERT_SIZE(TerrainComputePush, 48)

GPU_NAMESPACE_END

#endif
