#version 450
// The sky compose pass (issue 4, points 2–4; issue 21, points 1 and 2; DESIGN.md "One frame",
// step 3): runs after the stars, terrain and water were drawn into the HDR target and, per
// pixel, along the view ray:
// - the atmosphere in front of whatever the pixel shows, single and multiple scattering: the
//   sky itself where nothing was drawn, from the sky-view table; aerial perspective on terrain,
//   water and clouds from the aerial-perspective volume (both built this frame by sky_view.comp
//   and aerial_perspective.comp, Hillaire 2020 §5.3–5.4). Compiled with SKY_REFERENCE (the
//   `--sky reference` mode), it marches every pixel's ray instead, with the multiple-scattering
//   table, as the reference the tables are tested against;
// - the cloud layer where the ray crosses it (seed 001 §4.4: three cover images cross-faded,
//   Elias's cover function), lit by the sun through the air, seen from above or below;
// - the clouds' shadow on the ground (toward the sun from the drawn surface);
// - the sun's disc, and the stars faded by the brightness of the sky in front of them;
// - eclipses (common/eclipse.glsl): the scene's other bodies hide the sun from the air and the
//   clouds (the reference march per sample, the tables per sample of the aerial-perspective
//   volume and, for the sky-view table, skyEclipse below).
// Results are written back in place (each invocation reads and writes only its own pixel).
#extension GL_GOOGLE_include_directive : require

#include "shared/noise_params.h"
#include "shared/sky_params.h"

layout(local_size_x = kSkyWorkgroupSize, local_size_y = kSkyWorkgroupSize) in;

// A storage buffer, not a uniform buffer (why: engine/render/sky_pass.cpp, kComposeBindings).
// SkyUniforms has only vec4 and mat4 members, so std430 lays it out as std140 would.
layout(std430, set = 0, binding = kSkyBindingUniforms) readonly buffer Uniforms { SkyUniforms sky; };
layout(set = 0, binding = kSkyBindingColor, rgba16f) uniform image2D color;
layout(set = 0, binding = kSkyBindingDepth) uniform sampler2D depthBuffer;
layout(set = 0, binding = kSkyBindingTransmittance) uniform sampler2D transmittanceTable;
layout(set = 0, binding = kSkyBindingClouds) uniform samplerCube cloudCover;
layout(set = 0, binding = kSkyBindingMultipleScattering) uniform sampler2D multipleScatteringTable;
layout(set = 0, binding = kSkyBindingSkyView) uniform sampler2D skyView;
layout(set = 0, binding = kSkyBindingAerialLight) uniform sampler2DArray aerialLight;
layout(set = 0, binding = kSkyBindingAerialTransmittance) uniform sampler2DArray aerialTransmittance;

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

#define PERM(i) 0u  // the fast hash only
#define OCTAVE_REMAINDER(layer, i) vec4(0.0f)
#define OCTAVE_SHIFT(layer, i) uvec4(0u)
#include "common/noise.glsl"

const float kInfinity = 3.0e38f;

float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

// The cloud layer (issue 20 point 4) is a height field: the column over each point of the
// cover holds cloud from the layer's bottom up to bottom + density · thickness, with extinction
// ∝ density, so a dense column is a tall, optically thick cloud and a thin one a low wisp. A far
// sample reads the density averaged over its footprint (the cover's mip levels): a sparse field
// of small clouds becomes a low, thin haze there, not an opaque deck (gaps stay open).

// Cover density (0..1) at a point `fromCentre` (local frame, relative to the planet's centre),
// cross-faded between the three images (seed 001 eq. 4.2) from mip level `lod`.
float coverDensity(vec3 fromCentre, float lod) {
  vec3 planetDir = normalize(mat3(sky.localToPlanet) * fromCentre);
  float angle = sky.cloudMotion.w;  // the layer drifts eastward: look up where it came from
  float ca = cos(angle), sa = sin(angle);
  vec3 drifted = vec3(ca * planetDir.x + sa * planetDir.y, -sa * planetDir.x + ca * planetDir.y, planetDir.z);
  return dot(textureLod(cloudCover, drifted, lod).rgb, sky.cloudMotion.xyz);
}

// The mip level whose texels span `footprintM` on the layer (radius rLayer).
float coverLod(float footprintM, float rLayer) {
  return clamp(log2(max(footprintM / (sky.cloudShape.x * rLayer), 1.0f)), 0.0f, sky.cloudShape.y);
}

