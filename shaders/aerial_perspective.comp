#version 450
// The aerial-perspective volume (Hillaire 2020, §5.4), rebuilt every frame before the compose
// pass: for each of kAerialSize² columns across the screen, the light the air scatters toward
// the camera (single and multiple scattering) and the transmittance from the camera to the far
// end of each of the column's kAerialSize slices, the latter as the optical depth (from above the
// air only: from inside, the compose and the cloud pass read the camera's transmittance table,
// sky_camera_transmittance.comp); and the light
// by the column's opacity rather than its distance (sky_compose.glsl, aerialPerspective, says
// why). One invocation marches a whole column, kSpecStepsPerSlice steps per slice
// (common/atmosphere.glsl, scatteringStep), and stops where the ray meets the ground sphere:
// slices past it keep the value there. The scene's other bodies darken the samples in their
// shadows (eclipses, common/eclipse.glsl).
#extension GL_GOOGLE_include_directive : require

#include "shared/sky_params.h"

layout(local_size_x = kSkyWorkgroupSize, local_size_y = kSkyWorkgroupSize) in;

#include "sky_uniforms.glsl"
layout(set = 0, binding = kSkyTableBindingTransmittance) uniform sampler2D transmittanceTable;
layout(set = 0, binding = kSkyTableBindingMultipleScattering) uniform sampler2D multipleScatteringTable;
layout(set = 0, binding = kSkyTableBindingAerialLight, rgba16f) uniform writeonly image3D aerialLight;
layout(set = 0, binding = kSkyTableBindingAerialTransmittance, rgba16f) uniform writeonly image3D aerialTransmittance;

#define MULTIPLE_SCATTERING(a, h, muS) \
  textureLod(multipleScatteringTable, multipleScatteringUv(a, h, muS), 0.0f).rgb
// Eclipses: each sample's light is scaled by the share of the sun it sees past the scene's other
// bodies, at its place on the column's ray (where the march starts, plus t along the ray).
// Whether another body can hide the sun (a scene) is a specialization constant (SkyPass): with
// none the loop over occluders has a constant count and no code, where lavapipe ran its body at
// every step of every column (the build 2.3-2.7 → 1.0-1.1 ms at 640×360).
layout(constant_id = 0) const bool kSpecEclipses = true;
#define ECLIPSE_POSSIBLE kSpecEclipses
// The march's steps per slice (kAerialStepsPerSlice, or kAerialStepsPerSliceAbove from above the
// air), as a specialization constant: with a count known when the pipeline is built the steps
// are unrolled, where a count read from the uniforms cost lavapipe a loop (0.3 ms a build).
layout(constant_id = 1) const uint kSpecStepsPerSlice = kAerialStepsPerSlice;
// Whether the camera is above the air (SkyUniforms::aerial.x), as a specialization constant: the
// two sides fill the volume differently (below), and from inside the air no pass reads the
// transmittance volume (the camera's transmittance table serves: sky_compose.glsl,
// aerialPerspective), whose stores were a fifth of the build on lavapipe.
layout(constant_id = 2) const bool kSpecFromAbove = false;
#include "common/eclipse.glsl"
vec3 marchStart;  // local frame, from the camera
vec3 marchDirection;
#define SUN_VISIBLE_ALONG(t) eclipseSunVisible(marchStart + marchDirection * (t), sky.sunLocal.xyz, sky.eclipse)
#include "atmosphere_lookup.glsl"
#include "sky_aerial.glsl"

