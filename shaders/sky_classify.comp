#version 450
// Sorts the tiles of the tables' compose (issue 21, point 7) by what their pixels need, before
// it runs: on lavapipe every pixel pays for both sides of the compose's branch between the
// sky-view table (a ray that met no geometry) and the aerial-perspective volume (one that did),
// and from a plane or the ground most tiles are all sky or all ground. Each class is composed by
// a pipeline of its own (sky.comp's kSpecTileClass) from the lists this pass writes
// (kSkyBindingTiles), by an indirect dispatch. The class is read from the depth alone (a
// per-pixel ray here cost as much as the compose saved):
// - sky: no pixel of the tile shows geometry (depth 0), so every one takes the sky-view table;
// - aerial: every pixel shows geometry and the frame's depth holds only this body's surfaces
//   (SkyView::ownSurfacesOnly): those lie below the top of its air, so no ray meets them past
//   the air's far side, and every pixel takes the aerial-perspective volume. Another body, a
//   ring, or terrain whose bound reaches above the top may lie past the air and take the
//   sky-view table: with those in the frame such a tile is aerial only when, from inside the
//   air, its rays are shown to end before they leave it (push.checkAirExit:
//   composeTileInsideAir in sky_tile_classes.glsl), else mixed. Those whose rays all end well
//   short of the ground sphere are listed apart (kSkyTileAerialNear: composeTileNear in
//   sky_tile_classes.glsl), for a pipeline without the code that serves the others;
// - mixed: the rest, composed by the pipeline with both sides.
// From below the cloud layer (the classes' kSkyTileAerialClear bit), the aerial tiles are left
// to sky_cloud_classify.comp, which lists each as aerial or as clear of the clouds from its
// neighbours' farthest depths, written here.
// One invocation per tile of the compose's region (sky.region; the compose's workgroup size),
// reading its pixels' depths in a loop: shared memory and barriers cost lavapipe more. It also
// keeps each tile's farthest depth, from which sky_cloud_classify.comp sorts the cloud pass's
// tiles without reading the depth again.
#extension GL_GOOGLE_include_directive : require

#include "sky_compose.glsl"

#include "sky_tile_classes.glsl"

void main() {
  uvec2 tile = gl_GlobalInvocationID.xy;
  if (tile.x >= push.tiles.x || tile.y >= push.tiles.y) return;
  ivec2 corner = ivec2(sky.region.xy) + ivec2(tile * kSkyWorkgroupSize);
  // The tile's pixels inside the image (the compose leaves those past its edge).
  ivec2 end = min(corner + int(kSkyWorkgroupSize), ivec2(sky.extent.xy));
  bool anySky = false, anyGeometry = false;
  float farthest = 1.0f;  // reversed Z: the least depth
  // Two by two pixels a read (depthTexels, a quarter of the reads one by one cost); a pair past
  // the image's last column or row reads that one again (the sampler clamps to the edge).
  for (int y = corner.y; y < end.y; y += 2) {
    for (int x = corner.x; x < end.x; x += 2) {
      vec4 depth = depthTexels(ivec2(x, y));
      bvec4 geometry = greaterThan(depth, vec4(0.0f));
      anySky = anySky || !all(geometry);
      anyGeometry = anyGeometry || any(geometry);
      farthest = min(farthest, min(min(depth.x, depth.y), min(depth.z, depth.w)));
    }
  }
  // For the cloud pass's tiles (sky_cloud_classify.comp).
  skyTiles.tiles[farthestDepthSlot(tile, push.tiles.x)] = floatBitsToUint(anySky ? 0.0f : farthest);
  uint tileClass = !anyGeometry ? kSkyTileSky : (!anySky ? kSkyTileAerial : kSkyTileMixed);
  if ((push.classes & (1u << tileClass)) == 0u) tileClass = kSkyTileMixed;
  // (The tile's rays' bounds once, for both checks below.)
  TileRays rays = composeTileRays(tile);
  if (tileClass == kSkyTileAerial && push.checkAirExit != 0u && !composeTileInsideAir(rays, farthest))
    tileClass = kSkyTileMixed;
  // Aerial tiles that may be clear of the cloud layer are listed by sky_cloud_classify.comp,
  // which needs their neighbours' depths.
  if (tileClass == kSkyTileAerial && (push.classes & (1u << kSkyTileAerialClear)) != 0u) return;
  if (tileClass == kSkyTileAerial && (push.classes & (1u << kSkyTileAerialNear)) != 0u &&
      composeTileNear(rays, farthest))
    tileClass = kSkyTileAerialNear;
  appendTile(tileClass, tile);
}
