// The GLSL half of the contract between GLSL and C++ for the shared files of this folder
// (noise.glsl, hash.glsl, terrain_height.glsl, terrain_surface.glsl, atmosphere.glsl,
// rings.glsl, stars.glsl), in the spirit of Bruneton's definitions.glsl / definitions.h pair.
// The C++ half is definitions.h beside it: the same names, each declared once per language.
//
// The common subset (STYLE.md): `real` for every floating-point value, .x/.y/.z instead of
// swizzles, an `f` suffix on every literal, explicit conversions, unsigned integer hashing
// only, IN()/OUT()/INOUT() for parameters passed by reference, PRECISE on intermediates whose
// rounding both sides must share, SHARED_CONST for constants.
#ifndef PLANET_COMMON_DEFINITIONS_GLSL
#define PLANET_COMMON_DEFINITIONS_GLSL

#ifndef __cplusplus
#define real float
#define IN(T) in T
#define OUT(T) out T
#define INOUT(T) inout T
#define SHARED_CONST const
// No multiply-add contraction or reassociation of these values (SPIR-V NoContraction): the
// C++ side is compiled with -ffp-contract=off and both must round identically.
#define PRECISE precise
#endif

#endif
