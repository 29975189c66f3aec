#version 450
// Sorts the cloud pass's tiles (8 × 8 samples, a workgroup of sky_clouds.comp each) into those
// whose rays may meet the cloud layer and those whose every ray ends before it can (issue 21,
// point 7): on lavapipe every sample pays for the layer's march, met or not, and from below the
// layer most of the ground's samples cannot meet it. Each list is run by a pipeline of its own
// (sky_clouds.comp's kSpecCloudTileClass), by an indirect dispatch.
//
// From below the layer's base a ray stays inside the ball under the base until it leaves it, so
// one that ends at geometry before that exit distance never enters the layer, mountains or not
// (sky_compose.glsl, layerIntervals: its one stretch starts at the exit). For the tile's samples:
// - the end: a sample's ray ends at its block's depth (the mean of its pixels' depths or the
//   nearest of them, sky_clouds.comp), never farther than the tile's farthest pixel. That is the
//   least depth of the compose tiles under the samples' pixels (sky_classify.comp keeps it;
//   0 where a pixel shows no geometry). Along a direction at cosine c to the view axis, depth d
//   lies at distance near / (d c), so the farthest end is near / (d_min c_min);
// - the exit distance falls as the ray turns upward, so the nearest is that of the tile's most
//   upward ray, which tileRays bounds (sky_tile_classes.glsl).
// The tile takes no march when the farthest end lies before the nearest exit, with a margin for
// rounding (kDistanceMargin). The CPU allows the class (push.classes) only when the camera is
// below the layer and both passes' regions start at the image's corner, so the compose tiles
// under a cloud tile are those of its pixels' rectangle.
//
// With the same bound it lists the compose's ground tiles under each cloud tile as clear of the
// clouds or not (kSkyTileAerialClear, kSkyTileAerial; sky_classify.comp leaves them here): a
// clear tile's pipeline reads no cloud light and no path through the layer, only the shadow.
// Either may also be near (composeTileNear, from the tile's own rays: kSkyTileNear).
// A clear cloud tile whose samples only clear compose tiles read (which take the clouds' shadow
// from the shadow table instead: sky_cloud_shadow.comp) is listed nowhere, and not run: from a
// few metres up about half of the cloud pass's tiles (onlyClearTilesRead).
#extension GL_GOOGLE_include_directive : require

#include "sky_compose.glsl"

#include "sky_tile_classes.glsl"

// The least depth (reversed Z: the farthest surface) of compose tiles `from` to `to` (inclusive),
// 0 where a pixel of them shows no geometry (sky_classify.comp).
float farthestDepthOf(uvec2 from, uvec2 to) {
  float farthest = 1.0f;
  for (uint y = from.y; y <= to.y; ++y)
    for (uint x = from.x; x <= to.x; ++x)
      farthest = min(farthest, uintBitsToFloat(skyTiles.tiles[farthestDepthSlot(uvec2(x, y), push.tiles.x)]));
  return farthest;
}

// Whether no view ray through the screen rectangle [lo, hi] (pixels) that ends at a depth of at
// least `farthest` (reversed Z) can reach the layer (see the top of the file).
bool raysEndBeforeLayer(vec2 lo, vec2 hi, float farthest) {
  float R = sky.atmosphere.radii.x;
  float h = sky.camera.x;
  float bottom = sky.clouds.x;
  if (h >= bottom || farthest <= 0.0f) return false;
  TileRays rays = tileRays(lo, hi);
  float nearestExit = raySphere(R, h, rays.muHighest, bottom).x;  // from inside: the way out
  return tileFarthestEnd(rays, farthest) < kDistanceMargin * nearestExit;
}

