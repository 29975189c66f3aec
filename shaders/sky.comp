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
// - the cloud layer where the ray crosses it (sky_compose.glsl), lit by the sun through the air,
//   seen from above or below, and the clouds' shadow on the ground (toward the sun from the drawn
//   surface). The tables read both from the cloud pass (sky_clouds.comp), which evaluates them
//   at half the resolution in each axis (full from far away), and upsample them here guided by
//   each ray's end (why: upsampledClouds); the reference evaluates them at every pixel;
// - the sun's disc, and the stars faded by the brightness of the sky in front of them;
// - eclipses (common/eclipse.glsl): the scene's other bodies hide the sun from the air and the
//   clouds (the reference march per sample, the tables per sample of the aerial-perspective
//   volume and, for the sky-view table, skyEclipse in sky_compose.glsl).
// Results are written back in place (each invocation reads and writes only its own pixel).
#extension GL_GOOGLE_include_directive : require

#include "sky_compose.glsl"
#include "shared/exposure_params.h"
#include "common/exposure.glsl"
#include "shared/star_params.h"
#include "common/star_visibility.glsl"

// Whether the body has airglow (its preset's airglow_cd_m2), as a specialization constant: the
// shell's two ray-sphere intersections cost lavapipe up to a millisecond a frame, for every body.
layout(constant_id = 3) const bool kSpecAirglow = true;

#ifndef SKY_REFERENCE
// The class of the tiles this pipeline composes (kSkyTileMixed, kSkyTileSky, kSkyTileAerial,
// kSkyTileAerialClear and the last two's near kinds), as a specialization constant: each class's
// tiles are dispatched by a pipeline of their own (SkyPass::recordCompose, from the lists of
// sky_classify.comp and sky_cloud_classify.comp), so that a tile of sky runs no
// aerial-perspective code, a tile of ground clear of the clouds none of the cloud pass's samples
// (its shadow from the clouds' shadow table), and a near one neither the sky-view table's light
// nor the volume's transmittance: lavapipe runs both sides of a branch for every pixel.
layout(constant_id = 2) const uint kSpecTileClass = kSkyTileMixed;
// Tiles of ground clear of the clouds; tiles of ground whose rays all end well short of the
// ground sphere (shared/sky_params.h, kSkyTileNear).
const bool kTileClear = kSpecTileClass == kSkyTileAerialClear || kSpecTileClass == kSkyTileAerialClearNear;
const bool kTileNear = kSpecTileClass == kSkyTileAerialNear || kSpecTileClass == kSkyTileAerialClearNear;

layout(set = 0, binding = kSkyBindingCloudLight, rgba16f) uniform readonly image2D cloudSampleLight;
layout(set = 0, binding = kSkyBindingCloudEnd, rgba32f) uniform readonly image2D cloudSampleEnd;

// How far apart two rays' lengths inside the cloud layer (before their ends) may be for one to
// lend the other its clouds, as a share of the longer (plus kPathSlackM): at a silhouette the
// samples of the object and of what is behind it differ by far more.
const float kPathTolerance = 0.1f;
const float kPathSlackM = 100.0f;
// The same for the drawn surfaces' distances, which the clouds' shadow on them depends on.
const float kDistanceTolerance = 0.1f;

