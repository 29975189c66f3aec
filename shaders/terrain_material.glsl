// Ground materials from climate and terrain (issue 20, point 1), for the earth and mars schemes.
//
// Temperature: the mean annual temperature at sea level falls from the equator to the poles as
// T₀(φ) = T_eq − ΔT · sin²φ (30 °C and 45 °C on Earth: 30 °C at the equator, −15 °C at the
// poles, 7.5 °C at 45°; a fit to zonal-mean surface air temperature), and with height by the
// lapse rate (6.5 K/km, the standard atmosphere's).
// Moisture (0 desert .. 1 rainforest): a mean, minus the dry subtropical belts (15–35° of
// latitude, where the Hadley cells' air sinks), plus the colour noise (regional rainfall), plus
// nearness to the sea estimated from height: low ground is near the coast (the continents' height
// rises inland; a shoreline distance would need neighbours, which the per-point design has not),
// so land below the coastal height is wetter. Interior basins come out too wet; known limit.
// Slope (1 − cos of the slope angle) from the per-pixel normal: bare rock on steep slopes, scree
// on the slopes just below the rock's (the talus at the angle of repose below cliffs), snow only
// where the mean annual temperature is below the snow temperature and the slope holds it.
// Curvature is left out: the patch normals are bilinear within a texel, so their screen
// derivatives are constant per texel and would print the texel grid near the camera.
// The biomes follow Whittaker's diagram (temperature against moisture): ice, tundra, boreal
// conifers, temperate forest, grassland, steppe and savanna, hot and cold desert, rainforest.
// Every edge is frayed by the band noise (per vertex) plus the per-pixel octaves
// (terrain_detail.glsl), so it is ragged at every scale down to the pixel.
#ifndef PLANET_TERRAIN_MATERIAL_GLSL
#define PLANET_TERRAIN_MATERIAL_GLSL

#include "terrain_colors.glsl"
#include "terrain_detail.glsl"

// What the ground is at a pixel: its albedo and how its detail looks.
struct GroundMaterial {
  vec3 albedo;
  float relief;    // detail slope scale (0 smooth .. 1 rough rock)
  float contrast;  // albedo variation of the detail (fraction)
  float stony;     // 0 .. 1: how much of the detail's stone field shows
};

// Mean annual temperature (°C) at sin(latitude) s and `altitudeM` above sea level.
float meanTemperatureC(float s, float altitudeM) {
  return frame.climate.x - frame.climate.y * s * s - frame.climate.z * altitudeM;
}

// Moisture 0 .. 1 at |latitude| (degrees), the noise and `altitudeM` above sea level.
float moistureAt(float latitudeDeg, float noise, float altitudeM) {
  float belt = (latitudeDeg - 25.0f) / 9.0f;
  float coast = 1.0f - smoothstep(0.0f, max(frame.moisture.z, 1.0f), altitudeM);
  return frame.moisture.x + frame.moisture.y * noise - frame.moisture.w * exp(-belt * belt) + 0.2f * coast;
}

GroundMaterial material(vec3 albedo, float relief, float contrast, float stony) {
  GroundMaterial m;
  m.albedo = albedo;
  m.relief = relief;
  m.contrast = contrast;
  m.stony = stony;
  return m;
}

GroundMaterial blend(GroundMaterial a, GroundMaterial b, float t) {
  return material(mix(a.albedo, b.albedo, t), mix(a.relief, b.relief, t), mix(a.contrast, b.contrast, t),
                  mix(a.stony, b.stony, t));
}

// Weight of a threshold crossed at `edge` by x over ±width (an edge frayed by x's noise).
float over(float x, float edge, float width) { return smoothstep(edge - width, edge + width, x); }

