// Camera paths (issue 6): keyframes that `planet bench` (and the viewer's --path) flies
// through, sampled by frame index, never by wall time, so that a run is deterministic.
//
// File format: plain text, one keyframe per line, six numbers separated by spaces or tabs:
//
//     # time_s  lat_deg  lon_deg  height_m  heading_deg  pitch_deg
//     0         33.8     -90      4e7       0            -90
//     29        33.8     -90      2         60           -8
//
// '#' starts a comment that runs to the end of the line; blank lines are skipped; CRLF line
// ends and a leading UTF-8 byte order mark are accepted. time_s: seconds in [-1e9, 1e9],
// strictly increasing from key to key. lat_deg in [-90, 90], lon_deg and heading_deg
// in [-360, 360] (heading clockwise from north), pitch_deg in [-90, 90] (above the horizon,
// -90 looks straight down). height_m: metres above the surface below the camera (the ground,
// or the sea where it is higher), in [0.01, 1e10]; measuring from the surface lets a path fly
// low over mountains and makes the geometric interpolation below meaningful at every scale.
// At least 2 keys; two consecutive keys may not be (nearly) antipodal, where the great circle
// between them is undefined. Every error is one line naming the file, the line and the value.
//
// Interpolation between keys k and k+1 at u = (t - t_k) / (t_k+1 - t_k):
//   - height geometric (log-linear): h_k · (h_k+1 / h_k)^u, so a descent from 40,000 km to 2 m
//     spends equal time on every factor of ten;
//   - position along the shorter great circle at a constant angular rate (slerp of the two
//     unit vectors; the ground speed is constant within a segment);
//   - heading linear the shorter way round (350° to 10° passes through 0°), pitch linear.
// Times before the first key give the first key, after the last the last.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "planet/planet_description.h"
#include "camera/camera.h"

namespace planet {

inline constexpr double kPathMinHeightM = 0.01;
inline constexpr double kPathMaxHeightM = 1e10;
inline constexpr double kPathMaxTimeS = 1e9;  // |time_s|: some 30 years, and a finite duration

struct CameraKey {
  double timeS = 0.0;
  double latitudeDeg = 0.0;
  double longitudeDeg = 0.0;
  double heightM = 1.0;  // above the surface (ground, or sea where higher)
  double headingDeg = 0.0;
  double pitchDeg = -90.0;
};

struct CameraPath {
  std::vector<CameraKey> keys;  // at least 2, times strictly increasing
  double startS() const { return keys.front().timeS; }
  double endS() const { return keys.back().timeS; }
  double durationS() const { return endS() - startS(); }
};

// Checks the rules above; `sourceName` starts every message ("path.txt: key 3: ...").
void validateCameraPath(const CameraPath& path, std::string_view sourceName);
// Parses the file format; messages start "sourceName:LINE: ".
CameraPath parseCameraPath(std::string_view text, std::string_view sourceName);
// Reads and parses a file (at most 4 MiB); messages start with `file`.
CameraPath loadCameraPath(const std::string& file);
// The file format of `path`: a header comment and one line per key, numbers in shortest
// round-trip form (parseCameraPath gives back the same keys).
std::string formatCameraPath(const CameraPath& path);

// The interpolated key at `timeS` (its timeS field is timeS clamped to the path).
CameraKey sampleCameraPath(const CameraPath& path, double timeS);
// Frame `frame` of `frameCount` frames spread evenly over the path: the first at the first key,
// the last at the last (a single frame: the first key).
double frameTimeS(const CameraPath& path, uint32_t frame, uint32_t frameCount);
// The renderer's pose for a key: altitude above the sea-level sphere = heightM + the surface
// height at the key's point (CPU reference terrain with every octave, or the sea level where
// it is higher).
CameraPose cameraPoseAt(const CameraKey& key, const PlanetDescription& planet);

// The default benchmark path on a planet of radius radiusM (issue 6): over the land at 33.8° N,
// 90° W of the earth preset, a descent from 40,000 km through 400 km, 10 km, 1 km and 100 m to
// 2 m above the ground, tilting from straight down toward the horizon (29 s); then a climb to
// 50 m and a traverse at 300 m/s toward 60° (34 s, 10.2 km).
CameraPath defaultCameraPath(double radiusM);

}  // namespace planet
