// What the two tile classifiers (sky_classify.comp, sky_cloud_classify.comp) share: their push
// constant (SkyPass::recordCompose's ClassifyPush) and the bounds they sort tiles by. The
// includer includes sky_compose.glsl first.
#ifndef PLANET_SKY_TILE_CLASSES_GLSL
#define PLANET_SKY_TILE_CLASSES_GLSL

layout(push_constant) uniform ClassifyPush {
  uvec2 tiles;       // the compose region's tiles in x and y
  uvec2 cloudTiles;  // the cloud region's tiles (8 × 8 samples) in x and y
  uint classes;      // bit c set: tiles may be of class c, else they are mixed (or marched)
  // 1: the frame's depth may hold surfaces past the far side of the air (another body, a ring,
  // terrain above the top: SkyView::ownSurfacesOnly is false), and the camera is inside the air;
  // a tile of ground is of the ground's classes only where composeTileInsideAir shows that none
  // of its pixels is.
  uint checkAirExit;
}
push;

// Bounds on the view rays through a rectangle [lo, hi] of the screen (pixels): the zenith
// cosines of the highest and the lowest direction, and the least cosine to the view axis. No
// direction of the rectangle is farther from its centre than one of its corners (the
// rectangle's directions are a convex spherical polygon), so none is nearer the zenith than the
// centre's zenith angle less that angle, nor farther from it than the centre's plus that angle
// (a little wider, for rounding); the angle to the view axis is greatest at a corner.
struct TileRays {
  float muHighest;
  float muLowest;
  float cosForward;
};

TileRays tileRays(vec2 lo, vec2 hi) {
  vec3 centre = viewDirection(0.5f * (lo + hi));
  float cosRadius = 1.0f;
  TileRays rays;
  rays.cosForward = 1.0f;
  for (int k = 0; k < 4; ++k) {
    vec3 corner = viewDirection(vec2((k & 1) == 0 ? lo.x : hi.x, (k & 2) == 0 ? lo.y : hi.y));
    cosRadius = min(cosRadius, dot(corner, centre));
    rays.cosForward = min(rays.cosForward, dot(corner, sky.forward.xyz));
  }
  // cos(max(θ − ρ, 0)) and cos(min(θ + ρ, π)) for the centre's zenith angle θ and the radius ρ.
  float muCentre = centre.z;
  float sinCentre = sqrt(max(1.0f - muCentre * muCentre, 0.0f));
  float sinRadius = sqrt(max(1.0f - cosRadius * cosRadius, 0.0f));
  float highest = muCentre >= cosRadius ? 1.0f : muCentre * cosRadius + sinCentre * sinRadius;
  float lowest = -muCentre >= cosRadius ? -1.0f : muCentre * cosRadius - sinCentre * sinRadius;
  rays.muHighest = min(highest + 1e-4f, 1.0f);
  rays.muLowest = max(lowest - 1e-4f, -1.0f);
  return rays;
}

// The farthest any of the rays runs to a drawn surface at a depth (reversed Z) of at least
// `farthest`: a ray at cosine c to the view axis meets depth d at near / (d c).
float tileFarthestEnd(TileRays rays, float farthest) {
  return sky.camera.y / farthest / max(rays.cosForward, 1e-6f);
}

// The view rays through the pixel centres (viewRay's screen points) of compose tile `tile`.
TileRays composeTileRays(uvec2 tile) {
  vec2 corner = sky.region.xy + vec2(tile * kSkyWorkgroupSize);
  vec2 end = min(corner + float(kSkyWorkgroupSize), sky.extent.xy);
  return tileRays(corner + 0.5f, end - 0.5f);
}

// How close to a bound the tiles' own rounding may bring a pixel's value: the distances to the
// ground sphere (a share of it) and out of the air.
const float kDistanceMargin = 0.99f;

// Whether every pixel of a compose tile whose rays are bounded by `rays` (composeTileRays), all
// of whose pixels show geometry no farther than depth `farthest` (reversed Z), takes its light
// from the aerial volume alone (kSkyTileNear; sky_compose.glsl, aerialPerspective, leaves the
// sky-view table's light out for such tiles). From inside the air that holds when every ray ends
// short of kSkyViewGroundShareFrom of its distance to the ground sphere (where the sky-view
// table's light starts), or misses that sphere: that distance grows as a ray turns up, so the
// least is the lowest direction's.
bool composeTileNear(TileRays rays, float farthest) {
  float R = sky.atmosphere.radii.x;
  float h = sky.camera.x;
  float hGround = sky.surface.z;  // as viewRay's
  if (aerialFromAbove() || !(farthest > 0.0f) || !(h > hGround)) return false;
  vec2 ground = raySphere(R, h, rays.muLowest, hGround);
  return !(ground.x >= 0.0f) ||
         tileFarthestEnd(rays, farthest) < kDistanceMargin * kSkyViewGroundShareFrom * ground.x;
}

// Whether every ray of a compose tile whose rays are bounded by `rays` (composeTileRays), all of
// whose pixels show geometry no farther than depth `farthest` (reversed Z), ends before it leaves
// the air, seen from inside it: then none shows a surface past the air's far side, which the
// compose sees through the whole crossing from the sky-view table (sky.comp, pastAir), and the
// ground's classes compose the tile as the mixed pipeline does. From inside, the way out of the
// top comes soonest on the highest ray.
bool composeTileInsideAir(TileRays rays, float farthest) {
  if (aerialFromAbove() || !(farthest > 0.0f)) return false;
  float exit = raySphere(sky.atmosphere.radii.x, sky.camera.x, rays.muHighest, sky.atmosphere.radii.y).x;
  return tileFarthestEnd(rays, farthest) < kDistanceMargin * exit;
}

#endif
