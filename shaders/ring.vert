#version 450
// The ring's annulus (engine/render/ring_pass.h), built from gl_VertexIndex: kRingSegments
// quads, each two triangles from the inner polygon to the outer one. Inner vertices lie on the
// inner circle, so its chords pass inside it; outer ones on the circle of radius outer / cos(π/N),
// whose chords touch the outer circle. The polygon only covers the disc: ring.frag finds each
// pixel's exact radius and leaves what lies outside the annulus transparent, so the edges are
// round however close the camera is.
//
// Positions are relative to the camera (the body-frame vertex minus the camera position). Every
// vertex has the same z, −camera.z, so the plane stays exactly flat; the few metres by which float
// rounding moves a vertex 10^8 m away neither show nor matter (the fragment shader does not use them).
#extension GL_GOOGLE_include_directive : require

#include "shared/ring_params.h"

layout(set = 0, binding = kRingBindingUniforms) uniform Uniforms { RingUniforms frame; };

void main() {
  uint segment = uint(gl_VertexIndex) / 6u;
  uint corner = uint(gl_VertexIndex) % 6u;
  // Corners 0..5: (k, in), (k, out), (k+1, out), (k, in), (k+1, out), (k+1, in): both triangles
  // wind the same way, and no culling is done anyway (the ring is seen from both sides).
  uint next = (corner == 2u || corner == 4u || corner == 5u) ? 1u : 0u;
  bool outer = corner == 1u || corner == 2u || corner == 4u;
  float angle = 6.28318531f * float((segment + next) % kRingSegments) / float(kRingSegments);
  float radius = outer ? frame.ring.radii.y / cos(3.14159265f / float(kRingSegments)) : frame.ring.radii.x;
  vec3 relative = vec3(radius * cos(angle) - frame.camera.x, radius * sin(angle) - frame.camera.y, -frame.camera.z);
  gl_Position = frame.relativeToClip * vec4(relative, 1.0f);
}
