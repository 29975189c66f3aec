// The ground's shading from a pixel's surface values, shared by terrain.frag (forward: in the
// fragment shader) and terrain_shade.comp (deferred: in a compute pass over the G-buffer that
// terrain.frag's TERRAIN_GBUFFER variant writes; TerrainSettings::deferredShading). The material
// from climate and slope (terrain_material.glsl) with per-pixel detail below the vertex spacing
// (terrain_detail.glsl), or the altitude and giant schemes' bands; sunlight through the
// atmosphere (transmittance table) plus sky light, as HDR radiance. Nothing here takes a
// derivative: terrain.frag takes them all (TerrainSample, terrain_surface.glsl), so the compute
// pass shades the same.
// The includer declares kSeaFloorPossible (whether a pixel may be sea floor) and includes
// terrain_common.glsl and terrain_surface.glsl first.
#ifndef PLANET_TERRAIN_SHADE_GLSL
#define PLANET_TERRAIN_SHADE_GLSL

// Per frame, the parts of the shading the view can show (TerrainPass::shadingFor), as
// specialization constants: lavapipe runs every side of a branch and a loop's body at least once,
// so code that a frame cannot use would still cost every pixel.
// The detail octaves: false when no ground in view is near enough for a pixel to resolve them.
layout(constant_id = 4) const bool kSpecGroundDetail = true;
#define GROUND_DETAIL_POSSIBLE kSpecGroundDetail
// The ring shadow: true only for a body with rings.
layout(constant_id = 5) const bool kSpecRingShadow = true;

#include "terrain_colors.glsl"
#include "terrain_material.glsl"

#include "common/color_schemes.glsl"

// Whether another body can hide the sun (a scene), as a specialization constant: the eclipse
// loop's body costs every pixel on lavapipe even with no occluder.
layout(constant_id = 3) const bool kSpecEclipses = true;  // false: no other body can hide the sun
#define ECLIPSE_POSSIBLE kSpecEclipses
#include "common/eclipse.glsl"

#include "common/city_lights.glsl"
#include "shared/exposure_params.h"
#include "common/exposure.glsl"

// The planet's colour scheme (ColorScheme) and whether it has polar caps, as specialization
// constants (TerrainPass::createDrawPipeline): lavapipe runs every side of a branch, so each
// scheme's code would cost every planet; with constants the compiler drops the others.
layout(constant_id = 0) const uint kSpecScheme = 0u;
layout(constant_id = 1) const uint kSpecPolarCaps = 0u;
// 1: the planet's city lights are drawn, and night is in view (the fill pipeline of a frame with
// no night in view leaves them out: lightsDuskFade is 0 wherever the sun is up).
layout(constant_id = 2) const uint kSpecLights = 0u;


// The gas giant's belts and zones: they follow the latitude; the preset's layers (small heights,
// large wavelengths) warp them into waves and eddies: snow_line_m is the height that moves a band
// by about a twentieth of its width. The poles fade into a dull hood.
vec3 bandColor(float altitude, float sinLatitude) {
  float snowLine = frame.planet.w;
  float latitude = asin(clamp(sinLatitude, -1.0f, 1.0f));
  float warp = altitude / max(snowLine, 1.0f);
  float s = 17.0f * latitude + 0.3f * warp;
  float zones = smoothstep(-0.35f, 0.35f, sin(s));
  float fine = 0.5f + 0.5f * sin(3.7f * s + 0.4f * warp);
  vec3 c = mix(kColorLowland, kColorHighland, zones);
  c = mix(c, kColorBeach, 0.35f * fine * (1.0f - zones));
  return mix(c, kColorCliff, smoothstep(1.0f, 1.45f, abs(latitude) + 0.05f * warp));
}

