#pragma once
// Quadrature rules and sphere-path helpers shared by the scattering bakers.
#include <vector>

#include <glm/vec3.hpp>

namespace cloudlut::bake {

// n-point Gauss–Legendre rule on [0, 1]: nodes x[i] ascending, weights w[i] summing to 1.
struct GaussRule {
  std::vector<double> x, w;
};
const GaussRule& gaussLegendre(int n);  // cached; n in [1, 64]

// Distance from x (|x| ≤ 1) along the unit direction d to the unit sphere (≥ 0).
double distanceToSphere(const glm::dvec3& x, const glm::dvec3& d);

// Path length of sunlight inside the sphere before reaching x: distance from x along +l to the
// sphere surface.
inline double sunPath(const glm::dvec3& x, const glm::dvec3& l) { return distanceToSphere(x, l); }

// ∫_0^length σ e^{-σt} e^{-σ d_sun(x + t d)} dt: sunlight scattered once (phase excluded) and
// gathered along the ray x + t d, i.e. the radiance arriving at x from the direction d points
// to. The log-integrand is convex (d_sun is concave along a line), so the mass sits at the
// ends: composite 8-point Gauss–Legendre panels graded geometrically toward both ends.
double sunlitRayIntegral(const glm::dvec3& x, const glm::dvec3& d, const glm::dvec3& l,
                         double sigma, double length);

// The same integral by a cheap fixed rule in u = 1 − e^{−σt}, U = 1 − e^{−σ·length}: 8-point
// Gauss–Legendre panels [0, U/4] and [U/4, U], or the single panel [0, U] when σ·length ≤ 1;
// accurate to ~1e-3 relative, used where many rays are needed.
double sunlitRayIntegralFast(const glm::dvec3& x, const glm::dvec3& d, const glm::dvec3& l,
                             double sigma, double length);

// Quadrature along a ray of the fast multiple-scattering method: ∫_0^d σe^{−σs} f(s) ds ≈ Σ w f(s).
// Near part (the first six mean free paths, where the attenuation dominates) in u = 1 − e^{−σs}
// on the panels
// [0, U₁/8] and [U₁/8, U₁], U₁ = 1 − e^{−min(σd, 6)}; far part (s > 6/σ) in s itself, where
// the source may grow as fast as the light decays (light crossing the particle toward its dark
// side) and u would crowd it into a singular corner. pts = points per panel. Dense particles
// (σ ≥ 20) use u over the whole ray: panels [0, U/16], [U/16, U/4], [U/4, U]. The far weights
// carry exactly the far mass e^{−6} − e^{−σd}, so the discrete transport conserves energy.
// Fills s (distances from the ray's start, ascending within each panel) and w; `total` points
// at least (every panel gets two or more).
void attenuatedRayRule(double sigma, double length, int total, std::vector<double>& s, std::vector<double>& w);
// Optical radius from which attenuatedRayRule drops the far panel (all points in u).
inline constexpr double kFarPanelMaxSigma = 20.0;

}  // namespace cloudlut::bake
