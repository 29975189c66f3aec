#version 450
// The clouds' shadow table (issue 21, point 7; shared/sky_params.h, kSkyBindingCloudShadowTable),
// rebuilt every frame from below the layer's base before the cloud pass: the cover's density on
// the sphere through the layer's middle, over a square of the local frame around the camera's
// nadir (sky_compose.glsl, cloudShadowTablePoint) wide enough to hold every point where the sun's
// ray from a surface that a ray ending before the layer shows crosses that sphere
// (SkyPass::cloudShadowSquare bounds it), its texels gathered toward the camera's own crossing
// (cloudShadowTableUv says why). The ground's tiles clear of the clouds read their shadow from it
// in one bilinear read per pixel (cloudShadowFromTable), at full resolution, where the cloud pass
// computed it per sample with a read of the cover's cube (the three images cross-faded and
// drifted) and the compose upsampled it; the cloud pass's clear tiles read it too.
// Each texel reads the cover at the mip level of its own size (level 0 at the default cover's
// resolution: its texels are several times the table's), so the table does not alias a finer
// cover.
#extension GL_GOOGLE_include_directive : require

#include "sky_compose.glsl"

layout(set = 0, binding = kSkyBindingCloudShadowTarget, r32f) uniform writeonly image2D cloudShadowTarget;

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(texel, uvec2(kCloudShadowTableSize)))) return;
  float rLayer = sky.atmosphere.radii.x + 0.5f * (sky.clouds.x + sky.clouds.y);
  vec2 uv = (vec2(texel) + 0.5f) / float(kCloudShadowTableSize);
  // (x = c + s · u |u| with u = 2 uv − 1: a texel spans 4 s |u| / size along each axis.)
  vec2 u = 2.0f * uv - 1.0f;
  float spacing = 4.0f * sky.cloudShadowTable.z * max(abs(u.x), abs(u.y)) / float(kCloudShadowTableSize);
  float d = coverDensity(cloudShadowTablePoint(uv, rLayer), coverLod(spacing, rLayer));
  imageStore(cloudShadowTarget, ivec2(texel), vec4(d, 0.0f, 0.0f, 0.0f));
}