void main() {
  uvec2 column = gl_GlobalInvocationID.xy;
  if (column.x >= kAerialSize || column.y >= kAerialSize) return;
  vec2 ndc = (vec2(column) + 0.5f) / float(kAerialSize) * 2.0f - 1.0f;
  vec4 nearPoint = sky.clipToLocal * vec4(ndc, 1.0f, 1.0f);
  vec3 dir = normalize(nearPoint.xyz / nearPoint.w);

  AtmosphereParams a = sky.atmosphere;
  float R = a.radii.x;
  float h = sky.camera.x;
  float hGround = sky.surface.z;
  // From above the air, a column whose ray misses the air (space beside the disc) marches instead
  // the ray of its vertical plane that just meets the ground sphere: the limb's, whose light the
  // pixels at the disc's edge, which the filter blends with this column's, nearly have. Left
  // empty it pulled their light toward none, and the transmittance toward 1.
  vec2 stretch = atmosphereStretch(a, h, dir.z, hGround);
  if (kSpecFromAbove && !(stretch.y > stretch.x)) {
    float ratio = (R + hGround) / (R + h);
    float muLimb = -sqrt(max(1.0f - ratio * ratio, 0.0f)) - 1.0e-4f;
    float across = length(dir.xy);
    vec2 side = across > 1.0e-6f ? dir.xy / across : vec2(1.0f, 0.0f);
    dir = vec3(side * sqrt(1.0f - muLimb * muLimb), muLimb);
    stretch = atmosphereStretch(a, h, dir.z, hGround);
  }
  float mu = dir.z;
  float muS = sky.sunLocal.z;
  float nu = dot(dir, sky.sunLocal.xyz);
  vec2 columnStretch = aerialColumnStretchOf(stretch, raySphere(R, h, mu, hGround), R, h, mu);
  bool air = a.radii.w > 0.5f && stretch.y > stretch.x;

  // The march starts where the ray enters the air, its distances counted from there.
  float tStart = air ? stretch.x : 0.0f;
  float r = R + h;
  float h0 = altitudeAlong(R, h, mu, tStart);
  float mu0 = clamp((r * mu + tStart) / (R + h0), -1.0f, 1.0f);
  float muS0 = clamp((r * muS + tStart * nu) / (R + h0), -1.0f, 1.0f);
  marchStart = dir * tStart;
  marchDirection = dir;
  float phaseR = rayleighPhase(nu);
  vec3 phaseM = miePhases(a, nu);
  vec3 single = vec3(0.0f), total = vec3(0.0f), transmittance = vec3(1.0f);
  float done = tStart;
  // The depth volume's slice 0 is the camera (no air yet), so that the compose reads any
  // distance between two slices (sky_aerial.glsl); slice k + 1 ends where the k-th of the
  // column's stretch does. From inside the air the light volume's level j holds the light where
  // the column's opacity (green) reaches j / kAerialSize, found between the ends of the march's
  // steps as linear in the opacity; levels the column never reaches hold its light at its end.
  // From above the air, where the columns' rays differ most (at the limb some cross the thick air
  // low down, their neighbours only the thin air above), it holds the light at the slices' ends,
  // as the depth volume does, and the compose reads both by distance.
  const bool byOpacity = !kSpecFromAbove;
  imageStore(aerialLight, ivec3(column, 0), aerialEncodeLight(vec3(0.0f)));
  if (kSpecFromAbove) imageStore(aerialTransmittance, ivec3(column, 0), vec4(0.0f));
  uint level = 1u;
  vec3 lastTotal = vec3(0.0f);
  float lastOpacity = 0.0f;
  for (uint k = 0u; k < kAerialSize; ++k) {
    float target = air ? min(aerialSliceEnd(k, columnStretch), stretch.y) : 0.0f;
    if (target > done) {
      float dt = (target - done) / float(kSpecStepsPerSlice);
      for (uint i = 0u; i < kSpecStepsPerSlice; ++i) {
        float t = done - tStart + (float(i) + 0.5f) * dt;
        scatteringStep(a, h0, mu0, muS0, nu, phaseR, phaseM, t, dt, single, total, transmittance);
        float opacity = 1.0f - transmittance.y;
        for (; byOpacity && level < kAerialSize && float(level) / float(kAerialSize) <= opacity; ++level) {
          float w = (float(level) / float(kAerialSize) - lastOpacity) / max(opacity - lastOpacity, 1.0e-7f);
          imageStore(aerialLight, ivec3(column, level),
                     aerialEncodeLight(mix(lastTotal, total, clamp(w, 0.0f, 1.0f))));
        }
        lastTotal = total;
        lastOpacity = opacity;
      }
      done = target;
    }
    if (kSpecFromAbove) {
      imageStore(aerialTransmittance, ivec3(column, k + 1u), vec4(-log(max(transmittance, vec3(1.0e-30f))), 0.0f));
      imageStore(aerialLight, ivec3(column, k + 1u), aerialEncodeLight(total));
    }
  }
  for (; byOpacity && level <= kAerialSize; ++level)
    imageStore(aerialLight, ivec3(column, level), aerialEncodeLight(total));
}
