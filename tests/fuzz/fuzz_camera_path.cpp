// libFuzzer target: the camera path reader (camera/camera_path.h), the round trip through
// formatCameraPath, and sampling of whatever path it accepts (the benchmark flies it frame by
// frame, so an accepted path must give finite poses everywhere).
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "core/error.h"
#include "fuzz_check.h"
#include "camera/camera_path.h"

namespace {

using planet::CameraKey;

// Bit for bit: formatCameraPath promises the same keys back, and -0 is not 0 here.
bool sameKey(const CameraKey& a, const CameraKey& b) {
  auto same = [](double x, double y) { return std::bit_cast<uint64_t>(x) == std::bit_cast<uint64_t>(y); };
  return same(a.timeS, b.timeS) && same(a.latitudeDeg, b.latitudeDeg) && same(a.longitudeDeg, b.longitudeDeg) &&
         same(a.heightM, b.heightM) && same(a.headingDeg, b.headingDeg) && same(a.pitchDeg, b.pitchDeg);
}

std::string describe(const CameraKey& k) {
  return fmt::format("{} {} {} {} {} {}", k.timeS, k.latitudeDeg, k.longitudeDeg, k.heightM, k.headingDeg, k.pitchDeg);
}

bool finite(const CameraKey& k) {
  return std::isfinite(k.latitudeDeg) && std::isfinite(k.longitudeDeg) && std::isfinite(k.heightM) &&
         std::isfinite(k.headingDeg) && std::isfinite(k.pitchDeg);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace planet;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  CameraPath path;
  try {
    path = parseCameraPath(text, "fuzz.path");
  } catch (const Error& e) {
    fuzz::checkErrorMessage(e.what(), "fuzz.path:");
    return 0;
  }

  try {
    validateCameraPath(path, "fuzz.path");
  } catch (const Error& e) {
    fuzz::finding("a parsed path fails validateCameraPath", e.what());
  }

  const std::string saved = formatCameraPath(path);
  CameraPath reread;
  try {
    reread = parseCameraPath(saved, "saved.path");
  } catch (const Error& e) {
    fuzz::finding("a formatted path does not parse back", std::string(e.what()) + "\n--- formatted:\n" + saved);
  }
  if (reread.keys.size() != path.keys.size())
    fuzz::finding("a formatted path reads back with a different number of keys", saved);
  for (size_t i = 0; i < path.keys.size(); ++i)
    if (!sameKey(path.keys[i], reread.keys[i]))
      fuzz::finding("a formatted path reads back to a different key",
                    fmt::format("key {}: {} became {}", i + 1, describe(path.keys[i]), describe(reread.keys[i])));

  // Each key's time, each segment's middle (halves added: the difference may overflow) and the
  // benchmark's frame times.
  auto sample = [&](double timeS) {
    const CameraKey key = sampleCameraPath(path, timeS);
    if (!finite(key))
      fuzz::finding("sampling an accepted path gives a non-finite pose", fmt::format("t={}: {}", timeS, describe(key)));
  };
  for (size_t i = 0; i < path.keys.size(); ++i) {
    sample(path.keys[i].timeS);
    if (i > 0) sample(path.keys[i - 1].timeS / 2 + path.keys[i].timeS / 2);
  }
  constexpr uint32_t kFrames = 7;
  for (uint32_t frame = 0; frame < kFrames; ++frame) sample(frameTimeS(path, frame, kFrames));
  return 0;
}
