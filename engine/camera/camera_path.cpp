#include "camera/camera_path.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "core/file.h"
#include "planet/terrain_height.h"

namespace planet {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr size_t kMaxPathBytes = size_t(4) << 20;
constexpr double kMaxKeyAngleDeg = 179.0;  // beyond, the great circle between two keys is ill-defined
constexpr const char* kColumns = "time_s lat_deg lon_deg height_m heading_deg pitch_deg";
constexpr std::string_view kUtf8ByteOrderMark = "\xef\xbb\xbf";

// A field as it can be quoted in a one-line message: printable ASCII (anything else, a NUL
// or a byte of some other encoding, as '?'), at most 40 characters.
std::string quotable(std::string_view field) {
  std::string out;
  for (char c : field.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (field.size() > 40) out += "...";
  return out;
}

// Angle between the directions of two keys, in degrees (atan2 form: accurate near 0 and 180).
double keyAngleDeg(const CameraKey& a, const CameraKey& b) {
  const glm::dvec3 p = directionFromLatLon(a.latitudeDeg, a.longitudeDeg);
  const glm::dvec3 q = directionFromLatLon(b.latitudeDeg, b.longitudeDeg);
  return std::atan2(glm::length(glm::cross(p, q)), glm::dot(p, q)) / kDegree;
}

// The first rule `key` breaks on its own (ranges), or "".
std::string keyRangeError(const CameraKey& k) {
  struct Field {
    const char* name;
    double value, min, max;
  } fields[] = {{"lat_deg", k.latitudeDeg, -90.0, 90.0},
                {"lon_deg", k.longitudeDeg, -360.0, 360.0},
                {"height_m", k.heightM, kPathMinHeightM, kPathMaxHeightM},
                {"heading_deg", k.headingDeg, -360.0, 360.0},
                {"pitch_deg", k.pitchDeg, -90.0, 90.0}};
  if (!std::isfinite(k.timeS)) return fmt::format("time_s {} is not a finite number", k.timeS);
  // Bounded so that the duration and the frame times computed from it stay finite.
  if (std::abs(k.timeS) > kPathMaxTimeS)
    return fmt::format("time_s {} is outside [{}, {}]", k.timeS, -kPathMaxTimeS, kPathMaxTimeS);
  for (const Field& f : fields) {
    if (!std::isfinite(f.value)) return fmt::format("{} {} is not a finite number", f.name, f.value);
    if (f.value < f.min || f.value > f.max)
      return fmt::format("{} {} is outside [{}, {}]", f.name, f.value, f.min, f.max);
  }
  return "";
}

// The first rule that `key` breaks relative to the key before it, or "".
std::string keyPairError(const CameraKey& previous, const CameraKey& key) {
  if (!(key.timeS > previous.timeS))
    return fmt::format("time_s {} is not after the previous key's {} (times must increase)", key.timeS, previous.timeS);
  if (keyAngleDeg(previous, key) > kMaxKeyAngleDeg)
    return fmt::format(
        "position {},{} is (nearly) antipodal to the previous key's {},{}: the great circle between "
        "them is undefined (add a key in between)",
        key.latitudeDeg, key.longitudeDeg, previous.latitudeDeg, previous.longitudeDeg);
  return "";
}

std::string tooFewKeys(std::string_view sourceName, size_t count) {
  return fmt::format("{}: a camera path needs at least 2 keys, got {}", sourceName, count);
}

// Shortest signed difference b - a of two angles in degrees, in (-180, 180].
double angleDifferenceDeg(double a, double b) {
  double d = std::fmod(b - a, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

}  // namespace

void validateCameraPath(const CameraPath& path, std::string_view sourceName) {
  if (path.keys.size() < 2) throw Error(tooFewKeys(sourceName, path.keys.size()));
  for (size_t i = 0; i < path.keys.size(); ++i) {
    std::string error = keyRangeError(path.keys[i]);
    if (error.empty() && i > 0) error = keyPairError(path.keys[i - 1], path.keys[i]);
    if (!error.empty()) throw Error(fmt::format("{}: key {}: {}", sourceName, i + 1, error));
  }
}

CameraPath parseCameraPath(std::string_view text, std::string_view sourceName) {
  CameraPath path;
  // Editors on Windows may start a UTF-8 file with a byte order mark: not part of the first key.
  size_t lineStart = text.starts_with(kUtf8ByteOrderMark) ? kUtf8ByteOrderMark.size() : 0;
  for (size_t lineNumber = 1; lineStart < text.size(); ++lineNumber) {
    size_t lineEnd = text.find('\n', lineStart);
    if (lineEnd == std::string_view::npos) lineEnd = text.size();
    std::string_view line = text.substr(lineStart, lineEnd - lineStart);
    lineStart = lineEnd + 1;
    line = line.substr(0, line.find('#'));
    auto fail = [&](const std::string& what) { throw Error(fmt::format("{}:{}: {}", sourceName, lineNumber, what)); };
    double values[6];
    size_t count = 0;
    size_t pos = 0;
    while (true) {
      pos = line.find_first_not_of(" \t\r", pos);
      if (pos == std::string_view::npos) break;
      const size_t end = std::min(line.find_first_of(" \t\r", pos), line.size());
      const std::string_view field = line.substr(pos, end - pos);
      pos = end;
      if (count >= 6) {
        ++count;
        continue;  // extra fields are only counted, for the message below
      }
      // A leading '+' is a number too (std::from_chars does not take one).
      const std::string_view digits = field.size() > 1 && field[0] == '+' ? field.substr(1) : field;
      double value = 0.0;
      auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
      if (ec == std::errc::result_out_of_range) fail(fmt::format("'{}' is out of range for a double", quotable(field)));
      if (ec != std::errc() || ptr != digits.data() + digits.size())
        fail(fmt::format("'{}' is not a number (expected {})", quotable(field), kColumns));
      values[count++] = value;
    }
    if (count == 0) continue;
    if (count != 6) fail(fmt::format("expected 6 numbers ({}), got {}", kColumns, count));
    const CameraKey key{values[0], values[1], values[2], values[3], values[4], values[5]};
    std::string error = keyRangeError(key);
    if (error.empty() && !path.keys.empty()) error = keyPairError(path.keys.back(), key);
    if (!error.empty()) fail(error);
    path.keys.push_back(key);
  }
  if (path.keys.size() < 2) throw Error(tooFewKeys(sourceName, path.keys.size()));
  return path;
}

CameraPath loadCameraPath(const std::string& file) {
  const std::string text = readFileUpTo(file, kMaxPathBytes);
  if (text.size() > kMaxPathBytes) throw Error(fmt::format("{}: larger than {} bytes", file, kMaxPathBytes));
  return parseCameraPath(text, file);
}

std::string formatCameraPath(const CameraPath& path) {
  std::string out = fmt::format("# {}\n", kColumns);
  for (const CameraKey& k : path.keys)
    out +=
        fmt::format("{} {} {} {} {} {}\n", k.timeS, k.latitudeDeg, k.longitudeDeg, k.heightM, k.headingDeg, k.pitchDeg);
  return out;
}

CameraKey sampleCameraPath(const CameraPath& path, double timeS) {
  const std::vector<CameraKey>& keys = path.keys;
  if (!(timeS > keys.front().timeS)) return keys.front();
  if (timeS >= keys.back().timeS) return keys.back();
  // The segment [k, k + 1] that holds timeS.
  const size_t k = size_t(std::upper_bound(keys.begin(), keys.end(), timeS,
                                           [](double t, const CameraKey& key) { return t < key.timeS; }) -
                          keys.begin()) -
                   1;
  const CameraKey& a = keys[k];
  const CameraKey& b = keys[k + 1];
  const double u = (timeS - a.timeS) / (b.timeS - a.timeS);
  CameraKey key;
  key.timeS = timeS;
  key.heightM = a.heightM * std::pow(b.heightM / a.heightM, u);
  key.headingDeg = a.headingDeg + u * angleDifferenceDeg(a.headingDeg, b.headingDeg);
  key.pitchDeg = a.pitchDeg + u * (b.pitchDeg - a.pitchDeg);
  const glm::dvec3 p = directionFromLatLon(a.latitudeDeg, a.longitudeDeg);
  const glm::dvec3 q = directionFromLatLon(b.latitudeDeg, b.longitudeDeg);
  const double omega = std::atan2(glm::length(glm::cross(p, q)), glm::dot(p, q));
  if (omega < 1e-15) {  // the same point (a vertical segment): keep the key's exact coordinates
    key.latitudeDeg = a.latitudeDeg;
    key.longitudeDeg = a.longitudeDeg;
    return key;
  }
  const glm::dvec3 d = (std::sin((1.0 - u) * omega) * p + std::sin(u * omega) * q) / std::sin(omega);
  key.latitudeDeg = std::atan2(d.z, std::hypot(d.x, d.y)) / kDegree;
  key.longitudeDeg = std::atan2(d.y, d.x) / kDegree;
  return key;
}

double frameTimeS(const CameraPath& path, uint32_t frame, uint32_t frameCount) {
  if (frameCount < 2) return path.startS();
  return path.startS() + path.durationS() * double(frame) / double(frameCount - 1);
}

CameraPose cameraPoseAt(const CameraKey& key, const PlanetDescription& planet) {
  const double surface = surfaceHeightM(planet, directionFromLatLon(key.latitudeDeg, key.longitudeDeg));
  return CameraPose{key.latitudeDeg, key.longitudeDeg, surface + key.heightM, key.headingDeg, key.pitchDeg};
}

CameraPath defaultCameraPath(double radiusM) {
  constexpr double kLat = 33.8, kLon = -90.0;  // land at ~1,700 m on the earth preset (tools/gallery.sh)
  constexpr double kBearing = 60.0;            // the traverse heads toward rising ground
  constexpr double kSpeed = 300.0;             // m/s
  const glm::dvec3 start = directionFromLatLon(kLat, kLon);
  auto along = [&](double timeS, double distanceM, double heightM) {
    const glm::dvec3 d = travelGreatCircle(start, kBearing, distanceM, radiusM);
    return CameraKey{
        timeS, std::atan2(d.z, std::hypot(d.x, d.y)) / kDegree, std::atan2(d.y, d.x) / kDegree, heightM, kBearing,
        -8.0};
  };
  CameraPath path;
  path.keys = {
      {0.0, kLat, kLon, 4.0e7, 0.0, -90.0},  // 2 decades of height in 8 s, then about 4 s per decade
      {8.0, kLat, kLon, 4.0e5, 0.0, -90.0},    {14.0, kLat, kLon, 1.0e4, 0.0, -45.0},
      {18.0, kLat, kLon, 1.0e3, 20.0, -25.0},  {22.0, kLat, kLon, 100.0, 40.0, -15.0},
      {29.0, kLat, kLon, 2.0, kBearing, -8.0}, along(33.0, 4.0 * kSpeed, 50.0),  // climbing to 50 m while it speeds off
      along(63.0, 34.0 * kSpeed, 50.0),
  };
  validateCameraPath(path, "default camera path");
  return path;
}

}  // namespace planet
