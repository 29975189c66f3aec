// What the sky compose pass (sky.comp) and its cloud pass (sky_clouds.comp) share: one
// descriptor set layout, the view ray through a point of the screen and where it ends, the read
// of the aerial-perspective volume, and the cloud layer (cloud_layer.glsl, which the sea's shader
// shares) with its light along a ray and its shadow on the ground.
// The cloud pass's images (kSkyBindingCloudLight, kSkyBindingCloudEnd) are declared by each
// includer, with the access it needs.
#ifndef PLANET_SKY_COMPOSE_GLSL
#define PLANET_SKY_COMPOSE_GLSL

#include "shared/sky_params.h"

layout(local_size_x = kSkyWorkgroupSize, local_size_y = kSkyWorkgroupSize) in;

// SkyUniforms has only vec4 and mat4 members, so std140 lays it out as C++ does.
#include "sky_uniforms.glsl"
layout(set = 0, binding = kSkyBindingColor, rgba32f) uniform image2D color;
layout(set = 0, binding = kSkyBindingDepth) uniform sampler2D depthBuffer;
layout(set = 0, binding = kSkyBindingTransmittance) uniform sampler2D transmittanceTable;
layout(set = 0, binding = kSkyBindingClouds) uniform samplerCube cloudCover;
layout(set = 0, binding = kSkyBindingMultipleScattering) uniform sampler2D multipleScatteringTable;
layout(set = 0, binding = kSkyBindingSkyView) uniform sampler2D skyView;
layout(set = 0, binding = kSkyBindingAerialLight) uniform sampler3D aerialLight;
layout(set = 0, binding = kSkyBindingAerialTransmittance) uniform sampler3D aerialTransmittance;
layout(set = 0, binding = kSkyBindingCameraTransmittance) uniform sampler2D cameraTransmittance;
layout(set = 0, binding = kSkyBindingCloudShadowTable) uniform sampler2D cloudShadowTable;

#define MULTIPLE_SCATTERING(a, h, muS) \
  textureLod(multipleScatteringTable, multipleScatteringUv(a, h, muS), 0.0f).rgb
// Eclipses: the reference march scales each sample's light by the share of the sun it sees past
// the scene's other bodies, at its place on the segment's ray (its start, plus t along the ray).
// Whether another body can hide the sun (a scene), as a specialization constant: the eclipse
// loop's body costs every pixel on lavapipe even with no occluder.
layout(constant_id = 0) const bool kSpecEclipses = true;
#define ECLIPSE_POSSIBLE kSpecEclipses
#include "common/eclipse.glsl"
vec3 marchStart;  // local frame, from the camera
vec3 marchDirection;
#define SUN_VISIBLE_ALONG(t) eclipseSunVisible(marchStart + marchDirection * (t), sky.sunLocal.xyz, sky.eclipse)
#include "atmosphere_lookup.glsl"
#include "sky_aerial.glsl"
#define CLOUD_COVER cloudCover
#define CLOUD_LAYER sky.clouds
#define CLOUD_SHAPE sky.cloudShape
#define CLOUD_MOTION sky.cloudMotion
#define CLOUD_LOCAL_TO_PLANET sky.localToPlanet
#include "cloud_layer.glsl"

const float kInfinity = 3.0e38f;

// The sky irradiance table at sun zenith cosine muS (atmosphere_lookup.glsl, skyIrradianceBetween).
vec3 skyIrradianceAt(float muS) {
  float x = skyIrradianceX(muS);
  uint i = skyIrradianceIndex(x);
  return skyIrradianceBetween(sky.skyIrradiance[i].rgb, sky.skyIrradiance[i + 1u].rgb, x, i, muS);
}