// The material at a ground pixel with its detail: albedo, and the normal tilted by the detail's
// height field. The detail's lattice is the planet's (terrain_detail.glsl), so it does not swim,
// and it depends on nothing of the patch levels, so it is continuous across them.
vec3 groundAlbedo(float altitude, float slope, float sinLatitude, float jitter, float pixelM, vec3 offsetPlanet,
                  float footprintM, inout vec3 normal) {
  uint scheme = kSpecScheme;
  GroundDetail d = groundDetail(offsetPlanet, footprintM);
  // The material noise: the band noise, the coarse octaves, and a little of the detail's second
  // field, so edges are ragged down to the pixel.
  float noise = jitter + groundBiomeNoise(offsetPlanet, footprintM) + 0.04f * d.hue;
  GroundMaterial m;
  if (scheme == kSchemeEarth)
    m = earthMaterial(altitude, slope, sinLatitude, noise, pixelM);
  else if (scheme == kSchemeMars)
    m = marsMaterial(altitude, slope, sinLatitude, noise);
  else
    m = moonMaterial(altitude, slope, noise);
  // Normal: minus the detail gradient's part along the surface.
  vec3 g = mat3(frame.planetToLocal) * (d.slope * (frame.slopes.z * m.relief));
  normal = normalize(normal - (g - dot(g, normal) * normal));
  // Albedo: lognormal variation (it stays positive, and a dark canopy varies as much in ratio as
  // bright sand), a warm-cool tint along the second field, and stones of the rock's colours.
  float contrast = frame.slopes.w * m.contrast;
  vec3 albedo = m.albedo * exp(contrast * (vec3(d.albedo) + d.hue * vec3(0.5f, 0.2f, -0.5f)));
  vec3 stone = mix(kColorScree, kColorCliff, 0.5f + 0.5f * d.hue) * (1.0f + 0.6f * d.albedo);
  return mix(albedo, stone, min(frame.slopes.w, 1.0f) * m.stony * d.stones);
}

// City lights (common/city_lights.glsl) on land `altitude` above sea level at unit direction
// `direction` (planet frame), before the dusk fade. The climate is the materials' (with the
// vertex's band noise only); coasts and valley floors come from the relief cube's mip level whose
// texels are ~80 km wide: a coast where that neighbourhood averages below sea level (a few per
// cent of sea in it does), a valley floor where the ground lies below its neighbourhood.
vec3 cityLights(float altitude, float slope, float sinLatitude, float jitter, vec3 direction, float footprintM) {
  float latitudeDeg = degrees(asin(min(abs(sinLatitude), 1.0f)));
  float temperature = meanTemperatureC(sinLatitude, altitude) + 4.0f * jitter;
  float moisture = moistureAt(latitudeDeg, jitter, altitude);
  float coast = 0.0f, valley = 0.0f;
  uint reliefSize = uint(textureSize(reliefCube, 0).x);
  if (reliefSize > kReliefStandInSize) {
    float radius = frame.camera.y;
    float lod = max(log2(80000.0f / radius * float(reliefSize) / 2.0f), 0.0f);
    float around = textureLod(reliefCube, direction, lod).w - frame.planet.x;
    coast = 1.0f - lightsStep(-300.0f, 0.0f, around);
    valley = lightsStep(30.0f, 250.0f, around - altitude);
  }
  float habitability = lightsHabitability(altitude, slope, temperature, moisture, coast, valley);
  return frame.lights.radiance.rgb * lightsCover(frame.lights, direction, habitability, footprintM / frame.camera.y);
}