// The earth scheme. noise: the band noise plus the per-pixel octaves (about [-1, 1]);
// pixelM: the height change across the pixel (a beach narrower than the pixel shows its share).
GroundMaterial earthMaterial(float altitudeM, float slope, float s, float noise, float pixelM) {
  float latitudeDeg = degrees(asin(min(abs(s), 1.0f)));
  // Temperature and moisture get the noise with different weights and signs, so their edges
  // do not run together.
  float t = meanTemperatureC(s, altitudeM) + 4.0f * noise;
  float wet = moistureAt(latitudeDeg, noise, altitudeM);
  GroundMaterial conifer = material(kColorConifer, 1.0f, 0.6f, 0.0f);
  GroundMaterial forest = material(kColorForest, 1.0f, 0.6f, 0.0f);
  GroundMaterial grass = material(kColorGrass, 1.0f, 0.6f, 0.05f);
  GroundMaterial dryGrass = material(kColorDryGrass, 0.9f, 0.5f, 0.25f);
  GroundMaterial desert = material(kColorDesert, 0.5f, 0.25f, 0.4f);
  GroundMaterial tundra = material(kColorTundra, 0.8f, 0.45f, 0.3f);
  GroundMaterial rock = material(kColorCliff, 1.0f, 0.25f, 0.6f);
  GroundMaterial scree = material(kColorScree, 0.9f, 0.3f, 1.0f);
  GroundMaterial sand = material(kColorBeach, 0.25f, 0.1f, 0.1f);
  GroundMaterial snow = material(kColorSnow, 0.3f, 0.04f, 0.0f);
  // Whittaker: trees where it is wet enough (the warmer, the more water they need), grass
  // where less, desert where dry; conifers where cool, broadleaf (and rainforest) where warm.
  GroundMaterial trees = blend(conifer, forest, over(t, 8.0f, 3.0f));
  GroundMaterial open = blend(dryGrass, grass, over(wet, 0.45f + 0.006f * t, 0.1f));
  GroundMaterial g = blend(desert, open, over(wet, 0.22f + 0.004f * t, 0.1f));
  g = blend(g, trees, over(wet, 0.6f + 0.006f * t, 0.08f));
  // Tundra beyond the tree line (mean annual temperature about −2 °C), whatever the moisture.
  g = blend(tundra, g, over(t, -2.0f, 1.5f));
  // Beaches only on gentle coasts.
  float beach = frame.planet.z;
  if (beach > 0.0f) {
    float top = beach * (1.0f + 0.8f * noise);
    float shore = (1.0f - smoothstep(top - pixelM, top + pixelM, altitudeM)) * clamp(top / max(pixelM, 1e-3f), 0.0f, 1.0f);
    g = blend(g, sand, shore * (1.0f - over(slope, 0.1f, 0.04f)));
  }
  // Rock on steep slopes; scree on the slopes just below the rock's where little grows to hold
  // the debris (above the tree line, or dry), vegetation elsewhere. Vegetation holds on slopes
  // a little steeper where it is warm and wet.
  float bare = max(1.0f - over(t, 2.0f, 3.0f), 1.0f - over(wet, 0.3f, 0.08f));
  float rockSlope = frame.slopes.x + 0.12f * noise + 0.05f * (1.0f - bare);
  g = blend(g, scree, over(slope, rockSlope - 0.12f, 0.04f) * bare);
  g = blend(g, rock, over(slope, rockSlope, 0.05f));
  // Snow where the mean annual temperature is below the snow temperature and the slope holds it.
  float cold = 1.0f - over(t, frame.climate.w, 1.5f);
  return blend(g, snow, cold * (1.0f - over(slope, frame.slopes.y, 0.06f)));
}

// The mars scheme: bright dust on the plains and high ground, dark basalt sand in the lows, rock
// on slopes, scree below it, and frost where the temperature is below the frost point.
GroundMaterial marsMaterial(float altitudeM, float slope, float s, float noise) {
  GroundMaterial basalt = material(kColorLowland, 0.4f, 0.2f, 0.3f);
  GroundMaterial dust = material(kColorHighland, 0.35f, 0.15f, 0.4f);
  GroundMaterial rock = material(kColorCliff, 1.0f, 0.25f, 0.6f);
  GroundMaterial scree = material(kColorScree, 0.9f, 0.3f, 1.0f);
  GroundMaterial ice = material(kColorSnow, 0.3f, 0.05f, 0.0f);
  GroundMaterial g = blend(basalt, dust, over(altitudeM + 2500.0f * noise, -1500.0f, 1200.0f));
  float rockSlope = frame.slopes.x + 0.12f * noise;
  g = blend(g, scree, over(slope, rockSlope - 0.12f, 0.04f));
  g = blend(g, rock, over(slope, rockSlope, 0.05f));
  float t = meanTemperatureC(s, altitudeM) + 6.0f * noise;
  float cold = 1.0f - over(t, frame.climate.w, 3.0f);
  return blend(g, ice, cold * (1.0f - over(slope, frame.slopes.y, 0.06f)));
}

// The moon scheme: maria low and dark, highlands bright (frayed by the noise at every scale), fresh
// rock on steep slopes with scree below it.
GroundMaterial moonMaterial(float altitudeM, float slope, float noise) {
  GroundMaterial mare = material(kColorLowland, 0.5f, 0.15f, 0.3f);
  GroundMaterial highland = material(kColorHighland, 0.5f, 0.15f, 0.3f);
  GroundMaterial rock = material(kColorCliff, 1.0f, 0.25f, 0.6f);
  GroundMaterial scree = material(kColorScree, 0.9f, 0.3f, 1.0f);
  GroundMaterial g = blend(mare, highland, smoothstep(-1500.0f, 1500.0f, altitudeM + 1500.0f * noise));
  float rockSlope = frame.slopes.x + 0.12f * noise;
  g = blend(g, scree, over(slope, rockSlope - 0.12f, 0.04f));
  return blend(g, rock, over(slope, rockSlope, 0.05f));
}

#endif