// The ray's stretches inside the layer (at most two: a ray from above may dip below its bottom
// and rise again), clipped to [0, tEnd]; returns how many.
uint layerIntervals(float R, float h, float mu, float tEnd, out vec2 first, out vec2 second) {
  float bottom = sky.clouds.x, top = sky.clouds.y;
  vec2 topHits = raySphere(R, h, mu, top);
  vec2 bottomHits = raySphere(R, h, mu, bottom);
  first = vec2(-1.0f);
  second = vec2(-1.0f);
  if (h >= top) {
    if (topHits.y < 0.0f) return 0u;  // misses the layer (or only grazes it)
    if (bottomHits.y >= 0.0f) {
      first = vec2(topHits.x, bottomHits.x);
      second = vec2(bottomHits.y, topHits.y);
    } else {
      first = topHits;
    }
  } else if (h >= bottom) {
    if (bottomHits.y >= 0.0f) {
      first = vec2(0.0f, bottomHits.x);
      second = vec2(bottomHits.y, topHits.x);
    } else {
      first = vec2(0.0f, topHits.x);
    }
  } else {
    first = vec2(bottomHits.x, topHits.x);
  }
  vec2 a0 = first, a1 = second;
  uint count = 0u;
  if (a0.x >= 0.0f && a0.x < tEnd && a0.y > a0.x) {
    first = vec2(a0.x, min(a0.y, tEnd));
    count = 1u;
  }
  if (a1.x >= 0.0f && a1.x < tEnd && a1.y > a1.x) {
    vec2 clipped = vec2(a1.x, min(a1.y, tEnd));
    if (count == 0u) first = clipped;
    else second = clipped;
    count += 1u;
  }
  return count;
}

// The segments a stretch of the ray in the layer is crossed in (nearer ones shorter).
uint layerSegments(vec2 stretch, float across) {
  float thickness = sky.clouds.y - sky.clouds.x;
  return uint(clamp(ceil((stretch.y - stretch.x) * across / (1.5f * thickness)), 1.0f, sky.cloudShape.z));
}

// Composes the layer along the ray's stretches in it (`count` of first, second): a few segments
// each, nearer ones shorter, each reading the cover once at its middle, averaged over the
// segment's length and the pixel's footprint (the mip level), and crossing the column there
// analytically: the part of the segment's altitude range inside the column is the part of its
// length inside the cloud. One loop over both stretches' segments: a CPU device runs a loop as
// long as its longest lane, and each call of a loop at least once.
void marchLayer(vec3 dir, float R, float h, float mu, vec2 first, vec2 second, uint count, float nu, float muSCamera,
                float r, vec3 sunLight, vec3 skyLight, inout vec3 light, inout float transmittance,
                inout float weightedT, inout float weight) {
  float bottom = sky.clouds.x, top = sky.clouds.y;
  float thickness = top - bottom;
  float phase = cloudPhase(nu);
  float across = sqrt(max(1.0f - mu * mu, 0.0f));
  uint firstSegments = layerSegments(first, across);
  uint segments = firstSegments + (count > 1u ? layerSegments(second, across) : 0u);
  float hPrevious = altitudeAlong(R, h, mu, first.x);
  float tPrevious = first.x;
  for (uint k = 0u; k < segments; ++k) {
    bool inFirst = k < firstSegments;
    vec2 stretch = inFirst ? first : second;
    uint i = inFirst ? k + 1u : k + 1u - firstSegments;
    float stretchSegments = float(inFirst ? firstSegments : segments - firstSegments);
    if (i == 1u) {  // the start of a stretch
      tPrevious = stretch.x;
      hPrevious = altitudeAlong(R, h, mu, stretch.x);
    }
    float f = float(i) / stretchSegments;
    float t = stretch.x + (stretch.y - stretch.x) * f * f;
    float hNext = altitudeAlong(R, h, mu, t);
    float tMid = 0.5f * (tPrevious + t);
    float segment = t - tPrevious;
    float footprint = max(tMid * sky.extent.z, 0.5f * segment * across);
    vec3 fromCentre = vec3(dir.x * tMid, dir.y * tMid, R + h + dir.z * tMid);
    float d = coverDensity(fromCentre, coverLod(footprint, R + 0.5f * (bottom + top)));
    float columnTop = bottom + d * thickness;
    float lo = min(hPrevious, hNext), hi = max(hPrevious, hNext);
    // Soft top: a near-horizontal segment fades through the column's upper tenth.
    float span = max(hi - lo, 0.1f * d * thickness + 20.0f);
    float inside = clamp((min(hi, columnTop) - max(lo, bottom)) / span, 0.0f, 1.0f);
    if (d > 0.002f && inside > 0.0f) {
      float tau = sky.clouds.z * d * inside * segment;
      float alpha = 1.0f - exp(-tau);
      // Lit where the eye sees into the cloud: one optical depth past where the ray enters the
      // column (its top seen from above, its base from below, its middle from the side).
      float overlapLo = max(lo, bottom), overlapHi = min(hi, columnTop);
      float visible = min(0.5f * (overlapHi - overlapLo), (hi - lo) / (max(segment, 1.0f) * sky.clouds.z * d));
      float hLight = hNext < hPrevious ? overlapHi - visible : overlapLo + visible;
      float muS = clamp((r * muSCamera + tMid * nu) / (R + hLight), -1.0f, 1.0f);
      light += transmittance * alpha * cloudLight(hLight, d, muS, phase, sunLight, skyLight);
      weightedT += transmittance * alpha * tMid;
      weight += transmittance * alpha;
      transmittance *= 1.0f - alpha;
    }
    tPrevious = t;
    hPrevious = hNext;
    if (transmittance < 0.01f) break;
  }
}

