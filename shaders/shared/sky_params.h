// The sky (issue 4): the atmosphere's coefficients and the per-frame block of the sky compose
// pass (engine/render/sky_pass.*, shaders/sky.comp), shared by C++ and GLSL. The meaning of
// the atmosphere's functions is in shaders/common/atmosphere.glsl.
#ifndef PLANET_SHARED_SKY_PARAMS_H
#define PLANET_SHARED_SKY_PARAMS_H

#include "shared/eclipse_params.h"
#include "shared/gpu_types.h"

GPU_NAMESPACE_BEGIN

// Transmittance table (Bruneton & Neyret 2008, §4 parameterisation): u from the view zenith
// cosine, v from the altitude; RGBA16F, rgb = transmittance to the top of the atmosphere.
GPU_CONST uint kTransmittanceWidth = 256u;
GPU_CONST uint kTransmittanceHeight = 64u;
GPU_CONST uint kTransmittanceSteps = 500u;  // midpoint steps of the optical-depth integral per texel
GPU_CONST uint kSkyWorkgroupSize = 8u;      // 8×8 invocations per group (compose, tables)

// Bindings of the sky compose pass (set 0).
GPU_CONST uint kSkyBindingUniforms = 0u;             // uniform SkyUniforms (sky_uniforms.glsl)
GPU_CONST uint kSkyBindingColor = 1u;                // image2D rgba32f: the HDR frame, read and written in place
GPU_CONST uint kSkyBindingDepth = 2u;                // sampler2D: the frame's reversed-Z depth
GPU_CONST uint kSkyBindingTransmittance = 3u;        // sampler2D: the transmittance table
GPU_CONST uint kSkyBindingClouds = 4u;               // samplerCube: the three cloud cover images (rgb)
GPU_CONST uint kSkyBindingMultipleScattering = 5u;   // sampler2D: Ψ_ms (the reference march)
GPU_CONST uint kSkyBindingSkyView = 6u;              // sampler2D: the sky-view table (the tables' compose)
GPU_CONST uint kSkyBindingAerialLight = 7u;          // sampler3D: in-scattered light per column and opacity
GPU_CONST uint kSkyBindingAerialTransmittance = 8u;  // sampler3D: optical depth per froxel
// The cloud pass's results (sky_clouds.comp writes one texel per SkyUniforms::cloudShape.w² pixels from the top
// left corner, sky.comp reads them):
GPU_CONST uint kSkyBindingCloudLight = 9u;  // image2D rgba16f: rgb the cloud's light composited with the air in front
                                            // of it (times kSkyHalfLightScale), a its transmittance
// Light held in half floats (the cloud light, the aerial volume's) is stored times this, so that
// deep twilight's (10⁻⁸ of the sun's irradiance, below a half float's smallest normal, 6·10⁻⁵)
// keeps its precision; light up to 16 fits.
GPU_CONST float kSkyHalfLightScale = 4096.0f;
GPU_CONST uint kSkyBindingCloudEnd = 10u;   // image2D rgba32f: x the distance to the drawn surface (kInfinity: none),
                                            // y the ray's path through the layer before its end, z the shadow there
// The compose's and the cloud pass's tiles (one workgroup each) by what their pixels need
// (sky_classify.comp and sky_cloud_classify.comp write them each frame, the tables' compose and
// the cloud pass read them): a storage buffer of kSkyTileLists VkDispatchIndirectCommand (x: the
// list's tile count, y = z = 1, each padded to 16 bytes; the first's padding holds the capacity
// of each list), then the lists, list c's from c × capacity, each tile as x | y << 16 in
// workgroups from its pass's region's corner; then, at kSkyTileLists × capacity, each compose
// tile's farthest depth (row by row; 0 where a pixel shows no geometry), for the cloud tiles.
GPU_CONST uint kSkyBindingTiles = 11u;
// sampler2D: the camera's transmittance table (kCameraTransmittanceDistances below), from inside the air.
GPU_CONST uint kSkyBindingCameraTransmittance = 12u;
// The clouds' shadow table (sky_cloud_shadow.comp writes it each frame from below the layer's base,
// before the cloud pass; the ground's tiles clear of the clouds read it): the cover's density on
// the sphere through the layer's middle around the camera, kCloudShadowTableSize² texels of r32f
// over a square of the local frame's x and y (SkyUniforms::cloudShadowTable), gathered toward its
// centre (sky_compose.glsl, cloudShadowTableUv). Bound twice: sampled (13) and as the build's
// target (14).
GPU_CONST uint kSkyBindingCloudShadowTable = 13u;
GPU_CONST uint kSkyBindingCloudShadowTarget = 14u;
GPU_CONST uint kCloudShadowTableSize = 128u;
GPU_CONST uint kSkyTileMixed = 0u;   // pixels of both kinds, or of geometry past the air
GPU_CONST uint kSkyTileSky = 1u;     // no pixel shows geometry: the sky-view table's
GPU_CONST uint kSkyTileAerial = 2u;  // every pixel shows geometry inside the air: the aerial volume's
// Aerial tiles from below the cloud layer whose pixels, and the cloud samples they read, all end
// their rays before the layer: no cloud in front of them, only its shadow on them (sorted by
// sky_cloud_classify.comp).
GPU_CONST uint kSkyTileAerialClear = 3u;
// The two classes above, for tiles whose every ray, seen from inside the air, ends well short of
// the ground sphere (so no pixel takes the sky-view table's light: sky_compose.glsl,
// aerialPerspective). Sorted by sky_classify.comp and sky_cloud_classify.comp (composeTileNear in
// sky_tile_classes.glsl); kSkyTileNear added to the class of the tile's kind.
GPU_CONST uint kSkyTileNear = 2u;
GPU_CONST uint kSkyTileAerialNear = 4u;
GPU_CONST uint kSkyTileAerialClearNear = 5u;
GPU_CONST uint kSkyTileClasses = 6u;
// The cloud pass's tiles (8 × 8 samples): those whose rays may meet the layer, and those whose
// every ray ends before it can (from below the layer's base, at geometry nearer than where the
// ray leaves the ball under the base), which take no march.
GPU_CONST uint kSkyCloudTileMarch = 6u;
GPU_CONST uint kSkyCloudTileClear = 7u;
GPU_CONST uint kSkyTileLists = 8u;

