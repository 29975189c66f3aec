#version 450
// Water shading (issue 4, point 1; glint issue 20, point 3): Fresnel reflection of the sky, the
// sun's glint off a rough sea, light scattered up from the water body in the preset's
// deep/shallow colours, and transparency that grows toward the coast from the depth under the
// pixel (sea level minus the patch-texture height). Output is premultiplied: the blend keeps
// (1 − α) of the sea floor drawn before.
//
// The glint is a microfacet reflection (Cook & Torrance 1982) with the wave-slope distribution
// Cox & Munk (1954) measured from sun-glitter photographs: an isotropic Gaussian of slopes with
// total mean square slope σ² = 0.003 + 0.00512·U (U: wind speed at 10 m, m/s), i.e. the
// Beckmann distribution with m² = σ²; Fresnel of water (n = 1.333, unpolarised) and Smith's
// height-correlated shadowing-masking (Heitz 2014) with Walter et al.'s (2007) rational Λ for
// Beckmann. The waves the pixel resolves tilt the normal; the rest of σ² (slopes of waves
// smaller than the pixel, and the resolved waves faded below the pixel's footprint) widens the
// distribution, so the total stays Cox–Munk's at every distance and no wave aliases. The sky's
// reflection takes Fresnel averaged over those unresolved facets (roughSeaReflectance).
//
// Clouds (a planet with clouds and air): the sea mirrors the layer's base (reflectedSky) and lies
// in its shadow, which takes the glint with the sun's direct light and the water body's light as
// the ground's. The target's alpha keeps only the share of the pixel that shows the sea floor
// (WaterPass), which the sky pass's cloud shadow still darkens.
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"
#include "terrain_surface.glsl"

// Whether another body can hide the sun (a scene), as a specialization constant: the eclipse
// loop's body costs every pixel on lavapipe even with no occluder.
layout(constant_id = 0) const bool kSpecEclipses = true;
#define ECLIPSE_POSSIBLE kSpecEclipses
#include "common/eclipse.glsl"

// The ring shadow (terrain_surface.glsl): true only for a body with rings (as terrain.frag's).
layout(constant_id = 1) const bool kSpecRingShadow = false;
// The cloud layer (a planet with clouds and air; frames that draw them set frame.cloudShape.z):
// the sea mirrors it and lies in its shadow, which the sky pass then leaves to it.
layout(constant_id = 2) const bool kSpecClouds = false;
layout(set = 0, binding = kRenderBindingClouds) uniform samplerCube cloudCover;
#define CLOUD_COVER cloudCover
#define CLOUD_LAYER frame.clouds
#define CLOUD_SHAPE frame.cloudShape
#define CLOUD_MOTION frame.cloudMotion
#define CLOUD_LOCAL_TO_PLANET frame.localToPlanet
#include "cloud_layer.glsl"

// The sky-view table of the body's sky pass (TerrainPass::setSkyView), read where
// frame.skyView.x > 0.
layout(set = 0, binding = kRenderBindingSkyView) uniform sampler2D skyViewTable;

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inUp;
layout(location = 2) in vec4 inAttributes;
layout(location = 3) in float inHeight;
layout(location = 4) in vec3 inToCamera;

layout(location = 0) out vec4 outColor;

const float kWaterIndex = 1.333f;  // refractive index of sea water (air = 1)
// The sun's disc (0.533° across, radius αs = 4.65e-3 rad) seen in a facet: the half vector
// sweeps a disc of slopes of radius αs/2. Added to the waves' variance as (αs/2)², the Gaussian
// has that disc's own peak density 1/(π(αs/2)²), so where the waves leave no variance the glint
// stays finite: the sun's image at its true radiance E/(π αs²) times Fresnel.
const float kSunDiscSlopeVariance = 5.41e-6f;
// A resolved wave fades into the roughness between these phase changes per pixel (radians):
// 8 pixels per wavelength keep it whole, 4 (half Nyquist) remove it before it can alias.
const float kWaveFadeStart = 0.25f * kAtmospherePi;
const float kWaveFadeEnd = 0.5f * kAtmospherePi;

