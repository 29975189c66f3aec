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
// table; C++: the integral below). An includer that defines MULTIPLE_SCATTERING(a, h, muS) (Ψ_ms
// from the multiple-scattering table) also gets multipleScattering() along a ray.
// An includer may define SUN_VISIBLE_ALONG(t): the share of the sun's disc that the sample at
// distance t from a segment's start sees past other bodies (eclipses, common/eclipse.glsl);
// scatteringStep scales both its single and its multiple scattering by it (the light scattered
// many times comes from the air around the sample, in the same shadow where the shadow is much
// wider than the air is high). Without it, no body hides the sun.
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

// The stretch (enter, leave) of a ray from altitude h (zenith cosine mu) inside the sphere at hs;
// leave < enter where it has none ahead.
vec2 stretchInsideSphere(real R, real h, real mu, real hs) {
  vec2 hits = raySphere(R, h, mu, hs);
  if (h < hs) return vec2(real(0.0f), hits.x);  // from inside, the only hit ahead
  if (hits.y < real(0.0f)) return vec2(real(0.0f), real(-1.0f));  // misses, or only touches it
  return hits;
}
// How much of [t0, t1] lies in such a stretch.
real overlap(vec2 stretch, real t0, real t1) { return max(min(stretch.y, t1) - max(stretch.x, t0), real(0.0f)); }

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

// Optical depth from altitude h along mu over the first t metres of the ray, by the midpoint rule
// with `steps` equal steps (past the ground the air keeps its density there: extinctionAt).
vec3 opticalDepthAlong(IN(AtmosphereParams) a, real h, real mu, real t, uint steps) {
  real R = real(a.radii.x);
  real dt = t / real(steps);
  vec3 sum = vec3(real(0.0f), real(0.0f), real(0.0f));
  for (uint i = 0u; i < steps; ++i) {
    real ti = (real(i) + real(0.5f)) * dt;
    sum = sum + extinctionAt(a, altitudeAlong(R, h, mu, ti));
  }
  return sum * dt;
}

// Optical depth from altitude h along mu to the top of the atmosphere, likewise.
vec3 opticalDepthToTop(IN(AtmosphereParams) a, real h, real mu, uint steps) {
  return opticalDepthAlong(a, h, mu, distanceToTop(a, h, mu), steps);
}

// The camera's transmittance table's parameterisation (shared/sky_params.h,
// kCameraTransmittanceDistances; sky_camera_transmittance.comp builds it from inside the air):
// the unit coordinates of distance t along a ray of zenith cosine mu, for a camera whose ground
// sphere's horizon has zenith cosine muHorizon and whose table reaches out to `farthest`.
// - x = sqrt(t / farthest): the texels gather toward the camera, as the aerial volume's slices do.
// - y: mu's share of the way from the horizon to straight up maps by its square root to
//   [0.5, 1], its share of the way to straight down to [0.5, 0]: the optical depth to a given
//   distance changes fastest with mu near the horizon, where the rays graze the dense air.
vec2 cameraTransmittanceUnit(real mu, real t, real muHorizon, real farthest) {
  real above = mu - muHorizon;
  real share = above / (above >= real(0.0f) ? real(1.0f) - muHorizon : real(1.0f) + muHorizon);
  real root = sqrt(min(abs(share), real(1.0f)));
  real y = real(0.5f) + real(0.5f) * (share >= real(0.0f) ? root : -root);
  return vec2(sqrt(clamp(t / farthest, real(0.0f), real(1.0f))), y);
}

