// The cloud layer (seed 001 §4.4: three cover images cross-faded, Elias's cover function) as the
// sky passes (sky_compose.glsl) and the sea (water.frag) see it: the cover's density at a point,
// the mip level of a footprint, the light a cloud sends toward the eye, and how much of the
// sun's direct light a column lets through. The includer defines, before including it:
// - CLOUD_COVER: the samplerCube of the three cover images (rgb);
// - CLOUD_LAYER: vec4 (bottom m above R, top, extinction of full density 1/m, cloud width over
//   the layer's thickness), SkyUniforms::clouds;
// - CLOUD_SHAPE: vec4 (angle of a level-0 cover texel rad, the cover's last mip level, ...),
//   SkyUniforms::cloudShape;
// - CLOUD_MOTION: vec4 (weights of the three images, drift angle rad), SkyUniforms::cloudMotion;
// - CLOUD_LOCAL_TO_PLANET: a mat3 or mat4 whose upper 3×3 turns local directions into the
//   planet frame's;
// and provides atmosphere_lookup.glsl (raySphere, kAtmospherePi).
//
// The layer is a height field: the column over each point of the cover holds cloud from the
// layer's bottom up to bottom + density · thickness, with extinction ∝ density, so a dense column
// is a tall, optically thick cloud and a thin one a low wisp. A far sample reads the density
// averaged over its footprint (the cover's mip levels): a sparse field of small clouds becomes a
// low, thin haze there, not an opaque deck (gaps stay open).
#ifndef PLANET_CLOUD_LAYER_GLSL
#define PLANET_CLOUD_LAYER_GLSL

// Cover density (0..1) at a point `fromCentre` (local frame, relative to the planet's centre),
// cross-faded between the three images (seed 001 eq. 4.2) from mip level `lod`.
float coverDensity(vec3 fromCentre, float lod) {
  vec3 planetDir = normalize(mat3(CLOUD_LOCAL_TO_PLANET) * fromCentre);
  float angle = CLOUD_MOTION.w;  // the layer drifts eastward: look up where it came from
  float ca = cos(angle), sa = sin(angle);
  vec3 drifted = vec3(ca * planetDir.x + sa * planetDir.y, -sa * planetDir.x + ca * planetDir.y, planetDir.z);
  return dot(textureLod(CLOUD_COVER, drifted, lod).rgb, CLOUD_MOTION.xyz);
}

// The mip level whose texels span `footprintM` on the layer (radius rLayer).
float coverLod(float footprintM, float rLayer) {
  return clamp(log2(max(footprintM / (CLOUD_SHAPE.x * rLayer), 1.0f)), 0.0f, CLOUD_SHAPE.y);
}

// Henyey–Greenstein phase function (per steradian) for the cosine nu between light and view.
float henyeyGreenstein(float g, float nu) {
  float k = 1.0f + g * g - 2.0f * g * nu;
  return (1.0f - g * g) / (4.0f * kAtmospherePi * k * sqrt(k));
}

// The clouds' phase function: forward peaked (the silver lining toward the sun), with some light
// sent back.
float cloudPhase(float nu) { return 0.8f * henyeyGreenstein(0.75f, nu) + 0.2f * henyeyGreenstein(-0.2f, nu); }

// Light scattered toward the eye by a cloud at altitude h in a column of density d, per unit of
// its opacity. Sunlight reaches the point through the column above it: directly, attenuated by
// Beer–Lambert along the slant path (the cloud's width caps it when the sun is low) and forward
// peaked (the silver lining toward the sun); and diffusely, by the two-stream transmission of a
// conservatively scattering slab, T = 1 / (1 + 3/4 (1 − g) τ) (Bohren 1987), which leaves a thick
// cloud's base grey and its top bright. Sky light comes in the same way from above; a tenth of
// it, the light from the ground and the sky's sides, reaches every part.
vec3 cloudLight(float h, float d, float muS, float phase, vec3 sunLight, vec3 skyLight) {
  float thickness = CLOUD_LAYER.y - CLOUD_LAYER.x;
  float top = CLOUD_LAYER.x + d * thickness;
  float depth = max(top - h, 0.0f);
  float extinction = CLOUD_LAYER.z * d;
  float slant = min(depth / max(muS, 0.05f), CLOUD_LAYER.w * thickness);
  float direct = exp(-extinction * slant);
  // Powder (Schneider & Vos 2015): just inside a cloud the light has not yet been scattered
  // toward the eye, which darkens the rims facing the viewer away from the sun a little.
  float powder = 1.0f - 0.5f * exp(-2.0f * extinction * depth);
  float tauDown = extinction * depth;
  float diffuse = 1.0f / (1.0f + 0.75f * (1.0f - 0.85f) * tauDown / max(muS, 0.2f));
  float diffuseSky = 1.0f / (1.0f + 0.75f * (1.0f - 0.85f) * tauDown);
  const float kAlbedo = 0.95f;
  return kAlbedo * (sunLight * (phase * direct * powder + max(muS, 0.0f) / kAtmospherePi * diffuse) +
                    skyLight / kAtmospherePi * (0.1f + 0.9f * diffuseSky));
}

// The share of the sun's direct light that a column of cover density d lets through, crossed at
// the sun's zenith cosine muS (> 0): at the sun's slant, capped by the cloud's width.
float columnSunTransmittance(float d, float muS) {
  float thickness = CLOUD_LAYER.y - CLOUD_LAYER.x;
  float slant = min(d * thickness / muS, CLOUD_LAYER.w * thickness);
  return exp(-CLOUD_LAYER.z * d * slant);
}

// Where the ray toward the sun from a surface point crosses the sphere through the layer's middle
// (`crossing`, local frame, from the planet's centre), for a point below that sphere in
// sunlight; false above it or at night, where no cloud shades the point. `fromCentre`: the point
// (local frame, from the planet's centre) at altitude hSurface (m above the radius R), muS: the
// sun's zenith cosine there.
bool cloudLayerCrossing(vec3 fromCentre, float R, float hSurface, vec3 sun, float muS, out vec3 crossing) {
  float cloudH = 0.5f * (CLOUD_LAYER.x + CLOUD_LAYER.y);
  crossing = fromCentre;
  if (!(hSurface < cloudH && muS > 0.0f)) return false;
  crossing += sun * raySphere(R, hSurface, muS, cloudH).x;
  return true;
}

// The share of the sun's direct light that reaches a surface point below the layer: the column
// at its crossing (cloudLayerCrossing), crossed at the sun's slant (the cloud's width caps it).
// footprintM: the area the result stands for (the cover's mip level). 1 above the layer's
// middle or at night.
float cloudSunTransmittance(vec3 fromCentre, float R, float hSurface, vec3 sun, float muS, float footprintM) {
  vec3 crossing;
  if (!cloudLayerCrossing(fromCentre, R, hSurface, sun, muS, crossing)) return 1.0f;
  float cloudH = 0.5f * (CLOUD_LAYER.x + CLOUD_LAYER.y);
  return columnSunTransmittance(coverDensity(crossing, coverLod(footprintM, R + cloudH)), muS);
}

// The clouds' shadow on the ground as a factor of all of its light (the compose applies it to
// what was drawn): a cloud blocks the sun's direct light; the sky's and its own scattered light
// still come in (a quarter at most of the full sun's, as under an overcast).
float cloudGroundShadow(float sunTransmittance) { return 1.0f - 0.75f * (1.0f - sunTransmittance); }

#endif
