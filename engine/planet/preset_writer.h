// Planet descriptions written back as TOML presets ("save preset" in the viewer): the text
// parsePlanetDescription reads, laid out like engine/planet/presets/*.toml.
//
// Round trip: for every description the parser can produce,
//   canonicalForm(parsePlanetDescription(formatPlanetDescription(p), ...)) == canonicalForm(p),
// so descriptionHash is kept too. Every key is written, optional ones included, with offset and
// gain resolved to the values used. Numbers are in shortest round-trip form; a colour is the
// shortest text whose double rounds to the same float; a layer's scale is written as
// wavelength_m when one reads back to exactly the same frequency, else as frequency.
//
// What the schema has no place for is left out and reads back at its default. None of it is
// drawn: the parameters of a disabled atmosphere or cloud layer, [clouds] without an
// [atmosphere] (the sky pass draws no clouds without air), sea_level_m and [water] without
// an ocean, and the parameters of [lights] with enabled = false.
#pragma once

#include <string>

#include "planet/planet_description.h"

namespace planet {

// The TOML preset text of `planet`; deterministic (same description, same bytes).
std::string formatPlanetDescription(const PlanetDescription& planet);

// Writes formatPlanetDescription(planet) to `path` whole or not at all (core/file.h: a
// temporary name in the same folder, then a rename). The text is parsed back first, so a
// description the parser would reject (a value out of range, clouds above the atmosphere, ...)
// is never saved. Throws planet::Error naming `path` on any failure.
void savePlanetDescription(const PlanetDescription& planet, const std::string& path);

}  // namespace planet