// The inverse: the distance (x) and zenith cosine (y) at unit coordinates (x, y).
vec2 cameraTransmittanceDistanceMu(real x, real y, real muHorizon, real farthest) {
  real z = real(2.0f) * y - real(1.0f);
  real share = z >= real(0.0f) ? z * z : -z * z;
  real mu = muHorizon + share * (share >= real(0.0f) ? real(1.0f) - muHorizon : real(1.0f) + muHorizon);
  return vec2(farthest * x * x, clamp(mu, real(-1.0f), real(1.0f)));
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

// Phase functions (per steradian): Rayleigh, and Cornette-Shanks for Mie (miePhases: with each
// channel's own asymmetry g; particles that are large for the wavelength scatter shorter
// wavelengths more forward).
real rayleighPhase(real nu) { return real(3.0f) / (real(16.0f) * kAtmospherePi) * (real(1.0f) + nu * nu); }
real miePhase(real g, real nu) {
  real k = real(3.0f) / (real(8.0f) * kAtmospherePi) * (real(1.0f) - g * g) / (real(2.0f) + g * g);
  real base = real(1.0f) + g * g - real(2.0f) * g * nu;
  return k * (real(1.0f) + nu * nu) / (base * sqrt(base));
}
vec3 miePhases(IN(AtmosphereParams) a, real nu) {
  return vec3(miePhase(real(a.mieG.x), nu), miePhase(real(a.mieG.y), nu), miePhase(real(a.mieG.z), nu));
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
  radiance = (rayleighSum * rayleighPhase(nu) + mieSum * miePhases(a, nu)) * (dt * sun);
  transmittance = vec3(exp(-depth.x), exp(-depth.y), exp(-depth.z));
}

// Multiple scattering (Hillaire 2020, "A Scalable and Production Ready Sky and Atmosphere
// Rendering Technique", §5.5). Light scattered two or more times is taken as isotropic, and the
// radiance around a point as the same over the region that lights it. The second order at a
// point is L2 = ∫ L'(ω) P_u dω over the sphere, with L' the single-scattered radiance arriving
// from ω (isotropic phase P_u = 1/4π, plus the sunlit Lambertian ground where the ray ends);
// the fraction of an isotropic unit radiance that one more scattering returns to the point is
// f_ms = ∫ L_f(ω) P_u dω with L_f = ∫ σ_s T dt; all orders from the second on sum as a
// geometric series, Ψ_ms = L2 / (1 − f_ms), per unit sun irradiance. A sample of the sky then
// adds σ_s · Ψ_ms to its single scattering.

// The table's parameterisation (Hillaire 2020, §5.5): u = (muS + 1) / 2, v = h / top, texel
// centres at the ends of each range.
vec2 multipleScatteringUv(IN(AtmosphereParams) a, real h, real muS) {
  real top = real(a.radii.y);
  real size = real(kMultiScatteringSize);
  return vec2(unitToTexel(clamp(real(0.5f) * (muS + real(1.0f)), real(0.0f), real(1.0f)), size),
              unitToTexel(clamp(h / top, real(0.0f), real(1.0f)), size));
}

// The inverse: the altitude (x) and sun zenith cosine (y) a texel stands for. The top row sits
// a metre below the top: on the top sphere itself, a ray going down would meet it at distance 0
// and read that as where it leaves.
vec2 multipleScatteringAltitudeMuS(IN(AtmosphereParams) a, real u, real v) {
  real top = real(a.radii.y);
  real size = real(kMultiScatteringSize);
  real h = min(clamp(texelToUnit(v, size), real(0.0f), real(1.0f)) * top, top - real(1.0f));
  real muS = real(2.0f) * clamp(texelToUnit(u, size), real(0.0f), real(1.0f)) - real(1.0f);
  return vec2(h, muS);
}

// (1 − e^(−x)) / x, the mean transmittance across a step of optical depth x through a uniform
// medium: the step's exact weight (Hillaire 2020, §5.1), which stays right for the long steps
// of rays toward the horizon; without the cancellation of small x.
real stepTransmittanceMean(real x) {
  return x < real(1.0e-3f) ? real(1.0f) - real(0.5f) * x : (real(1.0f) - exp(-x)) / x;
}

// Ψ_ms (radiance per steradian per unit sun irradiance) and f_ms at altitude h for a sun at zenith
// cosine muS: kMultiScatteringDirections² directions in equal-area cells (midpoints in the zenith
// cosine and the azimuth about the zenith, each cell 4π / n² of the sphere), each ray marched to
// the top or the ground in kMultiScatteringSteps equal steps.
void multipleScatteringTexel(IN(AtmosphereParams) a, real h, real muS, OUT(vec3) psi, OUT(vec3) transfer) {
  real R = real(a.radii.x);
  real r = R + h;
  real sinS = sqrt(max(real(1.0f) - muS * muS, real(0.0f)));
  real isotropic = real(1.0f) / (real(4.0f) * kAtmospherePi);
  real groundBrdf = real(kMultiScatteringGroundAlbedo) / kAtmospherePi;
  uint n = kMultiScatteringDirections;
  vec3 secondOrder = vec3(real(0.0f), real(0.0f), real(0.0f));
  vec3 returned = vec3(real(0.0f), real(0.0f), real(0.0f));
  for (uint i = 0u; i < n; ++i) {
    real mu = real(1.0f) - real(2.0f) * (real(i) + real(0.5f)) / real(n);
    real sinV = sqrt(max(real(1.0f) - mu * mu, real(0.0f)));
    bool ground = rayHitsGround(R, h, mu);
    real tMax = ground ? raySphere(R, h, mu, real(0.0f)).x : distanceToTop(a, h, mu);
    real dt = tMax / real(kMultiScatteringSteps);
    for (uint j = 0u; j < n; ++j) {
      real phi = real(2.0f) * kAtmospherePi * (real(j) + real(0.5f)) / real(n);
      real nu = mu * muS + sinV * sinS * cos(phi);
      vec3 depth = vec3(real(0.0f), real(0.0f), real(0.0f));
      vec3 light = vec3(real(0.0f), real(0.0f), real(0.0f));
      vec3 fraction = vec3(real(0.0f), real(0.0f), real(0.0f));
      for (uint k = 0u; k < kMultiScatteringSteps; ++k) {
        real t = (real(k) + real(0.5f)) * dt;
        real ht = altitudeAlong(R, h, mu, t);
        real muSt = clamp((r * muS + t * nu) / (R + ht), real(-1.0f), real(1.0f));
        vec3 stepDepth = extinctionAt(a, ht) * dt;
        // Transmittance from the point to the step's start, times the step's mean transmittance.
        vec3 weight = vec3(exp(-depth.x) * stepTransmittanceMean(stepDepth.x),
                           exp(-depth.y) * stepTransmittanceMean(stepDepth.y),
                           exp(-depth.z) * stepTransmittanceMean(stepDepth.z)) * dt;
        vec3 scattered = (rayleighScatteringAt(a, ht) + mieScatteringAt(a, ht)) * weight;
        fraction = fraction + scattered;
        light = light + scattered * SUN_TRANSMITTANCE(a, ht, muSt) * isotropic;
        depth = depth + stepDepth;
      }
      if (ground) {
        // The ground where the ray ends, lit by the sun through the air, seen through the ray.
        real muSGround = clamp((r * muS + tMax * nu) / R, real(-1.0f), real(1.0f));
        vec3 viewT = vec3(exp(-depth.x), exp(-depth.y), exp(-depth.z));
        light = light + viewT * SUN_TRANSMITTANCE(a, real(0.0f), muSGround) * (groundBrdf * max(muSGround, real(0.0f)));
      }
      secondOrder = secondOrder + light;
      returned = returned + fraction;
    }
  }
  // Each direction weighs P_u · 4π / n² = 1 / n².
  real cell = real(1.0f) / real(n * n);
  transfer = returned * cell;
  vec3 series = vec3(real(1.0f) / (real(1.0f) - transfer.x), real(1.0f) / (real(1.0f) - transfer.y),
                     real(1.0f) / (real(1.0f) - transfer.z));
  psi = secondOrder * cell * series;
}

// The sky-view table (Hillaire 2020, §5.3), rebuilt for each frame's viewpoint and sun: the sky
// radiance around the viewpoint by view azimuth from the sun (u: 0 toward the sun .. π away; the
// sky is symmetric about the sun's vertical plane, so half the circle is enough) and view zenith
// angle θ (v). The rows are spread non-linearly toward the horizon of the ground sphere θh,
// where the sky changes fastest: above it v = (1 − sqrt((θh − θ) / (θh − θmin))) / 2, below it
// v = (1 + sqrt((θ − θh) / (π − θh))) / 2. θmin is the zenith inside the atmosphere; above its top
// it is the direction that grazes the top, so that from orbit the rows hold only the rays that
// cross the shell and gather at the limb.
vec2 skyViewZenithRange(IN(AtmosphereParams) a, real h, real hGround) {
  real R = real(a.radii.x);
  real top = real(a.radii.y);
  real hg = min(hGround, h);
  // The angles as atan(sin, cos) of the tangent rays (both scaled by r), not acos of their
  // cosines: from far away the whole range is ~10⁻³ rad next to θ ≈ π, where acos of a float
  // (lavapipe's approximation especially) may be off by ~10⁻⁵ rad, kilometres of tangent
  // altitude at the limb.
  real horizonCos = -sqrt(max((h - hg) * (real(2.0f) * R + h + hg), real(0.0f)));
  real start = real(0.0f);
  if (h > top) start = atan(R + top, -sqrt((h - top) * (real(2.0f) * R + h + top)));
  return vec2(start, atan(R + hg, horizonCos));
}

real skyViewV(real theta, vec2 range) {
  if (theta <= range.y) {
    real x = clamp((range.y - theta) / max(range.y - range.x, real(1.0e-6f)), real(0.0f), real(1.0f));
    return real(0.5f) * (real(1.0f) - sqrt(x));
  }
  real x = clamp((theta - range.y) / max(kAtmospherePi - range.y, real(1.0e-6f)), real(0.0f), real(1.0f));
  return real(0.5f) * (real(1.0f) + sqrt(x));
}

real skyViewTheta(real v, vec2 range) {
  if (v < real(0.5f)) {
    real s = real(1.0f) - real(2.0f) * v;
    return range.y - s * s * (range.y - range.x);
  }
  real s = real(2.0f) * v - real(1.0f);
  return range.y + s * s * (kAtmospherePi - range.y);
}

#ifdef MULTIPLE_SCATTERING
// Light scattered two or more times toward the start of a ray segment, per the params' sun
// irradiance, over the same samples as singleScattering (altitude h, zenith cosine mu, sun zenith
// cosine muS, view-sun cosine nu, length tMax, `steps` midpoint steps): σ_s · Ψ_ms at each sample,
// with Ψ_ms from the includer's MULTIPLE_SCATTERING(a, h, muS) (GLSL: the table; C++: the CPU
// table), seen through the air before it.
vec3 multipleScattering(IN(AtmosphereParams) a, real h, real mu, real muS, real nu, real tMax, uint steps) {
  real R = real(a.radii.x);
  real r = R + h;
  real dt = tMax / real(steps);
  vec3 sum = vec3(real(0.0f), real(0.0f), real(0.0f));
  vec3 depth = vec3(real(0.0f), real(0.0f), real(0.0f));
  for (uint i = 0u; i < steps; ++i) {
    real t = (real(i) + real(0.5f)) * dt;
    real ht = altitudeAlong(R, h, mu, t);
    real muSt = clamp((r * muS + t * nu) / (R + ht), real(-1.0f), real(1.0f));
    vec3 extinction = extinctionAt(a, ht);
    vec3 toSample = depth + extinction * (real(0.5f) * dt);
    vec3 viewT = vec3(exp(-toSample.x), exp(-toSample.y), exp(-toSample.z));
    sum = sum + viewT * (rayleighScatteringAt(a, ht) + mieScatteringAt(a, ht)) * MULTIPLE_SCATTERING(a, ht, muSt);
    depth = depth + extinction * dt;
  }
  return sum * (dt * real(a.ozoneSun.y));
}

// One step of the sky march (Hillaire 2020, §5.1): the sample at distance t from the start of a
// segment (altitude h, zenith cosine mu, sun zenith cosine muS, view-sun cosine nu) stands for a
// step of length dt; its single scattering (sun through the transmittance table, phases given)
// and multiple scattering (σ_s · Ψ_ms) are integrated over the step in closed form for a uniform
// medium, S · (1 − e^(−σ_t dt)) / σ_t, which stays right for the long steps of rays toward the
// horizon. Adds to `single` and `total` (per the params' sun irradiance) through the segment's
// transmittance so far, and moves that transmittance past the step.
#ifndef SUN_VISIBLE_ALONG
#define SUN_VISIBLE_ALONG(t) real(1.0f)
#endif
void scatteringStep(IN(AtmosphereParams) a, real h, real mu, real muS, real nu, real phaseR, vec3 phaseM, real t,
                    real dt, INOUT(vec3) single, INOUT(vec3) total, INOUT(vec3) transmittance) {
  real R = real(a.radii.x);
  real visible = SUN_VISIBLE_ALONG(t);
  real ht = altitudeAlong(R, h, mu, t);
  real muSt = clamp(((R + h) * muS + t * nu) / (R + ht), real(-1.0f), real(1.0f));
  vec3 rayleigh = rayleighScatteringAt(a, ht);
  vec3 mie = mieScatteringAt(a, ht);
  vec3 stepDepth = extinctionAt(a, ht) * dt;
  vec3 weight = vec3(transmittance.x * stepTransmittanceMean(stepDepth.x),
                     transmittance.y * stepTransmittanceMean(stepDepth.y),
                     transmittance.z * stepTransmittanceMean(stepDepth.z)) * (dt * real(a.ozoneSun.y) * visible);
  vec3 once = SUN_TRANSMITTANCE(a, ht, muSt) * (rayleigh * phaseR + mie * phaseM) * weight;
  single = single + once;
  total = total + once + (rayleigh + mie) * MULTIPLE_SCATTERING(a, ht, muSt) * weight;
  transmittance = transmittance * vec3(exp(-stepDepth.x), exp(-stepDepth.y), exp(-stepDepth.z));
}

// Where the point at x (0 .. 1) of a segment's steps lies along it, as a share of its length, for
// steps spaced as `spacing` says (kStepsEqual, kStepsTowardStart, kStepsTowardEnd:
// shared/sky_params.h).
real stepShare(real x, uint spacing) {
  return spacing == kStepsTowardStart ? x * x : spacing == kStepsTowardEnd ? x * (real(2.0f) - x) : x;
}

// How the sky-view table spaces the steps of a ray from altitude h that meets the ground sphere or
// not: equally from above the air; from inside it, toward the viewpoint, or, for a ray that meets
// the ground, toward the ground, where the haze is.
uint skyStepSpacing(IN(AtmosphereParams) a, real h, bool meetsGround) {
  return h >= real(a.radii.y) ? kStepsEqual : meetsGround ? kStepsTowardEnd : kStepsTowardStart;
}

// Single (`single`) and single plus multiple (`total`) scattering toward the start of a segment of
// length tMax, and its transmittance, in `steps` steps of scatteringStep spaced as `spacing` says
// (stepShare).
void scatteringAlong(IN(AtmosphereParams) a, real h, real mu, real muS, real nu, real tMax, uint steps, uint spacing,
                     OUT(vec3) single, OUT(vec3) total, OUT(vec3) transmittance) {
  real phaseR = rayleighPhase(nu);
  vec3 phaseM = miePhases(a, nu);
  single = vec3(real(0.0f), real(0.0f), real(0.0f));
  total = vec3(real(0.0f), real(0.0f), real(0.0f));
  transmittance = vec3(real(1.0f), real(1.0f), real(1.0f));
  real tPrevious = real(0.0f);
  for (uint i = 0u; i < steps; ++i) {
    real x = real(i + 1u) / real(steps);
    real t = tMax * stepShare(x, spacing);
    real dt = t - tPrevious;
    scatteringStep(a, h, mu, muS, nu, phaseR, phaseM, tPrevious + real(0.5f) * dt, dt, single, total, transmittance);
    tPrevious = t;
  }
}

// The stretch of a view ray inside the atmosphere, from altitude h along zenith cosine mu: x =
// where it starts (0 inside; outside, where it enters the top), y = where it ends (it leaves the
// top, or meets the ground sphere at altitude hGround ≤ h). y ≤ x when it misses the air.
vec2 atmosphereStretch(IN(AtmosphereParams) a, real h, real mu, real hGround) {
  real R = real(a.radii.x);
  vec2 air = stretchInsideSphere(R, h, mu, real(a.radii.y));
  real tStart = air.x;
  real tExit = air.y;
  if (tStart < real(0.0f) || tExit <= tStart) return vec2(real(0.0f), real(-1.0f));
  vec2 ground = raySphere(R, h, mu, min(hGround, h));
  real tEnd = (mu < real(0.0f) && ground.x >= real(0.0f)) ? min(ground.x, tExit) : tExit;
  return vec2(tStart, tEnd);
}

// The sky along a whole view ray from altitude h (inside or above the atmosphere) to where it
// leaves the air or meets the ground sphere at hGround (black: the ground itself is drawn by the
// terrain), in `steps` steps spaced as skyStepSpacing says (from outside, where the densest air is
// anywhere along the ray, equally).
void skyAlong(IN(AtmosphereParams) a, real h, real mu, real muS, real nu, real hGround, uint steps, OUT(vec3) single,
              OUT(vec3) total, OUT(vec3) transmittance) {
  single = vec3(real(0.0f), real(0.0f), real(0.0f));
  total = vec3(real(0.0f), real(0.0f), real(0.0f));
  transmittance = vec3(real(1.0f), real(1.0f), real(1.0f));
  vec2 stretch = atmosphereStretch(a, h, mu, hGround);
  if (a.radii.w < 0.5f || stretch.y <= stretch.x) return;
  real R = real(a.radii.x);
  real r = R + h;
  real h0 = altitudeAlong(R, h, mu, stretch.x);
  real mu0 = clamp((r * mu + stretch.x) / (R + h0), real(-1.0f), real(1.0f));
  real muS0 = clamp((r * muS + stretch.x * nu) / (R + h0), real(-1.0f), real(1.0f));
  uint spacing = skyStepSpacing(a, h, stretch.y < stretchInsideSphere(R, h, mu, real(a.radii.y)).y);
  scatteringAlong(a, h0, mu0, muS0, nu, stretch.y - stretch.x, steps, spacing, single, total, transmittance);
}

// The table's texel (u, v) in [0, 1] (texel centres at the ends of each range) for a viewpoint at
// altitude h over the ground sphere at hGround and a sun at zenith cosine muS: the total sky
// radiance along its direction, in kSkyViewSteps steps, and the transmittance along it.
vec3 skyViewTexelAndTransmittance(IN(AtmosphereParams) a, real h, real hGround, real muS, real u, real v,
                                  OUT(vec3) transmittance) {
  vec2 range = skyViewZenithRange(a, h, hGround);
  real theta = skyViewTheta(clamp(texelToUnit(v, real(kSkyViewHeight)), real(0.0f), real(1.0f)), range);
  real mu = cos(theta);
  real phi = kAtmospherePi * clamp(texelToUnit(u, real(kSkyViewWidth)), real(0.0f), real(1.0f));
  real sinV = sqrt(max(real(1.0f) - mu * mu, real(0.0f)));
  real sinS = sqrt(max(real(1.0f) - muS * muS, real(0.0f)));
  real nu = clamp(mu * muS + sinV * sinS * cos(phi), real(-1.0f), real(1.0f));
  vec3 single, total;
  skyAlong(a, h, mu, muS, nu, hGround, kSkyViewSteps, single, total, transmittance);
  return total;
}
vec3 skyViewTexel(IN(AtmosphereParams) a, real h, real hGround, real muS, real u, real v) {
  vec3 transmittance;
  return skyViewTexelAndTransmittance(a, h, hGround, muS, u, v, transmittance);
}
#endif

// Airglow (issue 21, point 4): the upper air's own faint light (oxygen's green line, OH, sodium),
// which is the larger part of the natural night sky's brightness away from the Milky Way. The
// shell between g.layer.x and .y (m above R) emits evenly through its depth, so a ray's
// light is the zenith radiance g.radiance.xyz times its path inside the shell over the shell's
// thickness: straight up it is the zenith radiance; toward the horizon the path grows (van
// Rhijn's effect: from the ground about 6 times at the horizon, and the air in front dims it
// there), and from space a ray grazing the shell crosses tens of thicknesses: the thin bright
// band photographs from orbit show along the night side's limb.
// The path inside the shell is that inside its top sphere less that inside its bottom one
// (stretchInsideSphere, overlap).

// The airglow along a ray from altitude h with zenith cosine mu up to distance tEnd (where it
// meets something drawn, or the ground): `nearLight`, the shell's light in front of the ray's
// lowest point seen from above the shell, which no air dims, and `farLight`, the rest, which
// the caller dims by the ray's transmittance through the air (the shell is above nearly all of
// it). Black without airglow.
void airglowAlong(IN(AirglowParams) g, real R, real h, real mu, real tEnd, OUT(vec3) nearLight, OUT(vec3) farLight) {
  nearLight = vec3(real(0.0f), real(0.0f), real(0.0f));
  farLight = nearLight;
  if (!(real(g.radiance.w) > real(0.5f))) return;
  real bottom = real(g.layer.x), top = real(g.layer.y);
  // From above the shell, the ray's stretch before its lowest point is in front of the air.
  real split = h > top ? min(max(-(R + h) * mu, real(0.0f)), tEnd) : real(0.0f);
  vec2 inTop = stretchInsideSphere(R, h, mu, top), inBottom = stretchInsideSphere(R, h, mu, bottom);
  real nearPath = overlap(inTop, real(0.0f), split) - overlap(inBottom, real(0.0f), split);
  real farPath = overlap(inTop, split, tEnd) - overlap(inBottom, split, tEnd);
  vec3 perMetre = vec3(real(g.radiance.x), real(g.radiance.y), real(g.radiance.z)) / (top - bottom);
  nearLight = perMetre * max(nearPath, real(0.0f));
  farLight = perMetre * max(farPath, real(0.0f));
}

#endif
