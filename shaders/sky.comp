#version 450
// The sky compose pass (issue 4, points 2–4; DESIGN.md "One frame", step 3): runs after the
// stars, terrain and water were drawn into the HDR target and, per pixel, along the view ray:
// - single scattering of the atmosphere in front of whatever the pixel shows (the sky itself
//   where nothing was drawn, aerial perspective on terrain and water), with the sun's
//   transmittance from the table (shaders/common/atmosphere.glsl);
// - the cloud layer where the ray crosses it (seed 001 §4.4: three cover images cross-faded,
//   Elias's cover function), lit by the sun through the air, seen from above or below;
// - the clouds' shadow on the ground (toward the sun from the drawn surface);
// - the sun's disc, and the stars faded by the brightness of the sky in front of them.
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

#include "atmosphere_lookup.glsl"

#define PERM(i) 0u  // the fast hash only
#define OCTAVE_REMAINDER(layer, i) vec4(0.0f)
#define OCTAVE_SHIFT(layer, i) uvec4(0u)
#include "common/noise.glsl"

const float kInfinity = 3.0e38f;

float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

// Elias's cloud density d = 1 − S^max(0, v − (1 − coverage)) (seed 001 eq. 4.1) at the point
// of the layer `t` metres along the ray; v cross-fades the three cover images (eq. 4.2) and
// adds a little per-pixel detail noise, finer than the cube map's texels.
float cloudDensity(vec3 rayLocal, float t) {
  float R = sky.atmosphere.radii.x;
  // The point relative to the planet's centre (local frame: centre at −R on z): planet size
  // in float is fine here, cloud detail needs metres.
  vec3 fromCentre = vec3(rayLocal.xy * t, R + sky.camera.x + rayLocal.z * t);
  vec3 planetDir = normalize(mat3(sky.localToPlanet) * fromCentre);
  float angle = sky.cloudMotion.w;  // the layer drifts eastward: look up where it came from
  float ca = cos(angle), sa = sin(angle);
  vec3 drifted = vec3(ca * planetDir.x + sa * planetDir.y, -sa * planetDir.x + ca * planetDir.y, planetDir.z);
  vec3 cover = textureLod(cloudCover, drifted, 0.0f).rgb;
  float v = dot(cover, sky.cloudMotion.xyz);
  NoiseParams detail;
  detail.type = kNoiseFbm;
  detail.octaves = 3u;
  detail.hash = kNoiseHashFast;
  detail.seedMix = floatBitsToUint(sky.cloudShape.w);
  detail.lacunarity = 2.0f;
  detail.octaveWeight = 0.5f;
  detail.offset = 0.0f;
  detail.gain = 0.0f;
  detail.lastOctaveWeight = 1.0f;
  // The detail fades out where a pixel spans more than half its wavelength (no aliasing).
  float footprint = t * sky.extent.z * sky.cloudShape.y;
  float detailWeight = 1.0f - smoothstep(0.25f, 0.5f, footprint);
  if (detailWeight > 0.0f)
    v += detailWeight * sky.cloudShape.z * evaluateFbm(detail, drifted * (R * sky.cloudShape.y));
  float excess = max(0.0f, v - (1.0f - sky.clouds.z));
  return 1.0f - exp(log(sky.clouds.w) * excess);
}

// Opacity of the layer crossed at zenith cosine mu (the slant path is longer).
float cloudAlpha(float density, float mu) {
  float tau = sky.cloudShape.x * density / max(abs(mu), 0.12f);
  return 1.0f - exp(-tau);
}