// Whether every compose tile that reads a sample of cloud tile `tile` is listed as clear of the
// clouds below (a sufficient test). The compose's pixel p reads the samples floor((p + 1/2) / scale
// − 1/2) and the next, so this tile's samples are read by pixels within `scale` of its own:
// compose tiles `first` to `final`. Each of those is clear when its neighbourhood's rays (it and the
// tiles around it) end before the layer, all of its pixels show ground, and, where the depth may
// hold surfaces past the air, its rays end inside the air. The bounds of both tests grow with the
// rectangle and with the depth's range, so one test over all the neighbourhoods together (and
// one over the tiles together) implies each tile's.
bool onlyClearTilesRead(uvec2 tile, uint scale) {
  if ((push.classes & (1u << kSkyTileAerialClear)) == 0u) return false;
  ivec2 firstPixel = ivec2(tile * kSkyWorkgroupSize * scale) - int(scale);
  ivec2 lastPixel = ivec2((tile + 1u) * kSkyWorkgroupSize * scale) + int(scale) - 1;
  uvec2 last = push.tiles - 1u;
  uvec2 first = uvec2(max(firstPixel / int(kSkyWorkgroupSize), 0));
  uvec2 final = min(uvec2(lastPixel) / kSkyWorkgroupSize, last);
  uvec2 near = max(first, 1u) - 1u, far = min(final + 1u, last);
  float farthest = farthestDepthOf(near, far);
  if (!(farthest > 0.0f)) return false;
  if (push.checkAirExit != 0u) {
    vec2 lo = vec2(first * kSkyWorkgroupSize);
    vec2 hi = min(vec2((final + 1u) * kSkyWorkgroupSize), sky.extent.xy);
    if (!composeTileInsideAir(tileRays(lo + 0.5f, hi - 0.5f), farthestDepthOf(first, final))) return false;
  }
  vec2 lo = vec2(near * kSkyWorkgroupSize);
  vec2 hi = min(vec2((far + 1u) * kSkyWorkgroupSize), sky.extent.xy);
  return raysEndBeforeLayer(lo, hi, farthest);
}

void main() {
  uvec2 tile = gl_GlobalInvocationID.xy;
  if (tile.x >= push.cloudTiles.x || tile.y >= push.cloudTiles.y) return;
  // The pixels the tile's samples read, and the compose tiles that hold them.
  uint scale = uint(sky.cloudShape.w);
  uvec2 last = uvec2(sky.extent.xy) - 1u;
  uvec2 firstPixel = tile * kSkyWorkgroupSize * scale;
  bool inside = all(lessThanEqual(firstPixel, last));
  uvec2 lastPixel = min(firstPixel + kSkyWorkgroupSize * scale - 1u, last);
  uvec2 from = firstPixel / kSkyWorkgroupSize, to = lastPixel / kSkyWorkgroupSize;
  bool clear = false;
  if ((push.classes & (1u << kSkyCloudTileClear)) != 0u && inside) {
    // The samples' centres span this rectangle of the screen.
    vec2 lo = (vec2(tile * kSkyWorkgroupSize) + 0.5f) * float(scale);
    vec2 hi = lo + float((kSkyWorkgroupSize - 1u) * scale);
    clear = raysEndBeforeLayer(lo, hi, farthestDepthOf(from, to));
  }
  // A clear tile whose samples no compose tile but those clear of the clouds reads is not run at
  // all: those take their shadow from the clouds' shadow table and read no sample.
  if (!(clear && onlyClearTilesRead(tile, scale))) appendTile(clear ? kSkyCloudTileClear : kSkyCloudTileMarch, tile);
  // The ground's compose tiles under this one (sky_classify.comp left them to this pass): clear
  // when every ray of their pixels and of the cloud samples they read ends before the layer. A
  // pixel reads the four samples around its centre, whose blocks of pixels lie within 1.5 samples
  // (3 pixels at half resolution) of it, so within the tile's neighbours: their rectangle and
  // their depths bound those rays.
  if ((push.classes & (1u << kSkyTileAerialClear)) == 0u || !inside) return;
  to = min(to, push.tiles - 1u);
  for (uint y = from.y; y <= to.y; ++y) {
    for (uint x = from.x; x <= to.x; ++x) {
      uvec2 composeTile = uvec2(x, y);
      float farthest = farthestDepthOf(composeTile, composeTile);
      if (!(farthest > 0.0f)) continue;
      // (A tile whose rays may leave the air is mixed: sky_classify.comp lists it.)
      TileRays rays = composeTileRays(composeTile);
      if (push.checkAirExit != 0u && !composeTileInsideAir(rays, farthest)) continue;
      uvec2 near = max(composeTile, 1u) - 1u, far = min(composeTile + 1u, push.tiles - 1u);
      vec2 lo = vec2(near * kSkyWorkgroupSize);
      vec2 hi = min(vec2((far + 1u) * kSkyWorkgroupSize), sky.extent.xy);
      bool clearTile = raysEndBeforeLayer(lo, hi, farthestDepthOf(near, far));
      uint composeClass = clearTile ? kSkyTileAerialClear : kSkyTileAerial;
      // (Whether the tile's own rays end short of the ground sphere: sky_tile_classes.glsl.)
      if ((push.classes & (1u << kSkyTileAerialNear)) != 0u &&
          composeTileNear(rays, farthest))
        composeClass += kSkyTileNear;
      appendTile(composeClass, composeTile);
    }
  }
}
