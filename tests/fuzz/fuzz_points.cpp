// libFuzzer target: the "x y z" point reader (noise/point_reader.h), as a whole stream and as
// a single line (newlines then are ordinary bytes inside a token).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "fuzz_check.h"
#include "noise/point_reader.h"

namespace {

void checkFinite(const glm::vec3& p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    planet::fuzz::finding("a point with a non-finite coordinate was accepted");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace planet;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    std::istringstream in(text);
    for (const glm::vec3& p : noise::readPoints(in)) checkFinite(p);
  } catch (const Error& e) {
    fuzz::checkErrorMessage(e.what(), "line ");
  }
  try {
    glm::vec3 p(0.0f);
    if (noise::parsePointLine(text, 7, p)) checkFinite(p);
  } catch (const Error& e) {
    fuzz::checkErrorMessage(e.what(), "line 7: ");
  }
  return 0;
}