// Radiance of the cloud layer at altitude h, sun zenith cosine muS there, seen from `above`.
vec3 cloudRadiance(float h, float muS, float alpha, bool above) {
  vec3 sunLight = sunTransmittanceTable(sky.atmosphere, h, muS) * sky.atmosphere.ozoneSun.y;
  // A thick layer lets little sunlight through to the side away from the sun.
  bool sunSide = above == (muS > 0.0f);
  float through = sunSide ? 1.0f : mix(1.0f, 0.18f, alpha);
  const float kAlbedo = 0.9f;
  float x = clamp((muS + 0.2f) / 1.2f, 0.0f, 1.0f) * 15.0f;
  uint i = min(uint(x), 14u);
  vec3 ambient = mix(sky.skyIrradiance[i].rgb, sky.skyIrradiance[i + 1u].rgb, x - float(i));
  return kAlbedo / kAtmospherePi * (sunLight * sqrt(max(muS, 0.0f)) * through + ambient);
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
  vec2 ground = raySphere(R, h, mu, hasSea ? 0.0f : min(lowest, 0.0f));
  bool seesGround = mu < 0.0f && ground.x >= 0.0f;
  float tEnd = geometry ? tGeometry : (seesGround ? ground.x : kInfinity);

  vec3 inscatter = vec3(0.0f);
  vec3 transmittance = vec3(1.0f);

  // Cloud shadow on the drawn surface: how much of the sun the layer blocks above it.
  bool clouds = sky.cameraPlanet.w > 0.5f && a.radii.w > 0.5f;
  float cloudH = 0.5f * (sky.clouds.x + sky.clouds.y);
  if (geometry && clouds) {
    float hSurface = altitudeAlong(R, h, mu, tGeometry);
    float muSSurface = (r * muS + tGeometry * nu) / (R + hSurface);
    if (hSurface < cloudH && muSSurface > 0.0f) {
      float toLayer = raySphere(R, hSurface, muSSurface, cloudH).x;
      vec3 surfacePoint = dir * tGeometry + vec3(0.0f, 0.0f, h);  // from the anchor
      vec3 layerPoint = surfacePoint + sun * toLayer;
      // cloudDensity wants a camera ray: express the layer point as one from the camera.
      vec3 fromCamera = layerPoint - vec3(0.0f, 0.0f, h);
      float reach = length(fromCamera);
      float density = cloudDensity(fromCamera / reach, reach);
      surface *= 1.0f - 0.6f * cloudAlpha(density, muSSurface);
    }
  }

  if (a.radii.w > 0.5f) {
    float top = a.radii.y;
    // Outside (or exactly on) the top sphere the ray enters and leaves it; inside, it leaves.
    vec2 topHits = raySphere(R, h, mu, top);
    bool outside = h >= top;
    float tStart = outside ? topHits.x : 0.0f;
    float tExit = outside ? topHits.y : topHits.x;
    // (A scene's nearer body may hide the whole shell: then the ray never enters it.)
    if (tStart >= 0.0f && tExit > tStart && min(tEnd, tExit) > tStart) {
      float tStop = min(tEnd, tExit);
      // Segment boundaries: the start, the layer crossings in between, the end.
      float cuts[4];
      uint cutCount = 0u;
      cuts[cutCount++] = tStart;
      if (clouds) {
        vec2 layer = raySphere(R, h, mu, cloudH);
        if (layer.x > tStart && layer.x < tStop) cuts[cutCount++] = layer.x;
        if (layer.y > tStart && layer.y < tStop) cuts[cutCount++] = layer.y;
      }
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
        if (i > 0u) {  // a layer crossing at t0
          float density = cloudDensity(dir, t0);
          float alpha = cloudAlpha(density, mu0);
          bool above = mu0 < 0.0f;  // coming down onto the layer: seen from above
          inscatter += transmittance * alpha * cloudRadiance(h0, muS0, alpha, above);
          transmittance *= 1.0f - alpha;
        }
        uint steps = max(2u, uint(ceil(float(samples) * (t1 - t0) / total)));
        vec3 segmentLight, segmentTransmittance;
        singleScattering(a, h0, mu0, muS0, nu, t1 - t0, steps, segmentLight, segmentTransmittance);
        inscatter += transmittance * segmentLight;
        transmittance *= segmentTransmittance;
      }
    }
  }

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