// Henyey–Greenstein phase function (per steradian) for the cosine nu between light and view.
float henyeyGreenstein(float g, float nu) {
  float k = 1.0f + g * g - 2.0f * g * nu;
  return (1.0f - g * g) / (4.0f * kAtmospherePi * k * sqrt(k));
}

// Light scattered toward the eye by a cloud at altitude h in a column of density d, per unit of
// its opacity. Sunlight reaches the point through the column above it: directly, attenuated by
// Beer–Lambert along the slant path (the cloud's width caps it when the sun is low) and forward
// peaked (the silver lining toward the sun); and diffusely, by the two-stream transmission of a
// conservatively scattering slab, T = 1 / (1 + 3/4 (1 − g) τ) (Bohren 1987), which leaves a thick
// cloud's base grey and its top bright. Sky light comes in the same way from above; a tenth of
// it, the light from the ground and the sky's sides, reaches every part.
vec3 cloudLight(float h, float d, float muS, float phase, vec3 sunLight, vec3 skyLight) {
  float thickness = sky.clouds.y - sky.clouds.x;
  float top = sky.clouds.x + d * thickness;
  float depth = max(top - h, 0.0f);
  float extinction = sky.clouds.z * d;
  float slant = min(depth / max(muS, 0.05f), sky.clouds.w * thickness);
  float direct = exp(-extinction * slant);
  // Powder (Schneider & Vos 2015): just inside a cloud the light has not yet been scattered
  // toward the eye, which darkens the rims facing the viewer away from the sun a little.
  float powder = 1.0f - 0.5f * exp(-2.0f * extinction * depth);
  float tauDown = extinction * depth;
  float diffuse = 1.0f / (1.0f + 0.75f * (1.0f - 0.85f) * tauDown / max(muS, 0.2f));
  float diffuseSky = 1.0f / (1.0f + 0.75f * (1.0f - 0.85f) * tauDown);
  const float kAlbedo = 0.95f;
  return kAlbedo * (sunLight * (phase * direct * powder + max(muS, 0.0f) / kAtmospherePi * diffuse) +
                    skyLight / kAtmospherePi * (0.1f + 0.9f * diffuseSky));
}

