#version 450
// Terrain shading (issue 3, point 8): per-pixel normal and height from the world-anchored
// patch textures where they reach (finest level first, blended across level edges), else the
// vertex normal; colour by altitude, slope, latitude and a noise perturbation of the band
// edges (seed 000 "Earth-like" and "altitude + noise" schemes, seed 001's altitude colour
// map); sunlight through the atmosphere (transmittance table) plus sky light, as HDR radiance.
// Ground below sea level is the sea floor; the water pass draws the sea over it.
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

#include "terrain_surface.glsl"

#include "common/rings.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inUp;
layout(location = 2) in vec4 inAttributes;
layout(location = 3) in float inHeight;
layout(location = 4) in vec3 inToCamera;

layout(location = 0) out vec4 outColor;

const uint kSchemeEarth = 0u;
const uint kSchemeAltitude = 1u;
const uint kSchemeMoon = 2u;
const uint kSchemeMars = 3u;
const uint kSchemeGiant = 4u;

// The earth scheme's vegetation at a point: forest and grass where it is wet, desert in the
// subtropical belts (about 15-35° of latitude, where the Hadley cells' dry air sinks), tundra
// toward the ice caps; the colour noise breaks every zone into patches. Derived from the
// preset's lowland, highland and beach colours.
vec3 vegetation(float latitudeDeg, float jitter) {
  float belt = (latitudeDeg - 24.0f) / 10.0f;
  float dryness = clamp(0.85f * exp(-belt * belt) + 0.6f * jitter + 0.12f, 0.0f, 1.0f);
  vec3 forest = 0.75f * frame.colorLowland.rgb;
  vec3 grass = 1.15f * mix(frame.colorLowland.rgb, frame.colorHighland.rgb, 0.35f);
  vec3 desert = mix(frame.colorBeach.rgb, frame.colorHighland.rgb, 0.45f);
  vec3 c = mix(forest, grass, smoothstep(0.05f, 0.4f, dryness));
  c = mix(c, desert, smoothstep(0.45f, 0.75f, dryness));
  float tundra = smoothstep(52.0f, 64.0f, latitudeDeg + 6.0f * jitter);
  return mix(c, 0.9f * frame.colorHighland.rgb, tundra);
}

// pixelM: how much the height changes across this pixel (fwidth), so that bands thinner than a
// pixel (a beach seen from orbit) fade to their share of it instead of aliasing into dots.
vec3 groundColor(float altitude, float slope, float sinLatitude, float jitter, float pixelM) {
  uint scheme = uint(frame.shading.y);
  float beach = frame.planet.z;
  float snowLine = frame.planet.w;
  float iceCap = frame.shading.x;
  float lat = abs(sinLatitude) + 0.04f * jitter;
  if (scheme == kSchemeAltitude) {
    float t = clamp(altitude / max(snowLine, 1.0f), 0.0f, 1.0f);
    return t < 0.5f ? mix(frame.colorLowland.rgb, frame.colorHighland.rgb, 2.0f * t)
                    : mix(frame.colorHighland.rgb, frame.colorSnow.rgb, 2.0f * t - 1.0f);
  }
  if (scheme == kSchemeMoon) {
    // Maria low and dark, highlands bright, fresh rock on steep slopes.
    vec3 c = mix(frame.colorLowland.rgb, frame.colorHighland.rgb,
                 smoothstep(-1500.0f, 1500.0f, altitude + 600.0f * jitter));
    return mix(c, frame.colorCliff.rgb, smoothstep(0.25f, 0.5f, slope));
  }
  if (scheme == kSchemeGiant) {
    // Belts and zones follow the latitude; the preset's layers (small heights, large
    // wavelengths) warp them into waves and eddies: snow_line_m is the height that moves a band
    // by about a twentieth of its width. The poles fade into a dull hood.
    float latitude = asin(clamp(sinLatitude, -1.0f, 1.0f));
    float warp = altitude / max(snowLine, 1.0f);
    float s = 17.0f * latitude + 0.3f * warp;
    float zones = smoothstep(-0.35f, 0.35f, sin(s));
    float fine = 0.5f + 0.5f * sin(3.7f * s + 0.4f * warp);
    vec3 c = mix(frame.colorLowland.rgb, frame.colorHighland.rgb, zones);
    c = mix(c, frame.colorBeach.rgb, 0.35f * fine * (1.0f - zones));
    return mix(c, frame.colorCliff.rgb, smoothstep(1.0f, 1.45f, abs(latitude) + 0.05f * warp));
  }
  vec3 c = frame.colorLowland.rgb;
  float highland = 0.7f * snowLine;
  if (scheme == kSchemeEarth) {
    c = vegetation(degrees(asin(min(abs(sinLatitude), 1.0f))), jitter);
    highland = 0.85f * snowLine;
  }
  c = mix(c, frame.colorHighland.rgb, smoothstep(0.25f * snowLine, highland, altitude + 250.0f * jitter));
  if (scheme == kSchemeEarth && beach > 0.0f) {
    float top = beach * (1.0f + 0.6f * jitter);
    float sand = (1.0f - smoothstep(top - pixelM, top + pixelM, altitude)) * clamp(top / max(pixelM, 1e-3f), 0.0f, 1.0f);
    c = mix(c, frame.colorBeach.rgb, sand);
  }
  c = mix(c, frame.colorCliff.rgb, smoothstep(0.3f, 0.55f, slope + 0.08f * jitter));
  // The snow line falls toward the poles; snow does not stick to cliffs.
  float snowAltitude = snowLine * (1.0f - 0.6f * lat * lat * lat * lat) + 300.0f * jitter;
  float snow = smoothstep(snowAltitude - 100.0f, snowAltitude + 100.0f, altitude) * (1.0f - smoothstep(0.45f, 0.7f, slope));
  snow = max(snow, smoothstep(iceCap - 0.01f, iceCap + 0.01f, lat));
  return mix(c, frame.colorSnow.rgb, snow);
}

