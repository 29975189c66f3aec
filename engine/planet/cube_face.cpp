#include "planet/cube_face.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {
namespace {

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

CubeFace cubeFace(int face) {
  // Each (A, B) pair is a right-handed basis of the face plane: A × B = N.
  switch (face) {
    case 0: return {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
    case 1: return {{0, -1, 0}, {0, 0, 1}, {-1, 0, 0}};
    case 2: return {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
    case 3: return {{0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
    case 4: return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case 5: return {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
    default: throw Error(fmt::format("cube face must be in 0..{}, got {}", kCubeFaceCount - 1, face));
  }
}

int dominantCubeFace(const glm::dvec3& direction) {
  if (!isFinite(direction) || direction == glm::dvec3(0.0))
    throw Error(
        fmt::format("cube face of a zero or non-finite direction ({}, {}, {})", direction.x, direction.y, direction.z));
  // Face 2k has normal +axis k and face 2k+1 has −axis k; a strict > keeps the lower index on ties.
  int best = 0;
  double bestDot = direction.x;
  for (int face = 1; face < kCubeFaceCount; ++face) {
    const double component = direction[face / 2];
    const double dot = (face % 2 == 0) ? component : -component;
    if (dot > bestDot) {
      best = face;
      bestDot = dot;
    }
  }
  return best;
}

glm::dvec3 cubeFaceDirection(int face, double a, double b) {
  const CubeFace f = cubeFace(face);
  return glm::normalize(f.normal + a * f.axisA + b * f.axisB);
}

glm::dvec2 cubeFaceCoordinates(int face, const glm::dvec3& direction) {
  const CubeFace f = cubeFace(face);
  const double n = glm::dot(direction, f.normal);
  if (!(n > 0.0))
    throw Error(fmt::format("direction ({}, {}, {}) is not on the hemisphere of cube face {}", direction.x, direction.y,
                            direction.z, face));
  return {glm::dot(direction, f.axisA) / n, glm::dot(direction, f.axisB) / n};
}

}  // namespace planet