// The per-frame tables of the sky (Hillaire 2020, §5.3 and §5.4), built by sky_view.comp and
// aerial_perspective.comp before the compose pass, from the same SkyUniforms.
// Sky-view table: RGBA16F, rgb = sky radiance; u = view azimuth from the sun's over 0..π (the
// sky is symmetric about the sun's vertical plane: 192 columns over the whole circle), v = view
// zenith angle, rows gathered toward the horizon (common/atmosphere.glsl, skyViewV).
GPU_CONST uint kSkyViewWidth = 96u;
GPU_CONST uint kSkyViewHeight = 108u;
GPU_CONST uint kSkyViewSteps = 24u;  // steps along each texel's ray (spaced as skyStepSpacing says)
// How a march (common/atmosphere.glsl, scatteringAlong) spaces its steps along a segment: equally;
// gathered toward its start (step i ends at (i / steps)² of it), where a view from inside the air
// sees its densest part; or toward its end (at 1 − (1 − i / steps)²), where a ray from high up
// meets the ground under the haze.
GPU_CONST uint kStepsEqual = 0u;
GPU_CONST uint kStepsTowardStart = 1u;
GPU_CONST uint kStepsTowardEnd = 2u;
// Aerial-perspective volume: kAerialSize² columns over the screen, each with kAerialSize + 1
// slices along its ray in two rgba16f 3D images: the air's optical depth τ = −ln T from the camera
// to each slice's far end (the first the camera's, 0; built from above the air only), and the
// light scattered toward the camera where the column's opacity 1 − T (green) reaches
// j / kAerialSize (from above the air: at the slices' ends; sky_compose.glsl, aerialPerspective,
// says why). The light is stored times kSkyHalfLightScale, as the cloud light is; alpha holds
// log2 of its luminance plus kAerialLogFloor (sky_aerial.glsl, aerialDecodeLight, says why): 2⁻⁴⁰
// of the sun's irradiance, 2⁸ below the darkest light auto exposure measures (kExposureMinLog2),
// so that the floor never shows.
GPU_CONST uint kAerialSize = 32u;
GPU_CONST float kAerialLogFloor = 9.094947e-13f;  // 2^-40
GPU_CONST float kAerialBlendExcess = 2.0f;
// Steps of the volume's march per slice: from inside the air one (its slices, gathered toward the
// camera, are short where the air is dense; a second step moved the tables' agreement with the
// march by 0.2 dB at most on the ground and from 10 km, and cost lavapipe 0.55 ms of the 1.35 ms
// build at 640x360); from above two (each column splits its own crossing evenly, and one step
// lost 0.4-0.6 dB at the limb from 100 km and from orbit).
GPU_CONST uint kAerialStepsPerSlice = 1u;
GPU_CONST uint kAerialStepsPerSliceAbove = 2u;
// From inside the air, what a ray ends on at the second share of its distance to the ground
// sphere or farther takes its light from the sky-view table (sky_compose.glsl, aerialPerspective,
// says why), blended in from the first share.
GPU_CONST float kSkyViewGroundShareFrom = 0.9f;
GPU_CONST float kSkyViewGroundShareTo = 0.98f;
GPU_CONST float kSkyViewGroundHeightFrom = 100.0f;
GPU_CONST float kSkyViewGroundHeightTo = 400.0f;
// The camera's transmittance table, built from inside the air before the compose
// (sky_camera_transmittance.comp; common/atmosphere.glsl, cameraTransmittanceUnit, has its
// mapping), again only when the camera's altitude or the air moved
// (SkyPass::cameraTransmittanceBuilt): the air's optical depth from the camera to distance t along
// a ray of zenith cosine mu, x by distance (t out to SkyUniforms::camera.z, gathered toward the
// camera), y by mu (gathered toward the ground sphere's horizon, whose cosine is aerial.w). One
// read gives a pixel's transmittance to what it shows. Each row is marched by one invocation,
// kCameraTransmittanceSteps midpoint steps between neighbouring texels, adding up as it goes. The
// sizes: on a model of Earth's air (exact integrals of random rays that end above the ground), the
// largest error of the transmittance is 0.25 of 255 from the ground, 1.7 from 10 km and 5 from 30
// and 60 km, on rays that end near the ground far below; it comes from the filter between texels,
// not from the steps (four steps moved it by less than 1 of 255). 256 directions halved it from
// 30 km up, for 0.2 ms more of the build on lavapipe (a row's texels cost it about 20 ns each, the
// steps almost nothing) and no more than 0.2 dB of the tables' agreement with the march.
GPU_CONST uint kCameraTransmittanceDistances = 128u;
GPU_CONST uint kCameraTransmittanceDirections = 128u;
GPU_CONST uint kCameraTransmittanceSteps = 1u;
GPU_CONST uint kCameraTransmittanceWorkgroup = 64u;
// Bindings of the per-frame table builds (set 0).
GPU_CONST uint kSkyTableBindingUniforms = 0u;             // SkyUniforms (uniform buffer: sky_uniforms.glsl)
GPU_CONST uint kSkyTableBindingTransmittance = 1u;        // sampler2D
GPU_CONST uint kSkyTableBindingMultipleScattering = 2u;   // sampler2D
GPU_CONST uint kSkyTableBindingSkyView = 3u;              // image2D rgba32f, written
GPU_CONST uint kSkyTableBindingAerialLight = 4u;          // image3D rgba16f, written
GPU_CONST uint kSkyTableBindingAerialTransmittance = 5u;  // image3D rgba16f, written
GPU_CONST uint kSkyTableBindingCameraTransmittance = 6u;  // image2D rgba32f, written