// HDR radiance of the ground at `s`, and the target's alpha for it: 1 (the ground's), or where
// city lights shine the mark of their share of the light, which auto exposure shows and measures
// apart (shared/exposure_params.h).
vec4 shadeGround(TerrainSample s) {
  vec3 normal = s.normal;
  float height = s.height;
  float pixelM = s.pixelM;
  // This pixel relative to the mesh's anchor (small floats near the camera) and its footprint
  // on the ground (the larger of its two sides, so no octave finer than the pixel shows).
  vec3 offsetPlanet = mat3(frame.localToPlanet) * (vec3(0.0f, 0.0f, frame.camera.x) - s.toCamera);
  float footprintM = max(s.footprintX, s.footprintY);
  vec3 up = normalize(s.up);
  float jitter = s.jitter;
  float seaLevel = frame.planet.x;
  bool ocean = frame.planet.y > 0.5f;
  vec3 sun = frame.sunLocal.xyz;
  vec3 albedo;
  vec3 emitted = vec3(0.0f);  // city lights, before the dusk fade
  if (kSeaFloorPossible && ocean && height < seaLevel) {
    // Under water at this pixel, though the triangle may be above sea level (terrain.frag
    // pushed its depth back, so the water pass draws the sea here too).
    // Sea floor: sand near the coast, darker mud deeper down (the water pass tints it).
    float depth = seaLevel - height;
    // A sand shelf narrower than the pixel shows only its share of it.
    float sand = (1.0f - smoothstep(0.0f, 60.0f, depth)) * clamp(60.0f / max(pixelM, 1e-3f), 0.0f, 1.0f);
    albedo = mix(0.4f * kColorLowland + 0.3f * kColorBeach, kColorBeach, sand);
    if (frame.water.z < 0.5f) {  // no water pass (debug): show the sea as its colour
      albedo = mix(kColorShallowWater, kColorDeepWater, smoothstep(0.0f, 200.0f, depth));
      normal = up;
    }
  } else {
    float slope = 1.0f - max(dot(normal, up), 0.0f);
    uint scheme = kSpecScheme;
    bool seedScheme = scheme == kSchemeAltitude || scheme >= kSchemeAltitudePerturbed;
    bool caps = kSpecPolarCaps != 0u;
    // Seed 000's colour noise, per pixel on the sphere (float directions are good to ~1 m on
    // Earth, far below its finest octave's few km).
    float colorNoise = 0.0f;
    if (scheme >= kSchemeAltitudePerturbed || caps) {
      float radius = frame.camera.y;
      vec3 direction = normalize(mat3(frame.localToPlanet)[2] + offsetPlanet / radius);
      colorNoise = schemeNoise(direction, frame.scheme.noise.x, footprintM / radius);
    }
    if (scheme == kSchemeGiant)
      albedo = bandColor(height - seaLevel, s.sinLatitude);
    else if (seedScheme)
      albedo = schemeColor(frame.scheme, height - seaLevel, dot(normal, up), s.sinLatitude, colorNoise, max(pixelM, 1.0f));
    else
      albedo = groundAlbedo(height - seaLevel, slope, s.sinLatitude, jitter, pixelM, offsetPlanet, footprintM, normal);
    if (caps) albedo = mix(albedo, kColorSnow, schemePolarCap(frame.scheme, s.sinLatitude, colorNoise, s.latitudeEdge));
    if (kSpecLights != 0u) {
      vec3 direction = normalize(mat3(frame.localToPlanet)[2] + offsetPlanet / frame.camera.y);
      // The pixel's area as a square (its sides' geometric mean): toward the limb the long side
      // alone averaged whole regions into a smooth glow the short side still resolves.
      emitted = cityLights(height - seaLevel, slope, s.sinLatitude, jitter, direction, sqrt(s.footprintX * s.footprintY));
    }
  }
  vec3 sunLight = sunIrradianceAt(height, up);
  if (kSpecRingShadow) sunLight *= surfaceRingShadow(s.toCamera);  // the body's rings shadow it
  // Other bodies of a scene hide the sun (common/eclipse.glsl); an occluder's air bends a little
  // red light into its shadow, taken as coming from the sun.
  vec3 refracted;
  float eclipse = eclipseSunVisibleRefracted(-s.toCamera, sun, frame.eclipse, refracted);
  sunLight *= vec3(eclipse) + refracted;
  float muS = dot(up, sun);
  // Sky light, more on ground that faces the sky, plus a faint fill: the light of the sunlit
  // ground around (airless bodies have no sky light). The surroundings are lit only while the sun
  // is up for them, so the fill sets with the sun and is gone 6° past the terminator: it lit a
  // night side no sunlight reaches (issue 14, point 2).
  float fill = frame.shading.w * frame.sunLocal.w * smoothstep(-0.1f, 0.0f, muS);
  // An eclipse dims both as it dims the sun: the air above a shadowed point and the ground
  // around it are in the same shadow (an approximation at its edge, where some comes from outside).
  vec3 skyIrradiance = skyIrradianceAt(muS) * eclipse;
  vec3 skyLight = (skyIrradiance + vec3(fill * eclipse)) * (0.6f + 0.4f * dot(normal, up));
  // Light from the ground around: a slope sees it over (1 − n·up) / 2 of its hemisphere (none on
  // level ground), lit as level ground by the sun and the sky and of this pixel's albedo. Without
  // it, slopes turned from the sun had only the sky's blue: desert hills' shadowed sides came out
  // blue-grey where photographs show them the ground's colour, darker, warmed by the lit sand.
  vec3 groundAround = albedo * (sunLight * max(muS, 0.0f) + skyIrradiance);
  vec3 bounce = groundAround * (0.5f - 0.5f * dot(normal, up));
  vec3 radiance = albedo / kAtmospherePi * (sunLight * max(dot(normal, sun), 0.0f) + skyLight + bounce);
  // The lights, switched on through dusk by the sun's elevation here; the sky pass sees them
  // through the air and the clouds as it sees the ground.
  if (kSpecLights == 0u) return vec4(radiance, 1.0f);
  vec3 lights = emitted * lightsDuskFade(muS);
  radiance += lights;
  float total = exposureLuminance(radiance.r, radiance.g, radiance.b);
  float share = total > 0.0f ? exposureLuminance(lights.r, lights.g, lights.b) / total : 0.0f;
  return vec4(radiance, exposureLightsMark(share, 1.0f));
}

#endif
