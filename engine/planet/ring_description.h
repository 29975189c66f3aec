// A planetary ring as a scene describes it (issue 8, point 3; seed 001 §4.5): the annulus in the
// ringed body's equatorial plane, the seed and colours of its noise, checked strictly, read
// from a TOML table, and turned into the block the shaders read by reference/ring_density.h's ringGpuParams.
#pragma once

#include <cstdint>
#include <string_view>

#include <glm/glm.hpp>
// toml++'s own forward declarations (toml::table): the full header stays out of includers.
#include <toml++/impl/forward_declarations.h>

#include "shared/ring_params.h"

namespace planet {

// Defaults: Saturn's main rings (C ring inner edge to A ring outer edge) in pale tan.
struct RingDescription {
  double innerRadiusM = 7.45e7;   // from the body's centre; > 0
  double outerRadiusM = 1.368e8;  // > innerRadiusM
  uint32_t seed = 1;
  glm::dvec3 colour{0.62, 0.53, 0.40};           // linear albedo of the particles, each in [0, 1]
  glm::dvec3 colourVariation{0.40, 0.36, 0.32};  // second albedo, mixed in by a second noise, each in [0, 1]
  double opacity = 1.0;                          // overall scale of the noise opacity, [0, 1]
  uint32_t octaves = 10;                         // of the opacity noise (seed 001: 10), 1 .. gpu::kRingMaxOctaves
  uint32_t gaps = 2;                             // Cassini-like divisions at seeded radii, 0 .. gpu::kRingMaxGaps
};

// Throws planet::Error with one line naming the bad field (by its TOML key) and value: a radius
// that is not finite and positive, an inner radius not below the outer one, a colour component
// or the opacity outside [0, 1] or not finite, octaves outside 1..16, gaps outside 0..4.
void validateRingDescription(const RingDescription& ring);

// Reads a ring table such as a scene's [bodies.rings] (keys: inner_radius_m, outer_radius_m,
// seed, colour = [r, g, b], colour_variation = [r, g, b], opacity, octaves, gaps; all optional,
// defaults above), then validates it. Messages start with `where` (the source's name) and the
// line of the value at fault (the table's when it has no line, e.g. built in code), as planet
// presets' do: "scene.toml:12: unknown key 'colour_x' in the ring table", "scene.toml:14:
// 'opacity' must be a number, got string", "scene.toml:9: ring inner_radius_m (2e+08) must be
// below outer_radius_m (1.4e+08)". Unknown keys and wrong types are errors.
RingDescription parseRingTable(const toml::table& table, std::string_view where);

}  // namespace planet
