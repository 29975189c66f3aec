// The built-in presets: the TOML files of engine/planet/presets, embedded by the build as
// string literals in the generated header presets/embedded_presets.h, so the executable
// never looks for them on disk.
#include <array>
#include <iterator>

#include "planet/planet_description.h"
#include "presets/embedded_presets.h"

namespace planet {
namespace {

// The generated header stays free of engine types; this copies its pointers once, at
// compile time, into the public struct.
constexpr auto kPresets = [] {
  std::array<EmbeddedPreset, std::size(presets::kEmbedded)> out{};
  for (size_t i = 0; i < out.size(); ++i) out[i] = {presets::kEmbedded[i].name, presets::kEmbedded[i].text};
  return out;
}();

}  // namespace

std::span<const EmbeddedPreset> embeddedPresets() { return kPresets; }

}  // namespace planet
