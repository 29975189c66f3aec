// Per-frame placement of the spherical-clipmap hemisphere (Clasen & Hege 2006, "Terrain rendering
// using spherical clipmaps"; Hayes-McCoy 2010, §2.4 and §4.5): the rotation that turns the mesh's
// pole toward the camera's nadir, and the range of rings worth drawing (horizon cut outside, pixel
// cut inside). Everything here runs on the CPU in double precision.
//
// Frames. The planet frame is centred on the planet (camera positions are relative to its
// centre). The mesh's local frame is the one of clipmap_mesh.h: pole (θ = 0) on local +z, θ the
// angle from the pole, φ the azimuth from local +x toward local +y, so a local direction is
// (cos φ sin θ, sin φ sin θ, cos θ). ClipmapFrame::localToPlanet maps local to planet directions:
// its columns are the local x, y and z axes in the planet frame, column 2 is the unit vector from
// the planet centre to the camera, and φ = 0 points along column 0.
//
// Rings. Ring k = 0..K−1 (K = levels·m) sits at θ_k = (π/2)·2^(−k/m), computed exactly like
// clipmapRingTheta (so both agree bit for bit); k = 0 is the rim, and "ring K" names the pole
// (θ = 0). Band b is the strip of quads between rings b and b+1; band K−1 is the mesh's pole fan.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace planet {

// Altitude floor of the cuts: a camera at or below sea level (a valley below sea level, on the
// water) is treated as 1 m up, so the horizon and pixel cuts never collapse to zero.
inline constexpr double kClipmapMinAltitudeM = 1.0;
// Lower clamp of horizonTheta, so the drawn region is never a point even on absurd radii.
inline constexpr double kClipmapMinHorizonTheta = 1e-9;
// Bounds accepted by the ring functions; wider than the mesh's own (40 levels, 256 rings per
// level) so that every mesh clipmap_mesh accepts also works here.
inline constexpr uint32_t kClipmapOrientationMaxLevels = 64;
inline constexpr uint32_t kClipmapOrientationMaxRingsPerLevel = 4096;

// Where the hemisphere points this frame.
struct ClipmapFrame {
  // Orthonormal, det = +1. Columns: local x, local y, local z (= unit vector centre → camera).
  glm::dmat3 localToPlanet{1.0};
  glm::dvec3 cameraPlanetFrame{0.0, 0.0, 1.0};  // camera position relative to the planet centre, metres
  double radiusM = 1.0;                         // sea-level radius r the frame was built for
  double cameraDistanceM = 1.0;                 // |cameraPlanetFrame| = r + h
  double altitudeM = 0.0;                       // h = distance − r above sea level; negative below it

  glm::dvec3 nadirDirection() const { return localToPlanet[2]; }  // planet centre → camera, unit
};

// Builds this frame's basis from the camera position alone, so that the same pose draws the
// same picture however the camera got there (issue 20, point 8). Column 2 is
// normalize(cameraPositionPlanetFrame); the tangent axes (the mesh's spin about its pole) are
// free, and their choice shows in the picture only through where the vertices sample the
// terrain (at quality low, with no patch textures, through the vertex normals too).
//
// Choice: local x points north, along the planet's axis (+z) projected into the tangent plane,
// (−n_z n_x, −n_z n_y, n_x² + n_y²)/|…| for pole n (1 − n_z² written as n_x² + n_y², so it stays
// exact near a world pole); local y = n × x points west. Everywhere but at the two world poles
// this is smooth: a camera step of angle α away from them turns the axes by about α/sin(colatitude).
// Why not a switch between two reference axes (or the old parallel transport):
// - No tangent field on the sphere is continuous everywhere (hairy ball theorem), and the mesh's
//   N-fold symmetry only weakens that to "continuous modulo 2π/N" (the field's singularities,
//   of index a multiple of 1/N, still add up to 2). Any blend or switch between axes therefore
//   just moves the singular points; a switch at a curve would add a seam where the spin jumps
//   by a non-symmetry angle, visible along the whole curve.
// - With north as reference the only singular points are the poles, and there a straight pass
//   turns the frame by exactly π, which for even N (every quality preset) is a symmetry of the
//   mesh (vertex i goes to i + N/2, triangles onto triangles): nothing pops. Only a camera whose
//   nadir passes within a few steps of the exact pole sees the spin turn fast for a few frames
//   (by at most π/N, half a vertex spacing, modulo the symmetry), like an odd N at any pass.
// - Parallel transport was smooth everywhere but path dependent: after a loop the mesh came
//   back turned by the enclosed solid angle, and the picture differed from a fresh render.
// At a world pole itself (n_x = n_y = 0) local x is world +x, the limit of approaching along
// longitude 180° (and, modulo the even-N symmetry, 0°). Same inputs (bit for bit) give the same
// basis bit for bit. Throws planet::Error for a radius that is not finite and > 0, and for a
// camera position that is not finite or is the planet centre.
ClipmapFrame orientClipmap(const glm::dvec3& cameraPositionPlanetFrame, double radiusM);

