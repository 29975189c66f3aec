// libFuzzer target: the TOML preset parser (planet/planet_description.h) and the round trip
// through the preset writer (planet/preset_writer.h) that the viewer's "save preset" relies on.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"
#include "fuzz_check.h"
#include "planet/planet_description.h"
#include "planet/preset_writer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace planet;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  PlanetDescription parsed;
  try {
    parsed = parsePlanetDescription(text, "fuzz.toml");
  } catch (const Error& e) {
    fuzz::checkErrorMessage(e.what(), "fuzz.toml");  // a rejection with a message is the parser's job
    return 0;
  }

  // preset_writer.h: every description the parser produces is written as a preset that reads
  // back to the same canonical form, hence the same descriptionHash.
  const std::string saved = formatPlanetDescription(parsed);
  PlanetDescription reread;
  try {
    reread = parsePlanetDescription(saved, "saved.toml");
  } catch (const Error& e) {
    fuzz::finding("a saved preset does not parse back", std::string(e.what()) + "\n--- saved preset:\n" + saved);
  }
  if (descriptionHash(reread) != descriptionHash(parsed))
    fuzz::finding("a saved preset reads back to a different description",
                  "--- parsed:\n" + canonicalForm(parsed) + "--- read back:\n" + canonicalForm(reread) +
                      "--- saved preset:\n" + saved);
  return 0;
}