// The transmittance of the air between a camera inside it and distance t along a ray of zenith
// cosine mu: one read of the camera's transmittance table (sky_camera_transmittance.comp).
vec3 transmittanceFromCamera(float mu, float t) {
  return exp(-textureLod(cameraTransmittance, cameraTransmittanceUv(mu, t), 0.0f).rgb);
}

// The depths of the 2×2 pixels from `pixel` (one gather, in its component order: x (+0, +1),
// y (+1, +1), z (+1, +0), w (+0, +0)); the depth sampler clamps to the image's edge.
vec4 depthTexels(ivec2 pixel) { return textureGather(depthBuffer, vec2(pixel + 1) / sky.extent.xy); }

// A view ray through a point of the screen (in pixels) and where it ends: at the drawn surface
// (depth, reversed Z), else at the ground sphere, else nowhere (kInfinity).
struct ViewRay {
  vec3 dir;  // local frame, unit
  bool geometry;
  float tGeometry;  // to the drawn surface (or the sea's sphere in front of it); kInfinity without geometry
  float hGround;    // the sphere a ray that met no geometry ends on (m above R)
  vec2 groundHits;  // raySphere at hGround
  bool seesGround;  // the ray meets that sphere
  float tEnd;
};

// The unit direction (local frame) of the view ray through a point of the screen (in pixels).
vec3 viewDirection(vec2 screenPoint) {
  vec2 ndc = screenPoint / sky.extent.xy * 2.0f - 1.0f;
  vec4 nearPoint = sky.clipToLocal * vec4(ndc, 1.0f, 1.0f);
  return normalize(nearPoint.xyz / nearPoint.w);
}

ViewRay viewRay(vec2 screenPoint, float depth) {
  ViewRay ray;
  ray.dir = viewDirection(screenPoint);
  ray.geometry = depth > 0.0f;
  // Reversed Z: depth = near / view distance; the ray length follows from the view axis.
  ray.tGeometry = ray.geometry ? sky.camera.y / depth / max(dot(ray.dir, sky.forward.xyz), 1e-6f) : kInfinity;
  float R = sky.atmosphere.radii.x;
  float h = sky.camera.x;
  float mu = ray.dir.z;
  // The sea is drawn on the mesh's flat triangles, up to a few hundred metres below the sphere
  // in their middles (chord sag) on the coarse rings seen from orbit; ending the march there
  // put a faint grid of the triangles into the haze. The march ends at the sea's sphere when
  // that is nearer than what was drawn.
  float lowest = sky.surface.x;
  bool hasSea = sky.surface.y > 0.5f;
  if (ray.geometry && hasSea && h > lowest) {
    vec2 sea = raySphere(R, h, mu, lowest);
    if (sea.x >= 0.0f && sea.x < ray.tGeometry) ray.tGeometry = sea.x;
  }
  // A ray that met no geometry has met the ground only below the lowest surface: without a sea,
  // basins below the radius sphere are seen past its horizon (the mesh may end before them), and
  // counting the radius sphere as ground drew those rays black.
  ray.hGround = sky.surface.z;  // the radius sphere with a sea, else min(lowest, 0)
  ray.groundHits = raySphere(R, h, mu, ray.hGround);
  ray.seesGround = mu < 0.0f && ray.groundHits.x >= 0.0f;
  ray.tEnd = ray.geometry ? ray.tGeometry : (ray.seesGround ? ray.groundHits.x : kInfinity);
  return ray;
}