// The planet-frame unit direction of local (θ, φ): localToPlanet · (cos φ sin θ, sin φ sin θ, cos θ).
glm::dvec3 localToPlanetDirection(const ClipmapFrame& frame, double theta, double phi);
// The inverse: local (θ ∈ [0, π], φ ∈ [0, 2π)) of a planet-frame direction, which need not be
// unit length. θ uses atan2, so it stays accurate near the pole; at the pole φ = 0. A zero vector
// gives (0, 0).
glm::dvec2 planetToLocalThetaPhi(const ClipmapFrame& frame, const glm::dvec3& direction);

// Horizon cut (Clasen & Hege 2006, via Hayes-McCoy 2010 §2.4: θmax = acos(r/(r+h))), with the
// "buffer zone" the smooth-sphere formula needs: the largest angle at the planet centre, from the
// nadir, at which terrain up to maxTerrainHeightM could still be seen. The sight line grazing the
// sea-level sphere reaches height H at a further acos(r/(r+H)), so
//   θmax = acos(r/(r+h)) + acos(r/(r+H)),
// each term evaluated as atan2(√(x(2r+x)), r) (no cancellation for x ≪ r). h below
// kClipmapMinAltitudeM counts as that floor; a negative H counts as 0. lowestSurfaceM L < 0 (the
// deepest terrain of a planet without a sea, whose basins go below the radius sphere) lowers the
// grazed sphere to r + L, and both terms become acos((r+L)/(r+h)) + acos((r+L)/(r+H)): from a
// rim above a basin the ground beyond the radius sphere's horizon stays drawn (without it, rays
// below that horizon found no mesh, and a black wedge showed at mars's horizon). L > 0 counts
// as 0 (a sea at L = 0 hides what lies below it). Clamped to [kClipmapMinHorizonTheta, π/2]: the
// mesh ends at the rim, so from beyond ~19 r an Everest-sized peak just past the limb is cut.
// Throws planet::Error for a radius (or r + L) that is not finite and > 0, and for NaN h, H or L.
double horizonTheta(double radiusM, double altitudeM, double maxTerrainHeightM, double lowestSurfaceM = 0.0);

// θdiffmin = s/r (Clasen & Hege 2006, via Hayes-McCoy 2010 §2.4): the angle at the planet centre
// spanned by one pixel at the nadir, with s = h·tan(fovY/2)/(viewportHeightPx/2) the ground size of
// a pixel at the centre of the view (flat-ground approximation, exact as the angle → 0; pixels off
// the optical axis subtend up to cos²(fovY/2) less, so this is "about one pixel"). h is floored at
// kClipmapMinAltitudeM. Not clamped. Throws planet::Error for a radius that is not finite and > 0,
// NaN h, fovY outside (0, π) or viewportHeightPx = 0.
double pixelFootprintTheta(double radiusM, double altitudeM, double fovYRad, uint32_t viewportHeightPx);

