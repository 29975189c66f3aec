// The push constant of the two tile classifiers (sky_classify.comp, sky_cloud_classify.comp;
// SkyPass::recordCompose's ClassifyPush).
#ifndef PLANET_SKY_CLASSIFY_PUSH_GLSL
#define PLANET_SKY_CLASSIFY_PUSH_GLSL

layout(push_constant) uniform ClassifyPush {
  uvec2 tiles;       // the compose region's tiles in x and y
  uvec2 cloudTiles;  // the cloud region's tiles (8 × 8 samples) in x and y
  uint classes;      // bit c set: tiles may be of class c, else they are mixed (or marched)
}
push;

#endif