// The sky-view table's texel for direction dir at zenith angle theta, for the zenith range `range`
// (skyViewZenithRange): rgb the light along the whole ray, alpha its opacity (green).
vec4 skyViewAt(vec3 dir, float theta, vec2 range) {
  return textureLod(skyView, skyViewUv(theta, range, vec3(dir.xy, 0.0f), vec3(sky.sunLocal.xy, 0.0f)), 0.0f);
}

// The sky-view table along a whole ray (none where the ray misses the air).
vec4 skyViewAlong(vec3 dir, float h, float hGround) {
  vec2 range = skyViewZenithRange(sky.atmosphere, h, hGround);
  float theta = atan(length(vec2(dir.x, dir.y)), dir.z);  // not acos (skyViewZenithRange says why)
  if (theta < range.x) return vec4(0.0f);
  return skyViewAt(dir, theta, range);
}

// The share of the sun seen by the air along a stretch of a ray, for the sky-view table, which has
// no place along the ray to hold an eclipse: the mean over four points of the stretch (the ray's
// through the air, or up to the sea it ends on), spaced as the table's steps are (`spacing`:
// common/atmosphere.glsl, skyStepSpacing). From
// inside an eclipse's shadow the whole sky darkens with it (the horizon's glow from outside the
// shadow is missed); from orbit the limb does where the shadow crosses it.
float skyEclipse(vec3 dir, vec2 stretch, uint spacing) {
  if (!(stretch.y > stretch.x) || !(sky.eclipse.sun.y > 0.5f)) return 1.0f;
  float sum = 0.0f;
  for (uint k = 0u; k < 4u; ++k) {
    float x = (float(k) + 0.5f) / 4.0f;
    float t = stretch.x + (stretch.y - stretch.x) * stepShare(x, spacing);
    sum += eclipseSunVisible(dir * t, sky.sunLocal.xyz, sky.eclipse);
  }
  return 0.25f * sum;
}