// Fine cut: the smallest θ at which the spacing to the next ring inward, θ·(1 − 2^(−1/m)), is still
// at least one pixel: pixelFootprintTheta / (1 − 2^(−1/m)), clamped to [0, π/2]. Rings inside it are
// closer than a pixel at the nadir (and further out pixels only get larger on the ground), so they
// need not be drawn. Throws as pixelFootprintTheta, and for ringsPerLevel outside
// 1..kClipmapOrientationMaxRingsPerLevel.
double minUsefulTheta(double radiusM, double altitudeM, double fovYRad, uint32_t viewportHeightPx,
                      uint32_t ringsPerLevel);

// The rings to draw this frame. Drawn are the quad bands firstRing..lastRing−1 (between ring
// firstRing and ring lastRing, covering θ ∈ [θ_lastRing, θ_firstRing]) and, when includePole, a
// fan closing ring lastRing at the pole (covering θ ∈ [0, θ_lastRing]). Invariants:
// 0 ≤ firstRing ≤ lastRing ≤ K−1, θ_firstRing ≥ thetaMax (clamped to π/2), and θ_lastRing ≤
// thetaMin unless lastRing = K−1 (the mesh has no finer ring). Both ends are tight: ring
// firstRing+1 is inside thetaMax, and ring lastRing−1 (if > firstRing) outside thetaMin.
// includePole is always true: the ground under the camera must never be a hole, so inside the
// fine cut the sub-pixel rings are replaced by one fan, never left open. With lastRing = K−1 that
// fan is the mesh's own (clipmapRingBandRange(params, firstRing, K)); with a smaller lastRing the
// renderer needs a fan for ring lastRing (a small extra index range per ring, or rings > lastRing
// collapsed onto the pole in the vertex shader). The fan has no interior vertex: its radius
// r·θ_lastRing is about m/ln 2 ring spacings (see poleCapRadiusM).
struct RingRange {
  uint32_t firstRing = 0;   // outermost drawn ring: the innermost ring with θ ≥ thetaMax
  uint32_t lastRing = 0;    // innermost drawn ring: the outermost ring with θ ≤ thetaMin (else K−1)
  bool includePole = true;  // close ring lastRing with a fan to the pole (always, see above)
};

// thetaMax is clamped to [0, π/2] and thetaMin to [0, thetaMax] (a fine cut at or beyond the
// horizon leaves at most the one band around thetaMax, plus the fan). Throws planet::Error for NaN
// angles, levels outside 1..kClipmapOrientationMaxLevels and ringsPerLevel outside
// 1..kClipmapOrientationMaxRingsPerLevel.
RingRange selectRings(uint32_t levels, uint32_t ringsPerLevel, double thetaMax, double thetaMin);

// Ground spacing of the innermost drawn ring pair, ring lastRing−1 (outer) and ring lastRing, in
// metres on the sea-level sphere: the larger of its radial edge r·(θ_lastRing−1 − θ_lastRing) and
// its longer azimuthal edge r·sin θ_lastRing−1·2π/N. lastRing = 0 has no outer ring and reports
// ring 0 against the pole instead. The benchmark's "metres per vertex" (Hayes-McCoy's "0.2 metres
// per vertex"). Throws planet::Error for a bad radius, levels or ringsPerLevel, numPhi < 3, or
// lastRing ≥ K.
double metresPerVertexAtNadir(double radiusM, uint32_t levels, uint32_t ringsPerLevel, uint32_t numPhi,
                              uint32_t lastRing);

// Radius r·θ_lastRing of the fan that closes ring lastRing at the pole: right under the camera the
// vertex spacing is this, not metresPerVertexAtNadir. Throws as metresPerVertexAtNadir.
double poleCapRadiusM(double radiusM, uint32_t levels, uint32_t ringsPerLevel, uint32_t lastRing);

}  // namespace planet
