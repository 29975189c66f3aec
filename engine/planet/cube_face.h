// The cube of six gnomonic faces that maps the sphere onto squares: planet geometry shared by
// the patch textures (render/patch_layout.h) and the cube-map heightmap export.
#pragma once

#include <glm/glm.hpp>

namespace planet {

inline constexpr int kCubeFaceCount = 6;

struct CubeFace {
  glm::dvec3 axisA;   // +a direction
  glm::dvec3 axisB;   // +b direction
  glm::dvec3 normal;  // the face centre, (a, b) = (0, 0)
};

// Faces 0..5 are +x, −x, +y, −y, +z, −z (normal); A, B are signed unit axes with A × B = N.
// Throws planet::Error for a face outside 0..5.
CubeFace cubeFace(int face);
// The face whose normal has the largest dot product with `direction` (ties: lower index).
// Throws planet::Error for a zero or non-finite direction.
int dominantCubeFace(const glm::dvec3& direction);
// normalize(N + a·A + b·B).
glm::dvec3 cubeFaceDirection(int face, double a, double b);
// (d·A / d·N, d·B / d·N); throws planet::Error when d·N <= 0 (not on the face's hemisphere).
glm::dvec2 cubeFaceCoordinates(int face, const glm::dvec3& direction);

}  // namespace planet