// The tables' atmosphere between the camera and distance t along the pixel's ray (screen
// position uv, zenith cosine mu): light scattered toward the camera and transmittance, from the
// aerial-perspective volume filtered across its columns.
// - The transmittance, from inside the air, is the pixel's own ray's from the camera's
//   transmittance table (transmittanceFromCamera); from above the air the volume's optical depth
//   filtered between the two slices around t (from above they split each column's own stretch
//   through the air).
// - The light, from inside the air, is the columns' at the pixel's opacity 1 − T (green), which
//   indexes the light's volume (from above, distance does, as for the depth). The light gathered
//   along a ray grows with its opacity at the rate of the air's own light, which changes slowly,
//   so it is close to linear between the volume's opacity levels, and the columns agree at equal
//   opacity where their rays have crossed different distances of different air. Held by distance
//   and filtered between slices, the light and the transmittance fell short of the march where
//   the air thickens along the ray (a slice near the camera is long next to the haze's scale
//   height): by 6 to 8 of 255 on the sea seen from 10 to 30 km at sunset, in bands at the slices.
// - Except where, from inside the air, the ray ends on the ground sphere or near it: from
//   kSkyViewGroundShareFrom of the distance to it (blended in up to kSkyViewGroundShareTo), with its
//   end less than kSkyViewGroundHeightFrom above that sphere (blended out by
//   kSkyViewGroundHeightTo) or within two rows of the volume's columns of the horizon. There the
//   light is the sky-view table's along the pixel's own direction, whose rays end on that sphere,
//   times the share of that ray's opacity the pixel's has (1 on the sea), with the eclipses along
//   it (skyEclipse). The volume's columns are 17 pixels apart at 540 lines and cannot hold the
//   horizon: seen from high up, a column just over it ends short of the ground's opacity with the
//   light of the sunlit air beyond, and it lifted the ground under the horizon to the sky's
//   brightness (from 60 km at twilight, 36.9 dB against the march, the worst row 15 of 255 off;
//   from the table 49.2 dB). The table's rows gather toward the horizon, and the sea's haze from
//   10 km at sunset follows the march within 61.2 dB (49.3 from the volume). Where the ray ends
//   nearer, or on land higher up, its light does not grow with its opacity as the whole ray's
//   does: the whole ray also crosses the haze under its end, which from 30 km over the Great
//   Plains at sunset is orange, and the land took its colour (46.7 dB against the volume's 49.0;
//   with the height limit 51.9). There the volume serves.
// `near` (a tile of kSkyTileAerialNear or kSkyTileAerialClearNear: composeTileNear proved that
// every pixel's ray ends short of that share) leaves that out, which does not change such a
// pixel; `inside` (a tile of those or of kSkyTileAerialClear, all classes seen from inside the
// air) leaves out the reads from above. Both are constants where the tile's class is: lavapipe
// runs the code of every branch.
void aerialPerspective(vec2 uv, ViewRay ray, float t, vec2 columnStretch, bool near, bool inside, out vec3 light,
                       out vec3 transmittance) {
  float mu = ray.dir.z;
  bool fromAbove = !inside && aerialFromAbove();
  // Slice k ends at aerialSlice k; the volume holds the camera in its first slice, k in k + 1.
  vec3 bySlice = vec3(0.0f);
  if (fromAbove) {
    float slice = min(aerialSlice(t, columnStretch), float(kAerialSize) - 1.0f) + 1.0f;
    bySlice = vec3(uv, (slice + 0.5f) / float(kAerialSize + 1u));
    transmittance = exp(-textureLod(aerialTransmittance, bySlice, 0.0f).rgb);
  } else {
    transmittance = transmittanceFromCamera(mu, t);
  }
  float share = 0.0f, theta = 0.0f;
  if (!near && !fromAbove && ray.seesGround) {
    theta = atan(length(ray.dir.xy), mu);
    float above = altitudeAlong(sky.atmosphere.radii.x, sky.camera.x, mu, t) - ray.hGround;
    // The horizon's distance in rows of the volume's columns.
    float rows = (theta - sky.aerial.z) / (sky.extent.z * sky.extent.y / float(kAerialSize));
    float low = max(1.0f - smoothstep(kSkyViewGroundHeightFrom, kSkyViewGroundHeightTo, above),
                    1.0f - smoothstep(1.0f, 2.0f, rows));
    share = smoothstep(kSkyViewGroundShareFrom, kSkyViewGroundShareTo, t / ray.groundHits.x) * low;
  }
  light = vec3(0.0f);
  if (share < 1.0f) {
    float level = (1.0f - transmittance.y) * float(kAerialSize);
    vec3 byLevel = vec3(uv, (level + 0.5f) / float(kAerialSize + 1u));
    vec4 texel = textureLod(aerialLight, fromAbove ? bySlice : byLevel, 0.0f);
    light = fromAbove ? aerialDecodeLight(texel) : texel.rgb * (1.0f / kSkyHalfLightScale);
  }
  if (share > 0.0f) {
    vec4 whole = skyViewAt(ray.dir, theta, vec2(0.0f, sky.aerial.z));  // inside the air: from the zenith
    float opacityShare = clamp((1.0f - transmittance.y) / max(whole.a, 1.0e-6f), 0.0f, 1.0f);
    float eclipse = skyEclipse(ray.dir, vec2(0.0f, t), skyStepSpacing(sky.atmosphere, sky.camera.x, true));
    vec3 alongView = whole.rgb * opacityShare * eclipse;
    light = mix(light, alongView, share);
  }
}

// The compose's and the cloud pass's tiles by class (kSkyBindingTiles): written by
// sky_classify.comp and sky_cloud_classify.comp, read by the tables' compose (sky.comp), the
// cloud pass (sky_clouds.comp) and their indirect dispatches.
layout(set = 0, binding = kSkyBindingTiles, std430) buffer SkyTiles {
  uvec4 dispatches[kSkyTileLists];  // x: the list's tiles; dispatches[0].w: each list's capacity
  uint tiles[];                     // the lists, then the compose tiles' farthest depths
}
skyTiles;

