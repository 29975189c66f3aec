#version 450
// One point sprite per star, at infinity: the direction goes in with w = 0, so the reversed-Z
// projection gives it depth 0 (infinitely far) and the camera's position does not move it.
// Stars behind the camera get w < 0 and are clipped.
#extension GL_GOOGLE_include_directive : require

#include "shared/star_params.h"

layout(push_constant) uniform Push { StarDrawPush params; };

layout(std430, set = 0, binding = kStarBindingCatalogue) readonly buffer Catalogue { StarRecord stars[]; };

layout(location = 0) flat out vec3 outFlux;    // HDR flux of the star, per channel
layout(location = 1) flat out float outSize;   // the point's size in pixels
layout(location = 2) flat out float outSigma;  // of the star's Gaussian, in pixels; 0: one plain pixel
layout(location = 3) flat out float outRelativeFlux;  // 10^(−0.4 m): 1 at magnitude 0

#include "common/stars.glsl"

void main() {
  StarRecord star = stars[gl_VertexIndex];
  gl_Position = params.directionToClip * vec4(star.direction.xyz, 0.0f);
  float diameter = starSpriteDiameter(star.direction.w) * params.pixelScale;
  float size = min(diameter + kStarSpriteMargin, params.maxPointSize);
  // Without large points (size 1) the star's whole flux goes into its pixel.
  bool plain = size < 1.0f + kStarSpriteMargin;
  outSigma = plain ? 0.0f : kStarSpriteSigma * (size - kStarSpriteMargin);
  gl_PointSize = plain ? 1.0f : size;
  outSize = gl_PointSize;
  outFlux = star.color.rgb * params.brightness;
  outRelativeFlux = exp2(-1.32877124f * star.direction.w);  // 10^(−0.4 m) = 2^(−0.4 log2(10) m)
}
