#include "planet/orbit.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Column-major rotations by `angle` about +x and +z (glm's layout: m[column][row]).
glm::dmat3 rotationX(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return glm::dmat3(1.0, 0.0, 0.0, 0.0, c, s, 0.0, -s, c);
}
glm::dmat3 rotationZ(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return glm::dmat3(c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0);
}

}  // namespace

void validateOrbit(const OrbitElements& o) {
  const double values[] = {o.semiMajorAxisM,   o.eccentricity,          o.inclinationRad, o.ascendingNodeRad,
                           o.periapsisArgumentRad, o.meanAnomalyAtEpochRad, o.periodS};
  for (double value : values)
    if (!std::isfinite(value)) throw Error(fmt::format("orbit element is not finite: {}", value));
  if (!(o.semiMajorAxisM > 0.0))
    throw Error(fmt::format("orbit semi-major axis must be > 0 m, got {}", o.semiMajorAxisM));
  if (!(o.eccentricity >= 0.0 && o.eccentricity < 1.0))
    throw Error(fmt::format("orbit eccentricity must be in [0, 1), got {}", o.eccentricity));
  if (!(o.periodS > 0.0)) throw Error(fmt::format("orbit period must be > 0 s, got {}", o.periodS));
}

double orbitalPeriodS(double semiMajorAxisM, double gmM3S2) {
  if (!(semiMajorAxisM > 0.0) || !(gmM3S2 > 0.0) || !std::isfinite(semiMajorAxisM) || !std::isfinite(gmM3S2))
    throw Error(fmt::format("orbital period needs a > 0 and GM > 0, got a = {} m, GM = {} m^3/s^2", semiMajorAxisM,
                            gmM3S2));
  return kTwoPi * std::sqrt(semiMajorAxisM * semiMajorAxisM * semiMajorAxisM / gmM3S2);
}

double solveKepler(double meanAnomalyRad, double e) {
  if (!std::isfinite(meanAnomalyRad)) throw Error(fmt::format("mean anomaly is not finite: {}", meanAnomalyRad));
  if (!(e >= 0.0 && e < 1.0)) throw Error(fmt::format("eccentricity must be in [0, 1), got {}", e));
  // Solve in the turn (−π, π] and add the turns back, so that large times keep their accuracy
  // relative to the angle within the orbit.
  const double turns = std::round(meanAnomalyRad / kTwoPi);
  const double m = meanAnomalyRad - turns * kTwoPi;
  // Start at π for very eccentric orbits (where M + e sin M can overshoot), else at M + e sin M.
  double E = e > 0.8 ? (m < 0.0 ? -std::numbers::pi : std::numbers::pi) : m + e * std::sin(m);
  for (int i = 0; i < 60; ++i) {
    const double f = E - e * std::sin(E) - m;
    const double step = f / (1.0 - e * std::cos(E));  // f' = 1 − e cos E >= 1 − e > 0
    E -= step;
    if (std::abs(step) <= 1e-15 * std::max(1.0, std::abs(E))) break;
  }
  return E + turns * kTwoPi;
}

glm::dvec3 orbitPosition(const OrbitElements& o, double timeS) {
  const double meanAnomaly = o.meanAnomalyAtEpochRad + kTwoPi * (timeS / o.periodS);
  const double E = solveKepler(meanAnomaly, o.eccentricity);
  const double e = o.eccentricity;
  const glm::dvec3 inPlane(o.semiMajorAxisM * (std::cos(E) - e), o.semiMajorAxisM * std::sqrt(1.0 - e * e) * std::sin(E),
                           0.0);
  return rotationZ(o.ascendingNodeRad) * (rotationX(o.inclinationRad) * (rotationZ(o.periapsisArgumentRad) * inPlane));
}

glm::dmat3 bodyToScene(const SpinElements& spin, double timeS) {
  // The turn is taken modulo one period first, so that a time of years keeps the angle exact.
  const double angle = spin.periodS > 0.0 ? spin.phaseRad + kTwoPi * (std::fmod(timeS, spin.periodS) / spin.periodS)
                                          : spin.phaseRad;
  return rotationX(spin.tiltRad) * rotationZ(angle);
}

}  // namespace planet