// The weather that shapes the cloud cover (shaders/clouds_cover.comp), one storage buffer
// written once per planet by engine/render/cloud_cover.cpp.
GPU_CONST uint kCloudMaxVortices = 96u;
GPU_CONST uint kCloudSharedOctaves = 4u;  // the cover's largest octaves, the same in all three images

struct CloudVortex {
  vec4 centre;  // xyz: unit direction (planet frame), w: angular radius (rad)
  vec4 shape;   // x: twist at the centre (rad; > 0 turns counter-clockwise seen from above), y: cover added at the
                // centre, z: clear eye radius (fraction of the radius; 0: none), w: unused
};
GPU_ASSERT_SIZE(CloudVortex, 32)

struct CloudWeather {
  vec4 shape;  // x: radius / wavelength (noise units per unit direction), y: face size (texels), z: seed (uint bits),
               // w: 1 / Σ octave weights
  vec4 cover;  // x: coverage, y: ln(1 / sharpness), z: climate strength, w: vortex count
  vec4 flow;   // x: zonal shear (rad of longitude at the jets' peak), y: warp (unit-sphere distance), z: jet meander
               // (rad of latitude), w: warp frequency (per unit direction)
  vec4 pad;
  CloudVortex vortices[kCloudMaxVortices];
};
GPU_ASSERT_SIZE(CloudWeather, 64 + 32 * 96)

// Sun irradiance at the top of the atmosphere, in the renderer's HDR units (the tonemap's
// exposure maps a sunlit ground of albedo ~0.2 to the middle of the display range).
GPU_CONST float kSunIrradiance = 1.0f;

struct AtmosphereParams {
  vec4 radii;  // x: planet radius R (m), y: atmosphere height above R (m), z: sun angular radius (rad), w: 1 if there
               // is air
  vec4 rayleigh;       // xyz: β_R per metre at the ground, w: 1 / Rayleigh scale height
  vec4 mieScattering;  // xyz: β_M, w: 1 / Mie scale height
  vec4 mieExtinction;  // xyz: β_M · extinction ratio, w: unused
  vec4 ozone;          // xyz: ozone absorption at the peak, w: peak altitude (m)
  vec4 ozoneSun;       // x: ozone half width (m), y: sun irradiance, z, w: unused
  vec4 mieG;           // xyz: Cornette-Shanks asymmetry g per channel, w: unused
};
GPU_ASSERT_SIZE(AtmosphereParams, 112)

