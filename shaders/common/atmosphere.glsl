// Single scattering in a spherical atmosphere with exponential Rayleigh and Mie densities and
// an absorbing ozone tent (Bruneton & Neyret 2008, "Precomputed Atmospheric Scattering", §2–4;
// the ozone and Mie-extinction terms follow its 2017 reference model), written once in the
// common subset of GLSL 4.50 and C++ like common/noise.glsl.
//
// Compiled as GLSL into the transmittance-table and sky shaders, and as C++ (double) into
// engine/reference/atmosphere_model.cpp, the CPU reference the tests compare the table with.
// The rules of the common subset, types and builtins: definitions.glsl (C++: definitions.h).
// The includer provides SUN_TRANSMITTANCE(a, h, muS): the transmittance from
// altitude h toward a sun of zenith cosine muS, zero where the planet is in the way (GLSL: the
// table; C++: the integral below).
//
// Every quantity is expressed through altitudes h above the planet radius R, never through
// differences of radii: r² − r_s² = (h − h_s)(2R + h + h_s). In float, R² = 4·10¹³ m² keeps
// only ~2·10⁶ m² of absolute precision, which would be kilometres of error near the ground.
#ifndef PLANET_COMMON_ATMOSPHERE_GLSL
#define PLANET_COMMON_ATMOSPHERE_GLSL

#include "common/definitions.glsl"

SHARED_CONST real kAtmospherePi = real(3.14159265358979f);

// The distances along a ray from altitude h with zenith cosine mu to the sphere at altitude hs:
// x = the nearer intersection ahead, y = the farther, -1 for each that does not exist (behind
// the start, or the ray misses). Roots of t² + 2 r mu t + c = 0 with c = r² − rs², taken in
// the cancellation-free form (q = −b − sign(b)·sqrt(b² − c), roots q and c / q).
vec2 raySphere(real R, real h, real mu, real hs) {
  real r = R + h;
  real b = r * mu;
  real c = (h - hs) * (real(2.0f) * R + h + hs);
  real disc = b * b - c;
  if (disc < real(0.0f)) return vec2(real(-1.0f), real(-1.0f));
  real s = sqrt(disc);
  real q = b > real(0.0f) ? -b - s : -b + s;
  real t0 = q;
  real t1 = q != real(0.0f) ? c / q : real(0.0f);
  real nearT = min(t0, t1);
  real farT = max(t0, t1);
  if (farT < real(0.0f)) return vec2(real(-1.0f), real(-1.0f));
  if (nearT < real(0.0f)) return vec2(farT, real(-1.0f));
  return vec2(nearT, farT);
}

// Altitude at distance t along the ray: sqrt(r² + t² + 2 r mu t) − R, without forming r² − R².
real altitudeAlong(real R, real h, real mu, real t) {
  real r = R + h;
  real above = h * (real(2.0f) * R + h) + t * (t + real(2.0f) * r * mu);
  real rt = sqrt(max(R * R + above, real(0.0f)));
  return above / (rt + R);
}

// Distance from altitude h along mu to the top of the atmosphere (the start is inside it).
real distanceToTop(IN(AtmosphereParams) a, real h, real mu) {
  vec2 t = raySphere(real(a.radii.x), h, mu, real(a.radii.y));
  return max(t.x, real(0.0f));
}

// True when the ray from altitude h along mu meets the ground (ahead of the start).
bool rayHitsGround(real R, real h, real mu) {
  if (mu >= real(0.0f)) return false;
  return raySphere(R, h, mu, real(0.0f)).x >= real(0.0f);
}

// Scattering coefficients (per metre) at altitude h.
vec3 rayleighScatteringAt(IN(AtmosphereParams) a, real h) {
  real density = exp(-max(h, real(0.0f)) * real(a.rayleigh.w));
  return vec3(real(a.rayleigh.x), real(a.rayleigh.y), real(a.rayleigh.z)) * density;
}
vec3 mieScatteringAt(IN(AtmosphereParams) a, real h) {
  real density = exp(-max(h, real(0.0f)) * real(a.mieScattering.w));
  return vec3(real(a.mieScattering.x), real(a.mieScattering.y), real(a.mieScattering.z)) * density;
}
// Extinction (scattering plus absorption) per metre at altitude h.
vec3 extinctionAt(IN(AtmosphereParams) a, real h) {
  real hc = max(h, real(0.0f));
  real rayleighDensity = exp(-hc * real(a.rayleigh.w));
  real mieDensity = exp(-hc * real(a.mieScattering.w));
  real ozoneDensity = real(0.0f);
  if (a.ozoneSun.x > 0.0f) ozoneDensity = max(real(0.0f), real(1.0f) - abs(hc - real(a.ozone.w)) / real(a.ozoneSun.x));
  return vec3(real(a.rayleigh.x), real(a.rayleigh.y), real(a.rayleigh.z)) * rayleighDensity +
         vec3(real(a.mieExtinction.x), real(a.mieExtinction.y), real(a.mieExtinction.z)) * mieDensity +
         vec3(real(a.ozone.x), real(a.ozone.y), real(a.ozone.z)) * ozoneDensity;
}

// Optical depth from altitude h along mu to the top of the atmosphere, by the midpoint rule
// with `steps` equal steps.
vec3 opticalDepthToTop(IN(AtmosphereParams) a, real h, real mu, uint steps) {
  real R = real(a.radii.x);
  real dt = distanceToTop(a, h, mu) / real(steps);
  vec3 sum = vec3(real(0.0f), real(0.0f), real(0.0f));
  for (uint i = 0u; i < steps; ++i) {
    real t = (real(i) + real(0.5f)) * dt;
    sum = sum + extinctionAt(a, altitudeAlong(R, h, mu, t));
  }
  return sum * dt;
}

