// Keplerian orbits and body spin (issue 8, point 2): where each body of a scene is at a time,
// in closed form, in double precision. The scene frame is inertial: the sun at its origin, the
// reference plane z = 0 (orbital inclinations are measured from it), +x the reference direction.
//
// An orbit around a parent at the parent's position (the sun for bodies without one):
//   M(t) = M0 + 2π t / T                      mean anomaly
//   E − e sin E = M                           Kepler's equation, solved by Newton's method
//   (x, y) = a (cos E − e, √(1 − e²) sin E)   in the orbit's plane, periapsis along +x
//   r = Rz(Ω) Rx(i) Rz(ω) (x, y, 0)           into the scene frame
// A body's frame (the planet frame of terrain_height.h, +z its north pole) is turned from the
// scene frame by its axial tilt about +x and its spin about its own pole:
//   bodyToScene = Rx(tilt) Rz(phase + 2π t / P)
#pragma once

#include <glm/glm.hpp>

namespace planet {

struct OrbitElements {
  double semiMajorAxisM = 0.0;         // a, > 0
  double eccentricity = 0.0;           // e in [0, 1): ellipses only
  double inclinationRad = 0.0;         // i, from the reference plane
  double ascendingNodeRad = 0.0;       // Ω, longitude of the ascending node
  double periapsisArgumentRad = 0.0;   // ω, argument of periapsis
  double meanAnomalyAtEpochRad = 0.0;  // M0, at t = 0
  double periodS = 0.0;                // T, > 0
};

// Throws planet::Error naming the first bad element (non-finite, a <= 0, e outside [0, 1), T <= 0).
void validateOrbit(const OrbitElements& orbit);

// The orbital period around a parent of gravitational parameter gm (m³/s²): 2π √(a³ / GM).
double orbitalPeriodS(double semiMajorAxisM, double gmM3S2);

// E for a mean anomaly M (any real; the result is in the same turn as M) and e in [0, 1):
// |E − e sin E − M| <= 1e-12 · max(1, |M|).
double solveKepler(double meanAnomalyRad, double eccentricity);

// Position relative to the parent at time t (s), scene frame, metres.
glm::dvec3 orbitPosition(const OrbitElements& orbit, double timeS);

struct SpinElements {
  double periodS = 0.0;  // sidereal rotation period; 0: the body does not turn
  double tiltRad = 0.0;  // axial tilt: the pole leans from +z toward −y by this angle
  double phaseRad = 0.0; // rotation angle at t = 0
};

// Rotation taking body-frame vectors into the scene frame at time t.
glm::dmat3 bodyToScene(const SpinElements& spin, double timeS);

}  // namespace planet