// The airglow's shell (common/atmosphere.glsl, airglowAlong), for the compose only (kept out of
// AtmosphereParams, which SkyRayPush carries in 128 bytes of push constants).
struct AirglowParams {
  vec4 radiance;  // xyz: radiance looking straight up through the shell (the frame's unit: kExposureSunCdM2 cd/m² of
                  // luminance; not scaled with the sun, which does not light it), w: 1 if any
  vec4 layer;     // x: the shell's bottom, y: its top (m above R), z, w: unused
};
GPU_ASSERT_SIZE(AirglowParams, 32)

struct SkyUniforms {
  AtmosphereParams atmosphere;
  mat4 clipToLocal;    // clip (x, y) at depth 1 → view ray, local frame, camera at the origin
  mat4 localToPlanet;  // rotation: local → planet frame directions
  vec4 camera;         // x: camera altitude above R (m), y: near plane (m), z: the camera's transmittance
                       // table's reach (m; aerial.y when it was built), w: time (s)
  vec4 forward;        // xyz: camera forward (local), w: view samples per pixel
  vec4 sunLocal;       // xyz: toward the sun (local), w: star brightness
  vec4 cameraPlanet;   // xyz: camera position in the planet frame (m, float: clouds only), w: 1 if clouds
  vec4 clouds;         // x: bottom (m above R), y: top, z: extinction of full density (1/m), w: cloud width over
                       // the layer's thickness (caps slant paths through a cloud)
  vec4 cloudShape;     // x: angle of a level-0 cover texel (rad), y: the cover's last mip level, z: most samples per
                       // crossing of the layer, w: pixels per sample of the cloud pass along each axis (1 or 2)
  vec4 cloudMotion;    // xyz: weights of the three cover images (seed 001 eq. 4.2), w: drift angle (rad) about the
                       // planet's axis
  vec4 extent;  // x: width, y: height (pixels), z: view angle of one pixel (rad), w: 1 in the frame's last compose (the
                // camera's body's): draws the sun's disc, leaves the stars' share in alpha
  vec4 surface;  // x: lowest surface (m above R: the sea level with a sea, else the deepest terrain), y: 1 with a sea,
                 // z: the ground sphere (m above R) a ray that met no geometry ends on, w: unused
  vec4 aerial;   // slices of the aerial-perspective volume: x: 1 when the camera is above the top of the
                 // atmosphere (each column's slices split its own stretch through the air evenly), else 0
                 // (slice k ends at distance y · ((k + 1) / kAerialSize)²); y: that farthest distance (m);
                 // z: the zenith angle of the ground sphere's horizon (rad; sky_compose.glsl,
                 // aerialPerspective); w: its cosine when the camera's transmittance table was built
                 // (sky_aerial.glsl, cameraTransmittanceUv)
  vec4 region;   // the passes' dispatches cover only where the air or the sun can show (SkyPass::prepare,
                 // skyRegion): x, y: the compose's first pixel; z, w: the cloud pass's first sample
  vec4 cloudShadowTable;  // the clouds' shadow table's square (kSkyBindingCloudShadowTable): xy its centre (local
                          // x and y, m), z half its side (m), w: unused
  // Sky irradiance on a horizontal surface for sun zenith cosines −0.2 .. 1 (atmosphere_model.h).
  vec4 skyIrradiance[16];
  // The other bodies of a scene, which hide the sun from this one's air (common/eclipse.glsl).
  EclipseParams eclipse;
  AirglowParams airglow;
};
GPU_ASSERT_SIZE(SkyUniforms, 688 + 272 + 32)

// Multiple-scattering table (Hillaire 2020, §5.5; shaders/atmosphere_multiscatter.comp): u from
// the sun's zenith cosine, v from the altitude; RGBA32F, rgb = Ψ_ms (radiance per steradian per
// unit sun irradiance, the isotropic phase included), a = the transfer f_ms of the green channel.
GPU_CONST uint kMultiScatteringSize = 32u;            // texels along each axis
GPU_CONST uint kMultiScatteringDirections = 8u;       // 8 × 8 directions over the sphere per texel
GPU_CONST uint kMultiScatteringSteps = 32u;           // steps along each direction's ray
GPU_CONST float kMultiScatteringGroundAlbedo = 0.3f;  // Lambertian ground under the air (second order only)

// One ray of `planet sky` on the GPU (shaders/sky_ray.comp): the sun's transmittance and Ψ_ms
// from the tables; the per-pixel march of sky.comp and the tables' march, side by side.
GPU_CONST uint kSkyRayWorkgroupSize = 64u;
struct SkyRayPush {
  AtmosphereParams atmosphere;
  vec4 counts;  // x: rays, y: steps of the reference march (sky.comp's samples), z: steps of the tables' march, w: 0
                // (whole numbers as floats)
};
GPU_ASSERT_SIZE(SkyRayPush, 128)

GPU_NAMESPACE_END

#endif