// The cloud pass's results at this pixel (sky_clouds.comp): its light composited with the air
// in front of it, its transmittance, and its shadow on the drawn surface. Of the four nearest
// samples of the pass, each counts with its bilinear weight times how well the layer path
// before its ray's end agrees with this pixel's (Gaussian in the difference, relative to the
// best agreeing sample, which therefore always counts): next to a mountain's silhouette the sky
// takes its clouds from the sky samples and the mountain none from them (the cloud pass ends a
// sample's ray at the nearer surface of its block, so each side has samples of its own). The
// shadow counts only samples of drawn surfaces at a distance like this pixel's.
void upsampledClouds(ivec2 pixel, ViewRay ray, out vec3 composite, out float transmittance, out float shadow) {
  float scale = sky.cloudShape.w;
  ivec2 last = (ivec2(sky.extent.xy) + int(scale) - 1) / int(scale) - 1;
  vec2 q = (vec2(pixel) + 0.5f) / scale - 0.5f;  // sample i is centred on pixel edge scale · (i + 1/2)
  vec2 base = floor(q);
  vec2 f = q - base;
  float pathHere = layerPathBefore(ray.dir, ray.tEnd);
  vec4 light[4];
  vec4 end[4];
  float bilinear[4], pathMismatch[4], distanceMismatch[4];
  float bestPath = 1e30f, bestDistance = 1e30f;
  for (int k = 0; k < 4; ++k) {
    ivec2 offset = ivec2(k & 1, k >> 1);
    ivec2 cell = clamp(ivec2(base) + offset, ivec2(0), last);
    light[k] = imageLoad(cloudSampleLight, cell);
    light[k].rgb *= 1.0f / kSkyHalfLightScale;
    end[k] = imageLoad(cloudSampleEnd, cell);  // x: distance to the drawn surface, y: layer path, z: shadow
    bilinear[k] = (offset.x == 1 ? f.x : 1.0f - f.x) * (offset.y == 1 ? f.y : 1.0f - f.y);
    float path = end[k].y;
    float x = abs(path - pathHere) / (kPathTolerance * max(path, pathHere) + kPathSlackM);
    pathMismatch[k] = min(x * x, 1e4f);
    bestPath = min(bestPath, pathMismatch[k]);
    // Only drawn surfaces near this pixel's distance (a sample of the sky has none: kInfinity).
    float t = end[k].x;
    float y = abs(t - ray.tGeometry) / (kDistanceTolerance * min(t, ray.tGeometry) + 1.0f);
    distanceMismatch[k] = min(y * y, 1e4f);
    bestDistance = min(bestDistance, distanceMismatch[k]);
  }
  vec4 sum = vec4(0.0f);
  float weightSum = 0.0f, shadowSum = 0.0f, shadowWeightSum = 0.0f;
  for (int k = 0; k < 4; ++k) {
    float w = bilinear[k] * exp(bestPath - pathMismatch[k]);
    sum += w * light[k];
    weightSum += w;
    float ws = bilinear[k] * exp(bestDistance - distanceMismatch[k]);
    shadowSum += ws * end[k].z;
    shadowWeightSum += ws;
  }
  composite = sum.rgb / weightSum;
  transmittance = sum.a / weightSum;
  shadow = shadowSum / shadowWeightSum;
}
#endif

// The clouds' shadow on what was drawn at a pixel, as a factor of its light: on the share of it
// that the target's alpha says still shows the ground (1 on the ground; the sea leaves only the
// floor it shows through, WaterPass), since the sea shades its own light under the clouds.
float cloudShadowOnDrawn(float shadow, float shadowedShare) { return mix(1.0f, shadow, clamp(shadowedShare, 0.0f, 1.0f)); }

