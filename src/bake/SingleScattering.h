#pragma once
// Single scattering L1 of the homogeneous unit sphere, without the phase function
// (seed eq. 9 for constant density), stored as log2 of its mean source (cloudlut_shading.glsl):
//   L1(S, v) = ∫_0^{chord} σ e^{−σt} e^{−σ d_sun(S + t v)} dt,
// d_sun(P) the distance from P along +l to the sphere surface (closed form). Evaluated per
// table node by composite Gauss–Legendre quadrature graded toward both ends of the chord,
// where the log-convex integrand keeps its mass (Quadrature.h).
#include <glm/vec3.hpp>

#include "core/Table4D.h"

namespace cloudlut::bake {

// L1 for the chord entering the unit sphere at S along v (v·S < 0; 0 otherwise), sun toward l.
double singleScatteringL1(const glm::dvec3& S, const glm::dvec3& v, const glm::dvec3& l, double sigma);

// L1 / (1 − e^{−σ·chord}): the e^{−σt}-weighted mean sun transmittance along the chord, in [0, 1];
// on a grazing chord (length → 0) its limit, the sun transmittance at S.
double singleScatteringMeanSource(const glm::dvec3& S, const glm::dvec3& v, const glm::dvec3& l, double sigma);

// The table node geometry in the light frame (l = +z, S in the xz plane), exactly the
// convention of scatteringAngles() in cloudlut_geometry.glsl.
struct ScatteringNode {
  glm::dvec3 S, v, l;
};
ScatteringNode scatteringNode(double thetaS, double phiV, double thetaV);

// Fills density slice `slice` (σ = optical radius) of the single-scattering table with
// singleScatteringToTable(singleScatteringMeanSource) (cloudlut_shading.glsl).
void bakeSingleScatteringSlice(double sigma, int slice, Table4D& table);

}  // namespace cloudlut::bake
