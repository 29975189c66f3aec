// The sky passes' per-frame values (SkyUniforms), read as `sky` by the compose and cloud passes
// (sky_compose.glsl) and the table builds (sky_view.comp, aerial_perspective.comp); binding 0 of
// each pass's set (kSkyBindingUniforms, kSkyTableBindingUniforms). The includer includes
// shared/sky_params.h first.
//
// A uniform buffer, reached through an array of one indexed by gl_WorkGroupID.z (0: every sky
// dispatch is two-dimensional), for lavapipe (Mesa 22.3), where both plainer forms are slow:
// - A storage buffer is read lane by lane, 8 bounds-checked scalar loads per component, wherever
//   the read is inside control flow (all of these shaders' reads: their first statement returns
//   early past the image's edge). That made over half of the compose pass (46 → 16 ms at 640×360)
//   and two thirds of the cloud pass (18 → 6 ms), measured on a static view 50 m above the ground.
// - From a uniform buffer at a constant block index, lavapipe compiles the values that steer
//   branches and loops into the shader, a new variant whenever they change: every frame of a
//   flight (+1 MB of process memory per frame, ~400 ms per recompile with the shader cache off).
// A block index that is not a compile-time constant keeps the values out of the shader, and the
// loads stay single scalar loads (the offsets are constant). The device must support
// shaderUniformBufferArrayDynamicIndexing (vk::Context requires it).
#ifndef PLANET_SKY_UNIFORMS_GLSL
#define PLANET_SKY_UNIFORMS_GLSL

layout(std140, set = 0, binding = kSkyBindingUniforms) uniform Uniforms { SkyUniforms values; } skyUniforms[1];
#define sky skyUniforms[gl_WorkGroupID.z].values

#endif