void main() {
  // The dispatch covers the pixels where the air or the sun can show (sky.region); elsewhere a ray
  // meets no air, and the pixel keeps what was drawn. The tables' compose runs this class's
  // tiles of the region (a workgroup each).
#ifdef SKY_REFERENCE
  ivec2 group = ivec2(gl_WorkGroupID.xy);
#else
  ivec2 group = listedTile(kSpecTileClass, gl_WorkGroupID.x);
#endif
  ivec2 pixel = ivec2(sky.region.xy) + group * int(kSkyWorkgroupSize) + ivec2(gl_LocalInvocationID.xy);
  if (pixel.x >= int(sky.extent.x) || pixel.y >= int(sky.extent.y)) return;
  vec4 stored = imageLoad(color, pixel);
  vec3 surface = stored.rgb;
  ViewRay ray = viewRay(vec2(pixel) + 0.5f, texelFetch(depthBuffer, pixel, 0).r);
  vec3 dir = ray.dir;
#ifdef SKY_REFERENCE
  bool geometry = ray.geometry;
#else
  bool geometry = kSpecTileClass == kSkyTileSky ? false : kSpecTileClass != kSkyTileMixed ? true : ray.geometry;
#endif
  float tGeometry = ray.tGeometry;
  bool seesGround = ray.seesGround;
  float hGround = ray.hGround;
  float tEnd = ray.tEnd;

  AtmosphereParams a = sky.atmosphere;
  float R = a.radii.x;
  float h = sky.camera.x;
  float r = R + h;
  float mu = dir.z;
  vec3 sun = sky.sunLocal.xyz;
  float muS = sun.z;
  float nu = dot(dir, sun);

  vec3 inscatter = vec3(0.0f);
  vec3 transmittance = vec3(1.0f);
#ifdef SKY_REFERENCE
  // The clouds and their shadow at this pixel (cloudShadowOnDrawn); the layer composed into the
  // march below at the distance its opacity is centred on.
  surface *= cloudShadowOnDrawn(cloudShadow(ray), stored.a);
  vec3 cloudLightSum;
  float cloudTransmittance, tCloud;
  cloudsAlong(ray, cloudLightSum, cloudTransmittance, tCloud);
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
        scatteringAlong(a, h0, mu0, muS0, nu, t1 - t0, steps, kStepsEqual, segmentSingle, segmentLight,
                        segmentTransmittance);
        inscatter += transmittance * segmentLight;
        transmittance *= segmentTransmittance;
      }
    }
    // The airglow: its far part seen through all the air and the clouds along the ray, the part
    // in front of the air (from above the shell) as it is.
    vec3 airglowNear = vec3(0.0f), airglowFar = vec3(0.0f);
    if (kSpecAirglow) airglowAlong(sky.airglow, R, h, mu, tEnd, airglowNear, airglowFar);
    inscatter += transmittance * airglowFar + airglowNear;
  }
#else
  vec3 cloudComposite;
  float cloudTransmittance, cloudShadowFactor;
  cloudComposite = vec3(0.0f);
  cloudTransmittance = 1.0f;
  cloudShadowFactor = 1.0f;
  // A tile clear of the clouds has none in front of it (composite 0, transmittance 1) and takes
  // its shadow at each pixel from the clouds' shadow table.
  if (kSpecClouds && kTileClear)
    cloudShadowFactor = cloudShadowFromTable(ray);
  else if (kSpecClouds)
    upsampledClouds(pixel, ray, cloudComposite, cloudTransmittance, cloudShadowFactor);
  if (geometry) surface *= cloudShadowOnDrawn(cloudShadowFactor, stored.a);
  if (a.radii.w > 0.5f) {
    vec2 uv = (vec2(pixel) + 0.5f) / sky.extent.xy;
    // (A tile clear of the clouds is seen from below them, so from inside the air: its columns
    // need no stretch, sky_aerial.glsl.)
    vec2 stretch = kTileClear ? vec2(0.0f, -1.0f) : atmosphereStretch(a, h, mu, hGround);
    vec2 columnStretch = aerialColumnStretchOf(stretch, ray.groundHits, R, h, mu);
    // Geometry past the far side of the air (another body, a ring, seen through this one's
    // limb or from under its sky) is seen through the whole crossing, as the sky around it is:
    // the same tables, so its outline leaves no seam in the haze. (From above, the volume's
    // columns end halfway through a crossing that misses the ground.) A tile of one class takes
    // one side only: its pipeline has no code of the other (sky_classify.comp says why that is
    // exact).
    bool pastAir = geometry && !seesGround && stretch.y > stretch.x && tGeometry >= stretch.y;
#ifdef SKY_REFERENCE
    bool aerial = geometry && !pastAir;
#else
    bool aerial = kSpecTileClass == kSkyTileSky ? false : kSpecTileClass != kSkyTileMixed ? true : geometry && !pastAir;
#endif
    if (aerial) {
      aerialPerspective(uv, ray, tGeometry, columnStretch, kTileNear, kTileNear || kTileClear, inscatter,
                        transmittance);
    } else {
      inscatter = skyViewAlong(dir, h, hGround).rgb;
      // Toward the sun's disc, the stars and geometry past the air: the transmittance table
      // from where the ray enters the air (the ground case is set below).
      inscatter *= skyEclipse(dir, stretch, skyStepSpacing(a, h, seesGround));
      if (!seesGround && stretch.y > stretch.x) {
        float h0 = altitudeAlong(R, h, mu, stretch.x);
        float mu0 = clamp((r * mu + stretch.x) / (R + h0), -1.0f, 1.0f);
        transmittance = textureLod(transmittanceTable, transmittanceUv(a, h0, mu0), 0.0f).rgb;
      }
    }
    // The airglow (common/atmosphere.glsl): the shell's light beyond the air is seen through it
    // (the transmittance from where the ray enters the air, or to what was drawn) and through
    // the clouds; from above the shell, its part in front of the air is seen as it is.
    // A tile clear of the clouds is seen from below them: its rays end on the ground before they
    // could reach the shell (the altitude along a ray is highest at one of its ends).
    vec3 airglowNear = vec3(0.0f), airglowFar = vec3(0.0f);
    if (kSpecAirglow && !kTileClear)
      airglowAlong(sky.airglow, R, h, mu, tEnd, airglowNear, airglowFar);
    inscatter += transmittance * airglowFar;
    // The layer splits the ray: the air in front of it and the cloud (the composite), and the
    // rest of the ray's light seen through the cloud.
    inscatter = cloudComposite + cloudTransmittance * inscatter + airglowNear;
    transmittance *= cloudTransmittance;
  }