void main() {
  gl_FragDepth = gl_FragCoord.z;
  if (frame.shading.z > 0.5f) {  // wireframe debug view
    outColor = vec4(0.05f, 0.25f, 0.08f, 1.0f);
    return;
  }
  vec3 normal;
  float height;
  surfaceDetail(inAttributes.xy, inUp, inNormal, inHeight, normal, height);
  float pixelM = fwidth(height);  // before any branch: derivatives need uniform control flow
  vec3 up = normalize(inUp);
  float jitter = inAttributes.z;
  float seaLevel = frame.planet.x;
  bool ocean = frame.planet.y > 0.5f;
  vec3 sun = frame.sunLocal.xyz;
  vec3 albedo;
  if (ocean && height < seaLevel) {
    // Under water at this pixel, though the triangle may be above sea level: the mesh is
    // coarser than the patch heights, and near a coast it often is. Pushed back to twice its
    // distance, it cannot hide the sea surface in front of it, so the water pass draws the sea
    // here too and the coastline is the patch heights' (the mesh's triangles showed as sandy
    // polygons along the shore). Reversed-Z: half the depth is twice the distance.
    if (frame.water.z > 0.5f) gl_FragDepth = 0.5f * gl_FragCoord.z;
    // Sea floor: sand near the coast, darker mud deeper down (the water pass tints it).
    float depth = seaLevel - height;
    // A sand shelf narrower than the pixel shows only its share of it.
    float sand = (1.0f - smoothstep(0.0f, 60.0f, depth)) * clamp(60.0f / max(pixelM, 1e-3f), 0.0f, 1.0f);
    albedo = mix(0.4f * frame.colorLowland.rgb + 0.3f * frame.colorBeach.rgb, frame.colorBeach.rgb, sand);
    if (frame.water.z < 0.5f) {  // no water pass (debug): show the sea as its colour
      albedo = mix(frame.colorShallowWater.rgb, frame.colorDeepWater.rgb, smoothstep(0.0f, 200.0f, depth));
      normal = up;
    }
  } else {
    float slope = 1.0f - max(dot(normal, up), 0.0f);
    albedo = groundColor(height - seaLevel, slope, inAttributes.w, jitter, pixelM);
  }
  vec3 sunLight = sunIrradianceAt(height, up);
  if (frame.cameraPlanet.w > 0.5f) {  // the body's rings shadow it
    mat3 localToPlanet = mat3(frame.localToPlanet);
    vec3 pointPlanet = frame.cameraPlanet.xyz - localToPlanet * inToCamera;
    sunLight *= ringShadow(pointPlanet, localToPlanet * sun, frame.ring);
  }
  float muS = dot(up, sun);
  // Sky light, more on ground that faces the sky; airless bodies get a faint fill instead.
  vec3 skyLight = (skyIrradianceAt(muS) + vec3(frame.shading.w * frame.sunLocal.w)) * (0.6f + 0.4f * dot(normal, up));
  vec3 radiance = albedo / kAtmospherePi * (sunLight * max(dot(normal, sun), 0.0f) + skyLight);
  outColor = vec4(radiance, 1.0f);
}
