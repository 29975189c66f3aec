// libFuzzer target: the TOML scene parser (planet/scene_description.h), its ring tables and the
// orbits it resolves: every input is either rejected with a one-line message naming the file or
// gives bodies whose positions are finite at any time.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"
#include "fuzz_check.h"
#include "planet/scene_description.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace planet;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  SceneDescription scene;
  try {
    scene = parseSceneDescription(text, "fuzz.toml");
  } catch (const Error& e) {
    fuzz::checkErrorMessage(e.what(), "fuzz.toml");
    return 0;
  }
  for (double t : {0.0, 1.0e3, -5.0e8, 1.0e9}) {
    const std::vector<BodyState> states = sceneStateAt(scene, t);
    for (size_t i = 0; i < states.size(); ++i) {
      const glm::dvec3& p = states[i].positionM;
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        fuzz::finding("a parsed scene puts a body at a non-finite position",
                      "body " + scene.bodies[i].name + " at t = " + std::to_string(t));
    }
  }
  return 0;
}
