// Eclipses (issue 23, point 1): how much of the sun's disc a point sees past the other bodies of
// a scene, written once in the common subset of GLSL 4.50 and C++. Included by the shaders that
// light a surface, the air or a ring (terrain.frag, water.frag, sky.comp, aerial_perspective.comp,
// ring.frag) and by engine/reference/eclipse.cpp (the CPU reference the tests hold it against).
//
// The sun and each occluder are discs on the point's sky: the sun of angular radius ρ, a sphere
// of radius R at distance d of angular radius β = asin(R / d), their centres c apart. The light
// that reaches the point is the share of the sun's disc that the occluder leaves uncovered (a
// uniform disc: no limb darkening): 0 in the umbra (β ≥ ρ + c), 1 − β²/ρ² in the antumbra (the
// occluder inside the sun's disc: an annular eclipse), and in the penumbra one minus the lens
// where the two discs overlap, over πρ². The discs are taken as flat, which is good to O(ρ²)
// while ρ stays below kMaxSunAngularRadiusRad (reference/sunlight.h). Several occluders multiply
// their visible shares (exact unless two of them overlap on the sun's disc at once). An occluder
// with air also bends a little reddened sunlight into its shadow (eclipseSunVisibleRefracted;
// its share comes from the CPU, engine/reference/eclipse.h refractedIntoShadow).
//
// Rules (STYLE.md, definitions.glsl): `real` for every float, .x/.y/.z, an `f` suffix on every
// literal, IN() for structs passed in. The includer provides EclipseParams
// (shared/eclipse_params.h); C++ adds acos, asin and the two-argument atan to the kernel.
#ifndef PLANET_COMMON_ECLIPSE_GLSL
#define PLANET_COMMON_ECLIPSE_GLSL

#include "common/definitions.glsl"

SHARED_CONST real kEclipsePi = 3.14159265358979f;
// A sun smaller than this (rad) is treated as this small: a point-like sun would divide by 0.
SHARED_CONST real kEclipseMinSunRadius = 1.0e-6f;

// The share of the sun's disc (radius 1) that a disc of radius k covers when their centres are s
// apart (k, s ≥ 0, both in units of the sun's radius).
real sunDiscCovered(real k, real s) {
  if (s >= 1.0f + k) return 0.0f;      // apart: full sun
  if (s <= k - 1.0f) return 1.0f;      // the occluder covers the sun: umbra
  if (s <= 1.0f - k) return k * k;     // the occluder inside the sun: antumbra (annular)
  // The lens: the circular segment of each disc beyond the chord through the two crossings,
  // which lies x from the sun's centre and y = s − x from the occluder's; h is the half chord.
  // h² = (1 − x)(1 + x) in factors that hold no cancellation (Heron's form), and each segment's
  // half angle from atan(h, ·): acos near 1, where a large occluder's segment is thin, loses
  // half the digits (and a GPU's acos more).
  PRECISE real x = (s * s + 1.0f - k * k) / (2.0f * s);
  PRECISE real y = s - x;
  PRECISE real h2 = (k - s + 1.0f) * (k + s - 1.0f) * (s + 1.0f - k) * (s + 1.0f + k) / (4.0f * s * s);
  PRECISE real h = sqrt(max(h2, 0.0f));
  PRECISE real sunSegment = atan(h, x) - x * h;
  PRECISE real occluderSegment = k * k * atan(h, y) - y * h;
  return clamp((sunSegment + occluderSegment) / kEclipsePi, 0.0f, 1.0f);
}

// The share of the sun's disc (toward the unit vector `sun`, angular radius sunRadius) that a
// point sees past a sphere of radius `radius` whose centre is `toOccluder` from the point.
// Inside the sphere: 0.
real occluderSunVisible(vec3 toOccluder, real radius, vec3 sun, real sunRadius) {
  PRECISE real d2 = toOccluder.x * toOccluder.x + toOccluder.y * toOccluder.y + toOccluder.z * toOccluder.z;
  PRECISE real d = sqrt(d2);
  if (!(d > radius)) return radius > 0.0f ? 0.0f : 1.0f;
  real beta = asin(radius / d);
  // The angle between the occluder and the sun: atan2(|D × S|, D · S) keeps it exact near 0,
  // where acos of the cosine would lose it.
  PRECISE real cx = toOccluder.y * sun.z - toOccluder.z * sun.y;
  PRECISE real cy = toOccluder.z * sun.x - toOccluder.x * sun.z;
  PRECISE real cz = toOccluder.x * sun.y - toOccluder.y * sun.x;
  PRECISE real along = toOccluder.x * sun.x + toOccluder.y * sun.y + toOccluder.z * sun.z;
  real c = atan(sqrt(cx * cx + cy * cy + cz * cz), along);
  real rho = max(sunRadius, kEclipseMinSunRadius);
  return 1.0f - sunDiscCovered(beta / rho, c / rho);
}

// The share of the sun's disc a point sees past every occluder of e; `fromCamera` is the point
// minus the camera, in the frame of e's positions and of `sun`. `refracted` is the sunlight the
// occluders' air bends into their shadows there, as a share of the sun's irradiance per
// channel: each occluder's e.refracted times the share of the sun it covers.
#ifndef ECLIPSE_POSSIBLE
#define ECLIPSE_POSSIBLE true
#endif

real eclipseSunVisibleRefracted(vec3 fromCamera, vec3 sun, IN(EclipseParams) e, OUT(vec3) refracted) {
  PRECISE real visible = 1.0f;
  refracted = vec3(0.0f, 0.0f, 0.0f);
  // ECLIPSE_POSSIBLE: a GLSL includer's specialization constant, false where no other body can
  // hide the sun (a renderer of one body): lavapipe runs a loop's body once even for no
  // occluders, and the shader compiler drops it only when the count is a constant.
  uint count = ECLIPSE_POSSIBLE ? uint(e.sun.y) : 0u;
  for (uint i = 0u; i < count; ++i) {
    vec4 o = e.occluders[i];
    vec3 toOccluder = vec3(o.x - fromCamera.x, o.y - fromCamera.y, o.z - fromCamera.z);
    real share = occluderSunVisible(toOccluder, o.w, sun, e.sun.x);
    visible = visible * share;
    vec4 bent = e.refracted[i];
    refracted = refracted + vec3(bent.x, bent.y, bent.z) * (1.0f - share);
  }
  return visible;
}

real eclipseSunVisible(vec3 fromCamera, vec3 sun, IN(EclipseParams) e) {
  vec3 refracted;
  return eclipseSunVisibleRefracted(fromCamera, sun, e, refracted);
}

#endif
