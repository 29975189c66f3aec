// The aerial-perspective volume's slices (Hillaire 2020, §5.4), shared by its build
// (aerial_perspective.comp) and its readers (sky.comp). The includer declares `sky`
// (SkyUniforms) and includes atmosphere_lookup.glsl first.
//
// From inside the atmosphere the slices sit at the same distances in every column, gathered
// toward the camera: slice k ends at D · ((k + 1) / N)², D the farthest distance a ray can run
// inside the air (past the ground's horizon to the top), so that neighbouring columns hold the
// same distances and blend right across the edges of what the pixels show. From above the top
// a common range would spend most slices outside the air (at 8,000 km the air along a ray is
// 100 km of a 6,000 km range), so each column splits its own stretch through the air evenly:
// from where it enters the top to where it meets the ground sphere, or, for a ray that misses
// it, to the point where it passes closest to it, which joins the two continuously at the limb.
#ifndef PLANET_SKY_AERIAL_GLSL
#define PLANET_SKY_AERIAL_GLSL

bool aerialFromAbove() { return sky.aerial.x > 0.5f; }

// Rec. 709 luminance (the frame's primaries).
float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

// The light volume's texels: rgb the light times kSkyHalfLightScale, a log2 of its luminance
// plus kAerialLogFloor, so that the filter blends both the light and its logarithm.
vec4 aerialEncodeLight(vec3 light) {
  return vec4(light * kSkyHalfLightScale, log2(max(luminance(light), 0.0f) + kAerialLogFloor));
}

// The light of a filtered texel. From above the air, neighbouring columns can differ by orders of
// magnitude: across the terminator the lit air's light falls 10⁻⁴ within a column's width, and
// the filter's linear blend carried the lit column's light most of the way into the night; once
// auto exposure lifts the night side each column's edge showed as a step, a staircase along the
// terminator seen from orbit. There the linear blend is held to at most kAerialBlendExcess times
// the blend of the logarithms, whose light falls geometrically between columns, as the light
// along the ground does; neighbours within a factor of about 14 (the limb's silhouette, a sunlit
// disc) keep the linear blend, which follows the march more closely there. (From inside the air
// each column's first level is the camera's, with no light, and the linear blend stays.)
vec3 aerialDecodeLight(vec4 texel) {
  vec3 light = texel.rgb * (1.0f / kSkyHalfLightScale);
  if (!aerialFromAbove()) return light;
  float linear = luminance(light);
  float geometric = max(exp2(texel.a) - kAerialLogFloor, 0.0f);
  return linear > kAerialBlendExcess * geometric ? light * (kAerialBlendExcess * geometric / linear) : light;
}

// The stretch [x, y] of distances from the camera that a column's slices split (from above),
// from the ray's stretch through the air (atmosphereStretch) and its hits on the ground sphere
// (raySphere at hGround), for a caller that has them already.
vec2 aerialColumnStretchOf(vec2 stretch, vec2 ground, float R, float h, float mu) {
  if (stretch.y <= stretch.x) return vec2(0.0f, -1.0f);
  bool hitsGround = mu < 0.0f && ground.x >= 0.0f;
  float closest = -(R + h) * mu;  // where a ray going down passes closest to the centre
  float end = hitsGround ? stretch.y : (mu < 0.0f ? clamp(closest, stretch.x, stretch.y) : stretch.y);
  return vec2(stretch.x, end);
}

vec2 aerialColumnStretch(float R, float h, float mu, float hGround) {
  return aerialColumnStretchOf(atmosphereStretch(sky.atmosphere, h, mu, hGround), raySphere(R, h, mu, hGround), R, h,
                               mu);
}

// The continuous slice coordinate of distance t from the camera: slice k's far end at k, the
// camera (or the column's start) at −1.
float aerialSlice(float t, vec2 columnStretch) {
  float n = float(kAerialSize);
  if (!aerialFromAbove()) return n * sqrt(max(t, 0.0f) / sky.aerial.y) - 1.0f;
  float length = columnStretch.y - columnStretch.x;
  if (length <= 0.0f) return -1.0f;
  return n * clamp((t - columnStretch.x) / length, 0.0f, 1.0f) - 1.0f;
}

// The distance from the camera where slice k ends.
float aerialSliceEnd(uint k, vec2 columnStretch) {
  float x = float(k + 1u) / float(kAerialSize);
  if (!aerialFromAbove()) return sky.aerial.y * x * x;
  return columnStretch.x + (columnStretch.y - columnStretch.x) * x;
}

// The camera's transmittance table (shared/sky_params.h, kCameraTransmittanceDistances), from
// inside the air: the texture coordinates of distance t along a ray of zenith cosine mu
// (common/atmosphere.glsl, cameraTransmittanceUnit: out to the volume's farthest distance when the
// table was built, sky.camera.z, from the ground sphere's horizon, whose cosine was sky.aerial.w:
// a kept table keeps its mapping, SkyPass::cameraTransmittanceBuilt). Texel centres
// fall on the ends of each range (unitToTexel): the first column is the camera's (no air).
vec2 cameraTransmittanceUv(float mu, float t) {
  vec2 unit = cameraTransmittanceUnit(mu, t, sky.aerial.w, sky.camera.z);
  return vec2(unitToTexel(unit.x, float(kCameraTransmittanceDistances)),
              unitToTexel(unit.y, float(kCameraTransmittanceDirections)));
}

// The inverse, for the table's build: the distance (x) and zenith cosine (y) of texel (i, j).
vec2 cameraTransmittanceTexel(uint i, uint j) {
  return cameraTransmittanceDistanceMu(float(i) / float(kCameraTransmittanceDistances - 1u),
                                       float(j) / float(kCameraTransmittanceDirections - 1u), sky.aerial.w,
                                       sky.camera.z);
}

#endif