// Tile `index` of list `list`, in workgroups from its pass's region's corner.
ivec2 listedTile(uint list, uint index) {
  uint tile = skyTiles.tiles[list * skyTiles.dispatches[0].w + index];
  return ivec2(tile & 0xffffu, tile >> 16u);
}

// Appends `tile` to list `list` (the classify passes).
void appendTile(uint list, uvec2 tile) {
  uint index = atomicAdd(skyTiles.dispatches[list].x, 1u);
  skyTiles.tiles[list * skyTiles.dispatches[0].w + index] = tile.x | (tile.y << 16u);
}

// Where compose tile `tile` of a region `tilesX` tiles wide keeps its farthest depth.
uint farthestDepthSlot(uvec2 tile, uint tilesX) {
  return kSkyTileLists * skyTiles.dispatches[0].w + tile.y * tilesX + tile.x;
}

// Whether the frame draws clouds (the preset has them, they are on, and there is air). Also as a
// specialization constant (SkyPass::cloudsDrawn), so that a pipeline without them has no cloud
// code: lavapipe runs every branch for every pixel.
layout(constant_id = 1) const bool kSpecClouds = true;
bool cloudsDrawn() { return kSpecClouds && sky.cameraPlanet.w > 0.5f && sky.atmosphere.radii.w > 0.5f; }

// The drawn surface a view ray ends on, for the clouds' shadow there: the point (local frame,
// from the planet's centre), its altitude (m above R) and the sun's zenith cosine there.
struct SurfacePoint {
  vec3 fromCentre;
  float h;
  float muS;
};

SurfacePoint surfacePoint(ViewRay ray) {
  float R = sky.atmosphere.radii.x;
  float h = sky.camera.x;
  vec3 sun = sky.sunLocal.xyz;
  SurfacePoint p;
  p.h = altitudeAlong(R, h, ray.dir.z, ray.tGeometry);
  p.muS = ((R + h) * sun.z + ray.tGeometry * dot(ray.dir, sun)) / (R + p.h);
  vec3 surface = ray.dir * ray.tGeometry;  // from the camera
  p.fromCentre = vec3(surface.x, surface.y, R + h + surface.z);
  return p;
}

// Cloud shadow on the drawn surface, as a factor of its light (cloud_layer.glsl).
float cloudShadow(ViewRay ray) {
  float shadow = 1.0f;
  if (ray.geometry && cloudsDrawn()) {
    SurfacePoint p = surfacePoint(ray);
    float footprint = max(ray.tGeometry * sky.extent.z, 1000.0f);
    shadow = cloudGroundShadow(
        cloudSunTransmittance(p.fromCentre, sky.atmosphere.radii.x, p.h, sky.sunLocal.xyz, p.muS, footprint));
  }
  return shadow;
}

// The clouds' shadow table (sky_cloud_shadow.comp): texture coordinates of a point on the sphere
// through the layer's middle (local frame, from the planet's centre), and the point of that
// sphere (radius rLayer) at texture coordinates uv. The table's square (SkyUniforms::cloudShadowTable)
// is centred where the sun's ray from the camera crosses that sphere, near where it does from the
// ground around the camera, which fills most of the picture; its texels are gathered there,
// x = c + s · u |u| for u in [−1, 1] along each axis (s half the side): at the edge a texel spans
// twice a uniform one's side. The table was uniform first: there it spanned a third of a cover
// texel or more from a low sun, and the bilinear filter of the cover's own filtered values cut its
// corners enough to show through the shadow's steep dependence on density (exp(−k d · slant)):
// from 50 m at a sun of 8° 52.6 dB against the march, from 1.9 km at 3° 48.2, where the cloud
// pass's samples had 57.4 and 52.8. Gathered, 57.6 and 52.5.
vec2 cloudShadowTableUv(vec3 onLayer) {
  vec2 u = (onLayer.xy - sky.cloudShadowTable.xy) / sky.cloudShadowTable.z;
  return 0.5f + 0.5f * sign(u) * sqrt(abs(u));
}
vec3 cloudShadowTablePoint(vec2 uv, float rLayer) {
  vec2 u = 2.0f * uv - 1.0f;
  vec2 xy = sky.cloudShadowTable.xy + u * abs(u) * sky.cloudShadowTable.z;
  return vec3(xy, sqrt(max(rLayer * rLayer - dot(xy, xy), 0.0f)));
}

