#version 450
// The cloud pass of the sky (issue 21, point 7): the cloud layer along the view rays and its
// shadow on the drawn surfaces, at half the frame's resolution in each axis, before the compose
// pass (sky.comp) upsamples them. On a CPU device every pixel pays for every branch of the
// layer's march, so a quarter of the rays is most of the saving; the cover's texels span many
// pixels except from far above the layer, where the pass runs at full resolution instead
// (SkyUniforms::cloudShape.w, engine/render/sky_pass.h: cloudPassScale).
// Each sample stands for a 2×2 block of pixels: its ray goes through the block's centre and, in
// a block across a silhouette, ends at the nearer object, so such a block holds the nearer
// object's clouds and the pixels beside it find the farther side's in the next block.
// Per sample it writes the cloud's light already composited with the air in front of it (the
// aerial-perspective volume at the distance its opacity is centred on) and its transmittance,
// and the ray's end, its path through the layer before it and the shadow there (cloudSampleEnd).
// It runs the tiles of sky_cloud_classify.comp's lists, each list with a pipeline of its own:
// where no ray of a tile can reach the layer, the pipeline has no march (the march would find
// nothing there and write the same) and reads the shadow from the clouds' shadow table
// (sky_cloud_shadow.comp), not the cover; such a tile that only the compose's tiles clear of the
// clouds read is not run at all (they read no sample).
#extension GL_GOOGLE_include_directive : require

#include "sky_compose.glsl"

// The list of tiles this pipeline runs (kSkyCloudTileMarch, kSkyCloudTileClear).
layout(constant_id = 2) const uint kSpecCloudTileClass = kSkyCloudTileMarch;

layout(set = 0, binding = kSkyBindingCloudLight, rgba16f) uniform writeonly image2D cloudSampleLight;
layout(set = 0, binding = kSkyBindingCloudEnd, rgba32f) uniform writeonly image2D cloudSampleEnd;

// The share of the whole ray's opacity in front of a cloud from which the light in front of it
// is the sky-view table's (main).
const float kCloudSkyShareFrom = 0.9f;
const float kCloudSkyShareTo = 0.98f;

// The largest ratio of distances within a block of pixels that are taken for one surface.
const float kOneSurfaceRatio = 1.05f;

void main() {
  ivec2 group = listedTile(kSpecCloudTileClass, gl_WorkGroupID.x);
  // The samples the compose reads.
  ivec2 cell = ivec2(sky.region.zw) + group * int(kSkyWorkgroupSize) + ivec2(gl_LocalInvocationID.xy);
  int scale = int(sky.cloudShape.w);
  if (any(greaterThanEqual(cell * scale, ivec2(sky.extent.xy)))) return;
  // The depth at the block's centre. Reversed Z stores 1 / view distance, which is affine across
  // the screen on a plane, so on one surface the mean of the four pixels' depths is the centre's
  // (from orbit neighbouring pixels' distances differ by far more than the layer is thick: the
  // nearest one would end the centre's ray in front of the layer). Across a silhouette, or where
  // a pixel shows no surface (depth 0), the nearest surface (the largest depth).
  // The block's pixels in one read (at full resolution the one pixel, four times), added in the
  // order (+0, +0), (+1, +0), (+0, +1), (+1, +1).
  vec4 texels = depthTexels(scale * cell);
  vec4 block = scale == 1 ? texels.wwww : texels.wzxy;
  float nearest = 0.0f, farthest = 1e30f, sum = 0.0f;
  for (int k = 0; k < 4; ++k) {
    float d = block[k];
    nearest = max(nearest, d);
    farthest = min(farthest, d);
    sum += d;
  }
  bool oneSurface = farthest > 0.0f && nearest <= kOneSurfaceRatio * farthest;
  vec2 centre = (vec2(cell) + 0.5f) * float(scale);
  ViewRay ray = viewRay(centre, oneSurface ? 0.25f * sum : nearest);

  vec3 light;
  float transmittance, tCloud;
  if (kSpecCloudTileClass == kSkyCloudTileMarch) {
    cloudsAlong(ray, light, transmittance, tCloud);
  } else {  // what the march finds on a ray that ends before the layer
    light = vec3(0.0f);
    transmittance = 1.0f;
    tCloud = -1.0f;
  }
  // The layer seen through the air in front of it: that air's light where the cloud hides the
  // rest of the ray, and the cloud's own light through it (the compose adds the rest of the
  // ray's light times the cloud's transmittance).
  vec3 composite = vec3(0.0f);
  if (tCloud >= 0.0f) {
    vec2 uv = centre / sky.extent.xy;
    float R = sky.atmosphere.radii.x;
    vec2 columnStretch = aerialColumnStretch(R, sky.camera.x, ray.dir.z, ray.hGround);
    vec3 frontLight, frontTransmittance;
    aerialPerspective(uv, ray, tCloud, columnStretch, false, false, frontLight, frontTransmittance);
    // From inside the air, a cloud toward the horizon lies behind nearly all of its ray's air: the
    // light in front of it is then the sky-view table's along the whole ray, times the share of
    // that ray's opacity in front of the cloud (as for the ground near the ground sphere,
    // aerialPerspective), blended in from kCloudSkyShareFrom of it. The volume's columns are
    // too far apart there: a column's ray a few rows higher ends before that opacity, and the
    // line of distant clouds along the horizon from the ground was 3 of 255 darker than the
    // march.
    if (!aerialFromAbove() && !ray.seesGround) {
      vec4 whole = skyViewAlong(ray.dir, sky.camera.x, ray.hGround);
      float opacityShare = clamp((1.0f - frontTransmittance.y) / max(whole.a, 1.0e-6f), 0.0f, 1.0f);
      float share = smoothstep(kCloudSkyShareFrom, kCloudSkyShareTo, opacityShare);
      float eclipse = skyEclipse(ray.dir, vec2(0.0f, tCloud), skyStepSpacing(sky.atmosphere, sky.camera.x, false));
      frontLight = mix(frontLight, whole.rgb * opacityShare * eclipse, share);
    }
    composite = (1.0f - transmittance) * frontLight + frontTransmittance * light;
  }
  imageStore(cloudSampleLight, cell, vec4(composite * kSkyHalfLightScale, transmittance));
  // (A ray that ends before the layer has no path through it before its end.)
  float path = kSpecCloudTileClass == kSkyCloudTileMarch ? layerPathBefore(ray.dir, ray.tEnd) : 0.0f;
  // (The clear tiles' surfaces lie where the clouds' shadow table serves: under the layer's base.)
  float shadow = kSpecCloudTileClass == kSkyCloudTileMarch ? cloudShadow(ray) : cloudShadowFromTable(ray);
  imageStore(cloudSampleEnd, cell, vec4(ray.tGeometry, path, shadow, 0.0f));
}