// The transmittance table's parameterisation (Bruneton & Neyret 2008, as in its 2017 reference
// code): v = ρ / H with ρ = sqrt(r² − R²) and H = sqrt(top² − R²); u places the distance to the
// top between its minimum (straight up) and its maximum (toward the horizon) at that altitude.
// Texel centres map to the ends of each range, so the table holds the exact end values.
real unitToTexel(real x, real size) { return real(0.5f) / size + x * (real(1.0f) - real(1.0f) / size); }
real texelToUnit(real u, real size) { return (u - real(0.5f) / size) / (real(1.0f) - real(1.0f) / size); }

vec2 transmittanceUv(IN(AtmosphereParams) a, real h, real mu) {
  real R = real(a.radii.x);
  real top = real(a.radii.y);
  real H = sqrt(top * (real(2.0f) * R + top));
  real rho = sqrt(max(h, real(0.0f)) * (real(2.0f) * R + max(h, real(0.0f))));
  real d = distanceToTop(a, h, mu);
  real dMin = top - h;
  real dMax = rho + H;
  real xMu = dMax > dMin ? (d - dMin) / (dMax - dMin) : real(0.0f);
  return vec2(unitToTexel(clamp(xMu, real(0.0f), real(1.0f)), real(kTransmittanceWidth)),
              unitToTexel(clamp(rho / H, real(0.0f), real(1.0f)), real(kTransmittanceHeight)));
}

// The inverse: the altitude (x) and zenith cosine (y) a table texel stands for.
vec2 transmittanceAltitudeMu(IN(AtmosphereParams) a, real u, real v) {
  real R = real(a.radii.x);
  real top = real(a.radii.y);
  real H = sqrt(top * (real(2.0f) * R + top));
  real xMu = texelToUnit(u, real(kTransmittanceWidth));
  real rho = H * texelToUnit(v, real(kTransmittanceHeight));
  // h from ρ² = h (2R + h), solved without cancellation.
  real h = rho * rho / (sqrt(R * R + rho * rho) + R);
  real r = R + h;
  real dMin = top - h;
  real dMax = rho + H;
  real d = dMin + xMu * (dMax - dMin);
  // top² − r² − d² = (top − h)(2R + top + h) − d², over 2 r d.
  real mu = d == real(0.0f) ? real(1.0f) : ((top - h) * (real(2.0f) * R + top + h) - d * d) / (real(2.0f) * r * d);
  return vec2(h, clamp(mu, real(-1.0f), real(1.0f)));
}

// Phase functions (per steradian): Rayleigh, and Cornette-Shanks for Mie.
real rayleighPhase(real nu) { return real(3.0f) / (real(16.0f) * kAtmospherePi) * (real(1.0f) + nu * nu); }
real miePhase(real g, real nu) {
  real k = real(3.0f) / (real(8.0f) * kAtmospherePi) * (real(1.0f) - g * g) / (real(2.0f) + g * g);
  real base = real(1.0f) + g * g - real(2.0f) * g * nu;
  return k * (real(1.0f) + nu * nu) / (base * sqrt(base));
}

// Single-scattered radiance reaching the start of a ray segment (altitude h, zenith cosine mu,
// length tMax) per unit sun irradiance, and the segment's transmittance. muS is the sun's
// zenith cosine at the start and nu the cosine between the ray and the sun; at distance t the
// sun's zenith cosine is (r muS + t nu) / r_t (Bruneton & Neyret 2008, eq. 5 ff.). Midpoint
// rule with `steps` equal steps; the sun's transmittance at each sample is SUN_TRANSMITTANCE.
void singleScattering(IN(AtmosphereParams) a, real h, real mu, real muS, real nu, real tMax, uint steps,
                      OUT(vec3) radiance, OUT(vec3) transmittance) {
  real R = real(a.radii.x);
  real r = R + h;
  real dt = tMax / real(steps);
  vec3 rayleighSum = vec3(real(0.0f), real(0.0f), real(0.0f));
  vec3 mieSum = vec3(real(0.0f), real(0.0f), real(0.0f));
  vec3 depth = vec3(real(0.0f), real(0.0f), real(0.0f));
  for (uint i = 0u; i < steps; ++i) {
    real t = (real(i) + real(0.5f)) * dt;
    real ht = altitudeAlong(R, h, mu, t);
    real muSt = clamp((r * muS + t * nu) / (R + ht), real(-1.0f), real(1.0f));
    vec3 extinction = extinctionAt(a, ht);
    // Transmittance from the start to the sample: half of this step's depth, then the rest after.
    vec3 toSample = depth + extinction * (real(0.5f) * dt);
    vec3 viewT = vec3(exp(-toSample.x), exp(-toSample.y), exp(-toSample.z));
    vec3 lit = viewT * SUN_TRANSMITTANCE(a, ht, muSt);
    rayleighSum = rayleighSum + lit * rayleighScatteringAt(a, ht);
    mieSum = mieSum + lit * mieScatteringAt(a, ht);
    depth = depth + extinction * dt;
  }
  real sun = real(a.ozoneSun.y);
  radiance = (rayleighSum * rayleighPhase(nu) + mieSum * miePhase(real(a.mieExtinction.w), nu)) * (dt * sun);
  transmittance = vec3(exp(-depth.x), exp(-depth.y), exp(-depth.z));
}

#endif