// cloudShadow from the clouds' shadow table: the cover's density where the ray toward the sun
// crosses the layer's middle (cloudLayerCrossing), one bilinear read, for a surface whose
// footprint is below a level-0 texel of the cover (the table's texels are smaller:
// SkyPass::cloudShadowSquare). It serves the rays that end before the layer, whose surfaces the
// table spans.
float cloudShadowFromTable(ViewRay ray) {
  if (!(ray.geometry && cloudsDrawn())) return 1.0f;
  SurfacePoint p = surfacePoint(ray);
  vec3 crossing;
  if (!cloudLayerCrossing(p.fromCentre, sky.atmosphere.radii.x, p.h, sky.sunLocal.xyz, p.muS, crossing)) return 1.0f;
  float d = textureLod(cloudShadowTable, cloudShadowTableUv(crossing), 0.0f).r;
  return cloudGroundShadow(columnSunTransmittance(d, p.muS));
}

// The cloud layer along the view ray up to its end: the light it sends toward the camera, its
// transmittance, and the distance its opacity is centred on (tCloud, where the compose puts it
// into the air's march; −1 where the ray meets no cloud).
void cloudsAlong(ViewRay ray, out vec3 light, out float transmittance, out float tCloud) {
  light = vec3(0.0f);
  transmittance = 1.0f;
  tCloud = -1.0f;
  AtmosphereParams a = sky.atmosphere;
  float R = a.radii.x;
  float h = sky.camera.x;
  float r = R + h;
  float mu = ray.dir.z;
  vec3 sun = sky.sunLocal.xyz;
  float muS = sun.z;
  float nu = dot(ray.dir, sun);
  float cloudH = 0.5f * (sky.clouds.x + sky.clouds.y);
  if (cloudsDrawn()) {
    vec2 first, second;
    uint stretches = layerIntervals(R, h, mu, ray.tEnd, first, second);
    if (stretches > 0u) {
      // Sunlight and sky light once, at the middle of the layer where the ray enters it.
      float muSLayer = clamp((r * muS + first.x * nu) / (R + cloudH), -1.0f, 1.0f);
      // Eclipses: the share of the sun seen there, for the sun's light and the sky's (as on the ground).
      float eclipse = eclipseSunVisible(ray.dir * first.x, sun, sky.eclipse);
      vec3 sunLight = eclipse * sunTransmittanceTable(a, cloudH, muSLayer) * a.ozoneSun.y;
      vec3 skyLight = eclipse * skyIrradianceAt(muSLayer);
      float weightedT = 0.0f, weight = 0.0f;
      marchLayer(ray.dir, R, h, mu, first, second, stretches, nu, muS, r, sunLight, skyLight, light, transmittance,
                 weightedT, weight);
      if (weight > 0.0f) tCloud = weightedT / weight;
    }
  }
}

// The length of the ray inside the cloud layer before distance t: what the clouds along a ray
// depend on its end by, so two rays whose ends differ only outside the layer carry the same clouds.
// The layer is the shell between two spheres: the length inside the top's less that inside the bottom's.
float insideBefore(float R, float h, float mu, float hSphere, float t) {
  vec2 hits = raySphere(R, h, mu, hSphere);
  vec2 span = h < hSphere ? vec2(0.0f, max(hits.x, 0.0f)) : (hits.y >= 0.0f ? hits : vec2(0.0f));
  return max(min(t, span.y) - span.x, 0.0f);
}
float layerPathBefore(vec3 dir, float t) {
  float R = sky.atmosphere.radii.x, h = sky.camera.x;
  return insideBefore(R, h, dir.z, sky.clouds.y, t) - insideBefore(R, h, dir.z, sky.clouds.x, t);
}

#endif