#endif
  // A ray that met no geometry but the ground sphere shows neither stars nor the sun through it.
  if (seesGround && !geometry) transmittance = vec3(0.0f);

  vec3 result;
  float starLuminance = 0.0f;  // of the stars' light in `result`
  float starFlux = -stored.a;  // on the background: the stars' relative flux (stars.frag)
  if (geometry) {
    result = surface * transmittance + inscatter;
  } else {
    // Background: stars (drawn first, where nothing covered them), each faded where the eye
    // would lose it against the sky in front: its magnitude (the relative flux stars.frag left in
    // alpha, through the air's transmittance) against the sky's radiance. A pixel with no star
    // (another body's air seen past this one's) keeps its light.
    float starFade = starFlux > 0.0f ? starVisibleShare(starFlux * luminance(transmittance), luminance(inscatter)) : 1.0f;
    result = surface * transmittance * starFade + inscatter;
    if (starFlux > 0.0f) starLuminance = luminance(surface * transmittance * starFade);
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
  // Alpha: from the frame's last compose (the camera's body's, which draws the sun), the mark of
  // a composed pixel plus the stars' share of its light, which auto exposure neither measures
  // nor applies (shared/exposure_params.h). From a farther body's: 1 on geometry, the stars'
  // negated relative flux kept on the background, for the compose of a nearer body's air, which
  // fades them against its own sky. From any, on geometry with city lights, the mark of their
  // share of the composed light: what reaches the camera of the share the terrain wrote.
  bool lastCompose = sky.extent.w > 0.5f;
  float total = luminance(result);
  float starShare = total > 0.0f ? clamp(starLuminance / total, 0.0f, 1.0f) : 0.0f;
  float lightsShare = 0.0f;
  if (geometry && total > 0.0f)
    lightsShare = exposureLightsShare(stored.a) * clamp(luminance(surface * transmittance) / total, 0.0f, 1.0f);
  float alpha = lastCompose ? kExposureComposedAlpha + starShare : geometry ? 1.0f : stored.a;
  alpha = exposureLightsMark(lightsShare, alpha);
  imageStore(color, pixel, vec4(result, alpha));
}