// Fresnel reflectance of unpolarised light from air onto water at incidence cosine c (exact
// dielectric form, mean of the s and p reflectances).
float fresnelWater(float c) {
  c = clamp(c, 0.0f, 1.0f);
  float g = sqrt(kWaterIndex * kWaterIndex - 1.0f + c * c);
  float a = (g - c) / (g + c);
  float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

// The share of a uniform sky's light a rough sea reflects toward a view at cosine c to its mean
// normal, whose facets tilt with mean square slope m2 (the waves the pixel does not resolve):
// Fresnel averaged over the facets the view sees, weighted by their projected area. Toward the
// horizon a flat sea's Fresnel nears 1, but there the view sees mostly facets tilted toward it,
// met at steeper incidence: at 7 m/s and 1° above the horizon a rough sea reflects 0.39, not
// 0.95. Fitted as Fresnel at the cosine (c^1.5 + (0.7 m)^1.5)^(2/3), m = √m2, within 0.05 of
// the average (a Monte Carlo over Cox–Munk slopes, winds 0.5 to 20 m/s, all view angles).
float roughSeaReflectance(float c, float m2) {
  c = clamp(c, 0.0f, 1.0f);
  float k = 0.7f * sqrt(m2);
  return fresnelWater(pow(c * sqrt(c) + k * sqrt(k), 2.0f / 3.0f));
}

// Smith's Λ for the Beckmann distribution of total mean square slope m2, at a direction whose
// cosine to the mean normal is c (Walter et al. 2007, eq. 27, rational fit of the erf form).
float smithLambdaBeckmann(float c, float m2) {
  c = clamp(c, 1e-4f, 1.0f);
  float a = c / (sqrt(m2) * sqrt(1.0f - c * c) + 1e-12f);
  if (a >= 1.6f) return 0.0f;
  return (1.0f - 1.259f * a + 0.396f * a * a) / (3.535f * a + 2.181f * a * a);
}

// Radiance factor of the glint: Fresnel · D · G / (4 cos θv), times the sun's irradiance
// (normal to its rays) gives the reflected radiance. m2: the unresolved total mean square slope.
float glintFactor(vec3 normal, vec3 toCamera, vec3 sun, float m2) {
  float cosV = dot(normal, toCamera);
  float cosL = dot(normal, sun);
  if (cosV <= 0.0f || cosL <= 0.0f) return 0.0f;
  vec3 halfway = normalize(sun + toCamera);
  float cosH = max(dot(normal, halfway), 1e-4f);
  float cosH2 = cosH * cosH;
  float tan2 = (1.0f - cosH2) / cosH2;
  // Beckmann / Cox–Munk: the density of facet slopes, per solid angle of facet normals.
  float distribution = exp(-tan2 / m2) / (kAtmospherePi * m2 * cosH2 * cosH2);
  float shadowing = 1.0f / (1.0f + smithLambdaBeckmann(cosV, m2) + smithLambdaBeckmann(cosL, m2));
  return fresnelWater(dot(halfway, sun)) * distribution * shadowing / (4.0f * cosV);
}

// The clear sky the sea mirrors along `reflected` (unit, local frame) at a point whose vertical is
// `up`: the sky-view table, the sky around the camera by view zenith angle and azimuth from the
// sun, read at the reflected ray's zenith angle and azimuth there. The table is the sky seen from
// the camera's altitude, whose horizon (the ground sphere's edge) lies below 90°: the sea's zenith
// angles 0 .. 90° are stretched onto the table's 0 .. horizon, so that a ray grazing the sea reads
// the haze of a ray grazing the ground, not the sky above the camera's horizontal. A ray a wave
// sends below the horizon reads the sky just above it.
vec3 skyViewReflection(vec3 reflected, vec3 up, vec3 sun) {
  vec2 range = skyViewZenithRange(frame.atmosphere, max(frame.camera.x, 0.0f), frame.skyView.y);
  float cosZenith = clamp(dot(reflected, up), 0.0f, 1.0f);
  float theta = mix(range.x, range.y, min(acos(cosZenith) * (2.0f / kAtmospherePi), 1.0f));  // the sky half
  vec2 uv = skyViewUv(theta, range, reflected - cosZenith * up, sun - dot(sun, up) * up);
  return textureLod(skyViewTable, uv, 0.0f).rgb;
}

// The sky the sea mirrors along `reflected` where the frame draws clouds: the layer's column
// where the ray reaches the layer's middle (from the sea point `fromCentre`, local frame from the
// planet's centre, at altitude hSea), its base lit as the sky pass lights a cloud seen from
// below, over the clear sky's reflection `clearSky`, which the cloud's opacity hides as the sky
// pass composes it. Under an overcast the sea is grey with the cloud base, not the clear sky's
// blue darkened by the clouds' shadow. `blur`: the spread of the directions the pixel reflects
// (rad; the waves' slopes): the cover is read averaged over it, so the rougher the sea, the
// softer the clouds in it.
vec3 reflectedSky(vec3 fromCentre, float hSea, vec3 up, vec3 reflected, vec3 clearSky, float blur, float eclipse) {
  // A ray a wave sends below the horizon meets the next wave: it sees what is just above the
  // horizon (leaving it the clear sky drew blue streaks along the horizon under an overcast).
  float below = dot(reflected, up);
  reflected = normalize(reflected + up * (max(below, 0.02f) - below));
  float muR = dot(reflected, up);
  float R = frame.camera.y;
  float cloudH = 0.5f * (CLOUD_LAYER.x + CLOUD_LAYER.y);
  float t = raySphere(R, hSea, muR, cloudH).x;  // the sea lies below the layer: the crossing ahead
  if (t < 0.0f) return clearSky;
  vec3 point = fromCentre + reflected * t;
  vec3 layerUp = normalize(point);
  float thickness = CLOUD_LAYER.y - CLOUD_LAYER.x;
  float muLayer = max(dot(reflected, layerUp), 0.02f);
  // The cover averaged over the pixel's spread of rays and over the stretch the ray crosses the
  // layer in: toward the horizon that is many clouds (the sky pass's march sees them all, and a
  // single column's gap would mirror as a clear streak under an overcast).
  float crossing = thickness * sqrt(1.0f - muLayer * muLayer) / muLayer;
  float d = coverDensity(point, coverLod(max(t * blur, crossing), R + cloudH));
  if (d <= 0.002f) return clearSky;
  float extinction = CLOUD_LAYER.z * d;
  // Through the columns up to density d of the layer's thickness, at the ray's slant.
  float alpha = 1.0f - exp(-extinction * d * thickness / muLayer);
  // Lit where the eye sees into the base: one optical depth up into the column (as the sky
  // pass's marchLayer).
  float hLight = CLOUD_LAYER.x + min(0.5f * d * thickness, muLayer / extinction);
  vec3 sun = frame.sunLocal.xyz;
  float muSLayer = dot(layerUp, sun);
  vec3 sunLight = eclipse * sunIrradianceAt(cloudH, layerUp);
  vec3 skyLight = eclipse * skyIrradianceAt(muSLayer);
  vec3 base = cloudLight(hLight, d, muSLayer, cloudPhase(dot(reflected, sun)), sunLight, skyLight);
  // (The air between the sea and the cloud is left out: the compose's haze over the sea pixel is
  // much like it, and the clear sky's reflection here is bluer than the sky's haze at the horizon.)
  return mix(clearSky, base, alpha);
}

void main() {
  vec3 terrainNormal;
  float ground;
  surfaceDetail(inAttributes.xy, inUp, inToCamera, inNormal, inHeight, terrainNormal, ground);
  float depth = frame.planet.x - ground;
  // The coastline follows the patch heights. It is antialiased: the water covers the part of
  // the pixel where the depth, extrapolated over the pixel by its screen derivatives, is
  // positive (a hard cut left stair-steps where a texel spans a few pixels, as near the limb).
  float fwidthDepth = fwidth(depth);
  float coverage = clamp(depth / max(fwidthDepth, 1e-6f) + 0.5f, 0.0f, 1.0f);
  // The pixel's footprint in the face plane, taken before the discard (derivatives need the
  // whole quad).
  vec2 offsetM = inAttributes.xy * frame.camera.y;
  vec2 offsetDx = dFdx(offsetM);
  vec2 offsetDy = dFdy(offsetM);
  float footprintM = max(length(dFdx(inToCamera)), length(dFdy(inToCamera)));
  if (coverage <= 0.0f) discard;  // dry land over the whole pixel
  vec3 up = normalize(inUp);
  vec3 toCamera = normalize(inToCamera);
  vec3 sun = frame.sunLocal.xyz;

  // Waves: a few travelling sines in the face plane; the CPU gives each one's phase at the
  // face reference point in double, the pixel adds its small offset (no float at planet scale).
  vec3 axisA = mat3(frame.planetToLocal) * frame.faceAxisA.xyz;
  vec3 axisB = mat3(frame.planetToLocal) * frame.faceAxisB.xyz;
  vec2 slope = vec2(0.0f);
  float resolvedVariance = 0.0f;
  // Without patch textures (quality low, --no-patches) there is no face frame and the CPU
  // leaves the waves zero: all of the slope variance is then unresolved roughness.
  uint waveCount = frame.refMinusNadir.w > 0.5f ? kWaterWaveCount : 0u;
  for (uint i = 0u; i < waveCount; ++i) {
    // xy: wave vector (1/m, face axes), z: phase at the reference, w: share of the slope
    vec4 wave = frameArray(kFrameTexelWaves, i);
    // The wave's phase change across the pixel: where it nears Nyquist the wave leaves the
    // normal (it would alias into moiré) and its slope variance joins the roughness below.
    float phasePerPixel = abs(dot(wave.xy, offsetDx)) + abs(dot(wave.xy, offsetDy));
    float shown = 1.0f - smoothstep(kWaveFadeStart, kWaveFadeEnd, phasePerPixel);
    float amplitude = frame.camera.w * wave.w * shown;
    float phase = wave.z + dot(wave.xy, offsetM);
    slope += amplitude * cos(phase) * normalize(wave.xy);
    resolvedVariance += 0.5f * amplitude * amplitude;  // a sine of slope amplitude A: mean square A²/2
  }
  vec3 normal = normalize(up - slope.x * axisA - slope.y * axisB);
  // Cox–Munk's total less what the normal shows here, plus the sun's disc.
  float unresolvedVariance = max(frame.water.w - resolvedVariance, 0.0f) + kSunDiscSlopeVariance;

  float cosView = max(dot(normal, toCamera), 0.0f);
  float fresnel = roughSeaReflectance(cosView, unresolvedVariance);
  float muS = dot(up, sun);
  // Other bodies of a scene hide the sun and the sky above (as in terrain.frag).
  vec3 refracted;
  float eclipse = eclipseSunVisibleRefracted(-inToCamera, sun, frame.eclipse, refracted);
  vec3 sunLight = (vec3(eclipse) + refracted) * sunIrradianceAt(frame.planet.x, up);
  if (kSpecRingShadow) sunLight *= surfaceRingShadow(inToCamera);  // the rings shadow the sea as the ground
  vec3 skyLight = eclipse * skyIrradianceAt(muS);
  // The sky seen in the reflection: near the ground the sky-view table along the reflected ray;
  // high above it (where the table is the sky seen from up there) the sky's irradiance spread over
  // the hemisphere, brighter low.
  vec3 reflected = reflect(-toCamera, normal);
  vec3 skyRadiance = skyLight / kAtmospherePi * mix(1.6f, 0.7f, clamp(dot(reflected, up), 0.0f, 1.0f));
  if (frame.skyView.x > 0.0f)
    skyRadiance = mix(skyRadiance, eclipse * skyViewReflection(reflected, up, sun), frame.skyView.x);
  // The clouds: their shadow takes the sun's glint as it takes the sun (the compose's factor, a
  // quarter of the light left under a thick cloud, would leave a glint under an overcast), and
  // the light from the water body as the ground's; the sky the sea mirrors has them in it.
  float cloudSun = 1.0f;
  bool cloudy = kSpecClouds && frame.cloudShape.z > 0.5f;
  if (cloudy) {
    vec3 fromCentre = up * (frame.camera.y + frame.planet.x);
    cloudSun = cloudSunTransmittance(fromCentre, frame.camera.y, frame.planet.x, sun, muS,
                                     max(footprintM, 1000.0f));
    skyRadiance = reflectedSky(fromCentre, frame.planet.x, up, reflected, skyRadiance,
                               2.0f * sqrt(unresolvedVariance), eclipse);
  }
  vec3 glint = cloudSun * sunLight * glintFactor(normal, toCamera, sun, unresolvedVariance);
  vec3 specular = fresnel * skyRadiance + glint;
  // The water body: shallow colour near the coast, deep colour offshore, lit from above.
  float clarity = frame.water.x;
  vec3 body = mix(frame.colorShallowWater.rgb, frame.colorDeepWater.rgb, smoothstep(0.0f, 6.0f * clarity, depth));
  float iceCap = frame.shading.x;
  float lat = abs(inAttributes.w) + 0.04f * inAttributes.z;
  float ice = smoothstep(iceCap + 0.02f, iceCap + 0.04f, lat);  // sea ice a little poleward of the land caps
  vec3 upwelling = mix(body, frame.colorSnow.rgb, ice) / kAtmospherePi * (sunLight * max(muS, 0.0f) + skyLight) *
                   cloudGroundShadow(cloudSun);
  // Where the depth changes by more than the clarity across the pixel (the coast from far
  // away), the clear shallow strip is a small part of it: weigh in half the pixel's depth range.
  float opacity = max(1.0f - exp(-(depth + 0.5f * fwidthDepth) / clarity * 3.0f), ice);
  float alpha = fresnel + (1.0f - fresnel) * opacity;
  outColor = coverage * vec4(specular * (1.0f - ice) + (1.0f - fresnel) * opacity * upwelling, alpha);
}