// The sky irradiance table at sun zenith cosine muS, fading to none by the end of astronomical
// twilight below its first entry (as terrain_surface.glsl's).
vec3 skyIrradianceAt(float muS) {
  float x = clamp((muS + 0.2f) / 1.2f, 0.0f, 1.0f) * 15.0f;
  uint i = min(uint(x), 14u);
  float night = clamp((muS + 0.309f) / 0.109f, 0.0f, 1.0f);
  return night * mix(sky.skyIrradiance[i].rgb, sky.skyIrradiance[i + 1u].rgb, x - float(i));
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

// Composes the layer along one stretch [t0, t1] of the ray: a few segments, nearer ones
// shorter, each reading the cover once at its middle, averaged over the segment's length and
// the pixel's footprint (the mip level), and crossing the column there analytically: the part of
// the segment's altitude range inside the column is the part of its length inside the cloud.
void marchLayer(vec3 dir, float R, float h, float mu, vec2 stretch, float nu, float muSCamera, float r,
                vec3 sunLight, vec3 skyLight, inout vec3 light, inout float transmittance, inout float weightedT,
                inout float weight) {
  float bottom = sky.clouds.x, top = sky.clouds.y;
  float thickness = top - bottom;
  float phase = 0.8f * henyeyGreenstein(0.75f, nu) + 0.2f * henyeyGreenstein(-0.2f, nu);
  float stretchLength = stretch.y - stretch.x;
  float across = sqrt(max(1.0f - mu * mu, 0.0f));
  uint segments = uint(clamp(ceil(stretchLength * across / (1.5f * thickness)), 1.0f, sky.cloudShape.z));
  float hPrevious = altitudeAlong(R, h, mu, stretch.x);
  float tPrevious = stretch.x;
  for (uint i = 1u; i <= segments; ++i) {
    float f = float(i) / float(segments);
    float t = stretch.x + stretchLength * f * f;
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

// The tables' atmosphere between the camera and distance t along the pixel's ray (screen
// position uv): light scattered toward the camera and transmittance, from the two slices of the
// aerial-perspective volume around t (in front of the first, toward nothing at the camera).
void aerialPerspective(vec2 uv, float t, vec2 columnStretch, out vec3 light, out vec3 transmittance) {
  float slice = min(aerialSlice(t, columnStretch), float(kAerialSize) - 1.0f);
  float k0 = floor(slice);
  float f = slice - k0;
  vec3 light1 = textureLod(aerialLight, vec3(uv, max(k0 + 1.0f, 0.0f)), 0.0f).rgb;
  vec3 transmittance1 = textureLod(aerialTransmittance, vec3(uv, max(k0 + 1.0f, 0.0f)), 0.0f).rgb;
  if (k0 < 0.0f) {
    light = light1 * f;
    transmittance = mix(vec3(1.0f), transmittance1, f);
    return;
  }
  if (f == 0.0f || k0 + 1.0f > float(kAerialSize) - 1.0f) {
    light = textureLod(aerialLight, vec3(uv, k0), 0.0f).rgb;
    transmittance = textureLod(aerialTransmittance, vec3(uv, k0), 0.0f).rgb;
    return;
  }
  light = mix(textureLod(aerialLight, vec3(uv, k0), 0.0f).rgb, light1, f);
  transmittance = mix(textureLod(aerialTransmittance, vec3(uv, k0), 0.0f).rgb, transmittance1, f);
}

// The sky along the whole ray from the sky-view table (black where the ray misses the air).
vec3 skyViewRadiance(vec3 dir, vec3 sun, float h, float hGround) {
  vec2 range = skyViewZenithRange(sky.atmosphere, h, hGround);
  float theta = atan(length(vec2(dir.x, dir.y)), dir.z);  // not acos (skyViewZenithRange says why)
  if (theta < range.x) return vec3(0.0f);
  float v = unitToTexel(skyViewV(theta, range), float(kSkyViewHeight));
  // Each half of the rows (above and below the ground's horizon) is read only from its own
  // texels: the two sides of the horizon are the sky and the ground.
  float middle = 0.5f * float(kSkyViewHeight);
  v = theta <= range.y ? min(v, (middle - 0.5f) / float(kSkyViewHeight)) : max(v, (middle + 0.5f) / float(kSkyViewHeight));
  vec2 viewFlat = vec2(dir.x, dir.y), sunFlat = vec2(sun.x, sun.y);
  float lengths = length(viewFlat) * length(sunFlat);
  float cosPhi = lengths > 1e-7f ? clamp(dot(viewFlat, sunFlat) / lengths, -1.0f, 1.0f) : 1.0f;
  float u = unitToTexel(acos(cosPhi) / kAtmospherePi, float(kSkyViewWidth));
  return textureLod(skyView, vec2(u, v), 0.0f).rgb;
}

// The share of the sun seen by the air along a ray that met no geometry, for the sky-view table,
// which has no place along the ray to hold an eclipse: the mean over four points of the ray's
// stretch through the air, spread as the table's steps are (gathered toward the camera from
// inside the air, even from above it). From inside an eclipse's shadow the whole sky darkens
// with it (the horizon's glow from outside the shadow is missed); from orbit the limb does where
// the shadow crosses it.
float skyEclipse(vec3 dir, vec2 stretch, bool fromInside) {
  if (!(stretch.y > stretch.x) || !(sky.eclipse.sun.y > 0.5f)) return 1.0f;
  float sum = 0.0f;
  for (uint k = 0u; k < 4u; ++k) {
    float x = (float(k) + 0.5f) / 4.0f;
    float t = stretch.x + (stretch.y - stretch.x) * (fromInside ? x * x : x);
    sum += eclipseSunVisible(dir * t, sky.sunLocal.xyz, sky.eclipse);
  }
  return 0.25f * sum;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(sky.extent.x) || pixel.y >= int(sky.extent.y)) return;
  vec4 stored = imageLoad(color, pixel);
  vec3 surface = stored.rgb;
  vec2 ndc = (vec2(pixel) + 0.5f) / sky.extent.xy * 2.0f - 1.0f;
  vec4 nearPoint = sky.clipToLocal * vec4(ndc, 1.0f, 1.0f);
  vec3 dir = normalize(nearPoint.xyz / nearPoint.w);
  float depth = texelFetch(depthBuffer, pixel, 0).r;
  bool geometry = depth > 0.0f;
  // Reversed Z: depth = near / view distance; the ray length follows from the view axis.
  float tGeometry = geometry ? sky.camera.y / depth / max(dot(dir, sky.forward.xyz), 1e-6f) : kInfinity;

  AtmosphereParams a = sky.atmosphere;
  float R = a.radii.x;
  float h = sky.camera.x;
  float r = R + h;
  float mu = dir.z;
  vec3 sun = sky.sunLocal.xyz;
  float muS = sun.z;
  float nu = dot(dir, sun);
  // The sea is drawn on the mesh's flat triangles, up to a few hundred metres below the sphere
  // in their middles (chord sag) on the coarse rings seen from orbit; ending the march there
  // put a faint grid of the triangles into the haze. The march ends at the sea's sphere when
  // that is nearer than what was drawn.
  float lowest = sky.surface.x;
  bool hasSea = sky.surface.y > 0.5f;
  if (geometry && hasSea && h > lowest) {
    vec2 sea = raySphere(R, h, mu, lowest);
    if (sea.x >= 0.0f && sea.x < tGeometry) tGeometry = sea.x;
  }
  // A ray that met no geometry has met the ground only below the lowest surface: without a sea,
  // basins below the radius sphere are seen past its horizon (the mesh may end before them), and
  // counting the radius sphere as ground drew those rays black.
  float hGround = sky.surface.z;  // the radius sphere with a sea, else min(lowest, 0)
  vec2 ground = raySphere(R, h, mu, hGround);
  bool seesGround = mu < 0.0f && ground.x >= 0.0f;
  float tEnd = geometry ? tGeometry : (seesGround ? ground.x : kInfinity);

  // Cloud shadow on the drawn surface: the column where the ray toward the sun crosses the
  // middle of the layer, crossed at the sun's slant (the cloud's width caps it), blocks the
  // sun's direct light; sky light still comes in.
  bool clouds = sky.cameraPlanet.w > 0.5f && a.radii.w > 0.5f;
  float cloudH = 0.5f * (sky.clouds.x + sky.clouds.y);
  if (geometry && clouds) {
    float hSurface = altitudeAlong(R, h, mu, tGeometry);
    float muSSurface = (r * muS + tGeometry * nu) / (R + hSurface);
    if (hSurface < cloudH && muSSurface > 0.0f) {
      float toLayer = raySphere(R, hSurface, muSSurface, cloudH).x;
      vec3 layerPoint = dir * tGeometry + sun * toLayer;  // from the camera
      vec3 fromCentre = vec3(layerPoint.x, layerPoint.y, R + h + layerPoint.z);
      float footprint = max(tGeometry * sky.extent.z, 1000.0f);
      float d = coverDensity(fromCentre, coverLod(footprint, R + cloudH));
      float thickness = sky.clouds.y - sky.clouds.x;
      float slant = min(d * thickness / muSSurface, sky.clouds.w * thickness);
      surface *= 1.0f - 0.75f * (1.0f - exp(-sky.clouds.z * d * slant));
    }
  }

  // The cloud layer along the view ray, composed into the march below at the distance its
  // opacity is centred on.
  vec3 cloudLightSum = vec3(0.0f);
  float cloudTransmittance = 1.0f;
  float tCloud = -1.0f;
  if (clouds) {
    vec2 first, second;
    uint stretches = layerIntervals(R, h, mu, tEnd, first, second);
    if (stretches > 0u) {
      // Sunlight and sky light once, at the middle of the layer where the ray enters it.
      float muSLayer = clamp((r * muS + first.x * nu) / (R + cloudH), -1.0f, 1.0f);
      // Eclipses: the share of the sun seen there, for the sun's light and the sky's (as on the ground).
      float eclipse = eclipseSunVisible(dir * first.x, sun, sky.eclipse);
      vec3 sunLight = eclipse * sunTransmittanceTable(a, cloudH, muSLayer) * a.ozoneSun.y;
      vec3 skyLight = eclipse * skyIrradianceAt(muSLayer);
      float weightedT = 0.0f, weight = 0.0f;
      marchLayer(dir, R, h, mu, first, nu, muS, r, sunLight, skyLight, cloudLightSum, cloudTransmittance, weightedT,
                 weight);
      if (stretches > 1u && cloudTransmittance >= 0.01f)
        marchLayer(dir, R, h, mu, second, nu, muS, r, sunLight, skyLight, cloudLightSum, cloudTransmittance,
                   weightedT, weight);
      if (weight > 0.0f) tCloud = weightedT / weight;
    }
  }

  vec3 inscatter = vec3(0.0f);
  vec3 transmittance = vec3(1.0f);
#ifdef SKY_REFERENCE
  if (a.radii.w > 0.5f) {
    vec2 stretch = atmosphereStretch(a, h, mu, hGround);
    float tStart = stretch.x;
    // (A scene's nearer body may hide the whole shell: then the ray never enters it.)
    if (stretch.y > tStart && min(tEnd, stretch.y) > tStart) {
      float tStop = min(tEnd, stretch.y);
      // Segment boundaries: the start, the layer crossings in between, the end.
      float cuts[3];
      uint cutCount = 0u;
      cuts[cutCount++] = tStart;
      if (tCloud > tStart && tCloud < tStop) cuts[cutCount++] = tCloud;
      cuts[cutCount++] = tStop;
      float total = max(tStop - tStart, 1e-3f);
      uint samples = uint(sky.forward.w);
      for (uint i = 0u; i + 1u < cutCount; ++i) {
        float t0 = cuts[i];
        float t1 = cuts[i + 1u];
        float h0 = altitudeAlong(R, h, mu, t0);
        float r0 = R + h0;
        float mu0 = clamp((r * mu + t0) / r0, -1.0f, 1.0f);
        float muS0 = clamp((r * muS + t0 * nu) / r0, -1.0f, 1.0f);
        if (i > 0u) {  // the cloud layer at t0
          inscatter += transmittance * cloudLightSum;
          transmittance *= cloudTransmittance;
        }
        uint steps = max(2u, uint(ceil(float(samples) * (t1 - t0) / total)));
        marchStart = dir * t0;
        marchDirection = dir;
        vec3 segmentSingle, segmentLight, segmentTransmittance;
        scatteringAlong(a, h0, mu0, muS0, nu, t1 - t0, steps, false, segmentSingle, segmentLight, segmentTransmittance);
        inscatter += transmittance * segmentLight;
        transmittance *= segmentTransmittance;
      }
    }
  }
#else
  if (a.radii.w > 0.5f) {
    vec2 uv = (vec2(pixel) + 0.5f) / sky.extent.xy;
    vec2 columnStretch = aerialColumnStretch(R, h, mu, hGround);
    vec2 stretch = atmosphereStretch(a, h, mu, hGround);
    // Geometry past the far side of the air (another body, a ring, seen through this one's
    // limb or from under its sky) is seen through the whole crossing, as the sky around it is:
    // the same tables, so its outline leaves no seam in the haze. (From above, the volume's
    // columns end halfway through a crossing that misses the ground.)
    bool pastAir = geometry && !seesGround && stretch.y > stretch.x && tGeometry >= stretch.y;
    if (geometry && !pastAir) {
      aerialPerspective(uv, tGeometry, columnStretch, inscatter, transmittance);
    } else {
      inscatter = skyViewRadiance(dir, sun, h, hGround);
      // Toward the sun's disc, the stars and geometry past the air: the transmittance table
      // from where the ray enters the air (the ground case is set below).
      inscatter *= skyEclipse(dir, stretch, h < a.radii.y);
      if (!seesGround && stretch.y > stretch.x) {
        float h0 = altitudeAlong(R, h, mu, stretch.x);
        float mu0 = clamp((r * mu + stretch.x) / (R + h0), -1.0f, 1.0f);
        transmittance = textureLod(transmittanceTable, transmittanceUv(a, h0, mu0), 0.0f).rgb;
      }
    }
    if (tCloud >= 0.0f) {
      // The layer at tCloud splits the ray: the air in front of it, the cloud, and the rest of
      // the ray's light (all of it less the part in front) seen through the cloud.
      vec3 frontLight, frontTransmittance;
      aerialPerspective(uv, tCloud, columnStretch, frontLight, frontTransmittance);
      inscatter = frontLight + frontTransmittance * cloudLightSum +
                  cloudTransmittance * max(inscatter - frontLight, vec3(0.0f));
      transmittance *= cloudTransmittance;
    }
  }
#endif
  // A ray that met no geometry but the ground sphere shows neither stars nor the sun through it.
  if (seesGround && !geometry) transmittance = vec3(0.0f);

  vec3 result;
  if (geometry) {
    result = surface * transmittance + inscatter;
  } else {
    // Background: stars (drawn first, where nothing covered them) fade out as the sky in
    // front of them brightens on the display, as the eye would lose them.
    float skyDisplay = luminance(inscatter) * sky.camera.z;
    // (A clear noon sky is ~0.07 here, civil twilight ~0.002.)
    float starFade = 1.0f - smoothstep(0.001f, 0.01f, skyDisplay);
    result = surface * transmittance * starFade + inscatter;
    if (!seesGround && sky.extent.w > 0.5f) {
      float sunRadius = a.radii.z;
      float cosRadius = cos(sunRadius);
      float disc = smoothstep(cosRadius - 0.2f * sunRadius * sunRadius, cosRadius, nu);
      float discRadiance = a.ozoneSun.y / (kAtmospherePi * sunRadius * sunRadius);
      result += disc * discRadiance * transmittance;
    }
  }
  // Keep the target finite whatever the inputs (a NaN would spread through the tonemap).
  result = clamp(result, vec3(0.0f), vec3(6.0e4f));
  imageStore(color, pixel, vec4(result, 1.0f));
}
